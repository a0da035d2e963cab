// Failure kinds: from a caught exception, to an exit code, and back to an exception on another rank.
#include "vots/dist/Failure.h"

#include "vots/fit/Error.h"

#include <new>

namespace vots::dist {

FailureKind failureKindOf(const std::exception_ptr& failure) {
    try {
        std::rethrow_exception(failure);
    } catch (const fit::InputError&) {
        return FailureKind::BadInput;
    } catch (const RanksOverBudget&) {
        return FailureKind::OverBudget;
    } catch (...) {
        return FailureKind::Internal;
    }
}

std::string failureTextOf(const std::exception_ptr& failure) {
    try {
        std::rethrow_exception(failure);
    } catch (const std::bad_alloc&) {
        return "out of memory";
    } catch (const std::exception& e) {
        return e.what();
    } catch (...) {
        return "unknown error";
    }
}

int exitCodeOf(FailureKind kind) {
    // Over the budget is the input's size, as `vots fit` refuses a volume over its budget.
    return kind == FailureKind::Internal ? EXIT_FAILED : EXIT_BAD_INPUT;
}

std::exception_ptr failureOf(FailureKind kind, const std::string& text) {
    switch (kind) {
    case FailureKind::BadInput:
        return std::make_exception_ptr(fit::InputError(text));
    case FailureKind::OverBudget:
        return std::make_exception_ptr(RanksOverBudget(text));
    case FailureKind::Internal:
        break;
    }
    return std::make_exception_ptr(std::runtime_error(text));
}

FailureKind failureKindFromWire(std::int32_t value) {
    switch (static_cast<FailureKind>(value)) {
    case FailureKind::BadInput:
    case FailureKind::OverBudget:
        return static_cast<FailureKind>(value);
    case FailureKind::Internal:
        break;
    }
    return FailureKind::Internal;
}

} // namespace vots::dist
