// What kind a failure is, in one place: the exit code `vots` ends with, the kind a rank's error travels
// as between ranks, and the errors the ranks' port throws (which the server answers 503 and 507).
#pragma once

#include <cstdint>
#include <exception>
#include <stdexcept>
#include <string>

namespace vots::dist {

/// Thrown when a rank's cells would need more memory than its --memory-budget leaves, before it reads
/// them: answered 507, as a study over the one-process budget is.
class RanksOverBudget : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Thrown when a rank no longer answers: the frame and every later one are refused (503).
class RanksLost : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The kinds of failure; their values travel between ranks.
enum class FailureKind : std::int32_t {
    Internal = 0,   // anything else, out of memory included
    BadInput = 1,   // fit::InputError, CLI11's parse errors
    OverBudget = 2, // RanksOverBudget
};

/// The exit codes of `vots`: 0 success, 1 a check failed (verify) or an internal error, 2 bad input.
inline constexpr int EXIT_FAILED = 1;
inline constexpr int EXIT_BAD_INPUT = 2;

/// The kind of a caught exception (`failure` not null).
FailureKind failureKindOf(const std::exception_ptr& failure);
/// Its one-line message: what(), "out of memory" for std::bad_alloc.
std::string failureTextOf(const std::exception_ptr& failure);
/// The exit code a failure of that kind ends `vots` with.
int exitCodeOf(FailureKind kind);
/// The exception another rank's failure is rethrown as: fit::InputError, RanksOverBudget or
/// std::runtime_error with `text`.
std::exception_ptr failureOf(FailureKind kind, const std::string& text);
/// The kind of a number that came from another rank; Internal for a value no kind has.
FailureKind failureKindFromWire(std::int32_t value);

} // namespace vots::dist
