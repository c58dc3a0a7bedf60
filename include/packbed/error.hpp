// Exceptions the library throws. Messages name the operation, the value and what is allowed.
#pragma once

#include <stdexcept>
#include <string>

namespace packbed {

/// A user-supplied value is outside what is allowed (the command line maps it to exit status 2).
class InvalidInput : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
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
