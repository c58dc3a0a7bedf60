// Exceptions the library throws. Messages name the operation, the value and what is allowed.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace packbed {

/// A user-supplied value is outside what is allowed (the command line maps it to exit status 2).
class InvalidInput : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

/// An input file that could not be opened: the message as InvalidInput's, with the system's
/// error number and the path (Python raises the OSError of that number: FileNotFoundError,
/// PermissionError).
class UnopenableFile : public InvalidInput {
public:
    UnopenableFile(const std::string& message, int error, std::string path)
        : InvalidInput(message)
        , m_error(error)
        , m_path(std::move(path)) {}
    int error() const { return m_error; }
    const std::string& path() const { return m_path; }

private:
    int m_error;
    std::string m_path;
};

/// The iteration left the region where it converges (NaN, a sphere out of the container,
/// overlaps growing without bound) or did not finish within its iteration limit.
class ConvergenceError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The caller asked the run to stop (e.g. Ctrl-C); nothing was written.
class Cancelled : public std::runtime_error {
public:
    Cancelled()
        : std::runtime_error("cancelled") {}
};

} // namespace packbed
