// The one exception type for bad input (malformed files, absurd parameters); message is user-facing.
#pragma once

#include <stdexcept>
#include <string>

namespace vots::fit {

/// Thrown for anything the user handed us that we cannot accept. what() is one clear line
/// that names the problem (and the file, where there is one).
class InputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

} // namespace vots::fit
