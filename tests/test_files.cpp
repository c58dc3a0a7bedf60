// Paths and input files from users: escaped in messages, checked, opened without blocking,
// read within bounds.
#include <sys/stat.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "packbed/error.hpp"
#include "packbed/files.hpp"

using namespace packbed;
namespace fs = std::filesystem;

namespace {

fs::path scratch() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const fs::path d = fs::temp_directory_path() / "packbed-test-files" /
                       (std::string(info->test_suite_name()) + "." + info->name());
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

template <class F> std::string refusal(F&& f) {
    try {
        f();
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST(Printable, EscapesControlCharactersOnly) {
    EXPECT_EQ(printable("x\nsystem(\"touch PWNED\") #"), "x\\nsystem(\"touch PWNED\") #");
    EXPECT_EQ(printable(std::string("a\tb\rc\x1b[31m\x7f\0", 12)), "a\\tb\\rc\\x1b[31m\\x7f\\x00");
    EXPECT_EQ(printable("plain/path with spaces 'quoted' \xc3\xa9"),
              "plain/path with spaces 'quoted' \xc3\xa9"); // UTF-8 stays
    EXPECT_EQ(printable(printable("a\nb")), "a\\nb");
}

TEST(ShellWord, ASmallShellReadsBackTheWordItWasGiven) {
    EXPECT_EQ(shell_word("results/a5-n500_1.csv"), "results/a5-n500_1.csv");
    EXPECT_EQ(shell_word("job dir's"), "'job dir'\\''s'");
    EXPECT_EQ(shell_word(""), "''");
    // /bin/sh prints each back as it was: spaces, quotes, $, backquotes, ; and globs stay data.
    for (const std::string word :
         {"job dir's", "$(touch PWNED)", "a`b`c", "x;y|z&", "*.csv ?", "it's \"quoted\"", "-n"}) {
        const std::string command = "printf '%s' " + shell_word(word);
        FILE* shell = popen(command.c_str(), "r");
        ASSERT_NE(shell, nullptr);
        std::string back;
        for (int c; (c = std::fgetc(shell)) != EOF;)
            back += static_cast<char>(c);
        EXPECT_EQ(pclose(shell), 0) << command;
        EXPECT_EQ(back, word) << command;
    }
}

TEST(CheckPath, RefusesControlCharactersEmptyAndOverlong) {
    EXPECT_EQ(refusal([] { check_path("--out", "x\nsystem(\"touch PWNED\") #"); }),
              "--out 'x\\nsystem(\"touch PWNED\") #' is not allowed (a control character in the "
              "path); allowed: a path of at most 4095 bytes without control characters "
              "(newline, tab, ...)");
    EXPECT_NE(refusal([] { check_path("--out", ""); }).find("(an empty path)"), std::string::npos);
    EXPECT_NE(
        refusal([] { check_path("--out", std::string(5000, 'a')); }).find("(a path of 5000 bytes)"),
        std::string::npos);
    EXPECT_EQ(refusal([] { check_path("--out", "results/a5 n500/'x'\xc3\xa9"); }), "");
}

TEST(OpenRegularFile, RefusesDirectoriesFifosAndDevicesWithoutBlocking) {
    const fs::path d = scratch();
    ASSERT_EQ(::mkfifo((d / "fifo").c_str(), 0600), 0);
    // Before, opening the FIFO waited for a writer for ever.
    EXPECT_EQ(refusal([&] { open_regular_file("--bed", d / "fifo"); }),
              "--bed " + (d / "fifo").string() +
                  ": a FIFO (named pipe); allowed: a readable regular file");
    EXPECT_NE(refusal([&] { open_regular_file("", d); }).find(": a directory; allowed"),
              std::string::npos);
    EXPECT_NE(refusal([] { open_regular_file("", "/dev/zero"); }).find("a device"),
              std::string::npos);
    EXPECT_NE(refusal([&] {
                  open_regular_file("", d / "missing");
              }).find("cannot open the file (No such file or directory)"),
              std::string::npos);
    std::ofstream(d / "ok.txt") << "hello\n";
    std::ifstream in = open_regular_file("", d / "ok.txt");
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "hello");
}

TEST(ReadSmallFile, BoundedBySize) {
    const fs::path d = scratch();
    std::ofstream(d / "big.json") << std::string(1000, ' ');
    EXPECT_EQ(read_small_file("", d / "big.json", 1000).size(), 1000u);
    EXPECT_NE(refusal([&] {
                  read_small_file("--config", d / "big.json", 999);
              }).find("larger than 999 bytes"),
              std::string::npos);
}

TEST(ReadLine, BoundedByLength) {
    std::istringstream in("short\r\n" + std::string(100, 'x') + "\nlast");
    std::string line;
    EXPECT_EQ(read_line(in, line, 50), LineRead::line);
    EXPECT_EQ(line, "short\r"); // the reader strips the \r
    EXPECT_EQ(read_line(in, line, 50), LineRead::too_long);
    EXPECT_EQ(line.size(), 50u);
    std::istringstream tail("a\nlast");
    read_line(tail, line, 50);
    EXPECT_EQ(read_line(tail, line, 50), LineRead::line);
    EXPECT_EQ(line, "last"); // no newline at the end
    EXPECT_EQ(read_line(tail, line, 50), LineRead::end);
    // A stream of zeros without a newline stops at the limit instead of filling memory.
    std::istringstream zeros(std::string(1 << 20, '\0'));
    EXPECT_EQ(read_line(zeros, line, 4096), LineRead::too_long);
}
