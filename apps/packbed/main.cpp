// packbed: the command line. Everything is in app.cpp (packbed_cli_core), which tests and fuzz
// targets link too.
#include "app.hpp"

int main(int argc, char** argv) {
    return packbed::cli::run(argc, argv);
}
