// The renderer's exception for GL/EGL failures (no context, shader compile error); user input uses
// fit::InputError.
#pragma once

#include <stdexcept>
#include <string>

namespace vots::render {

/// Thrown when the graphics stack fails: no EGL display or context, a shader that does not compile,
/// an incomplete framebuffer. what() is one line. Bad user input (sizes, names, camera text) throws
/// vots::fit::InputError instead, so the CLI maps it to exit code 2.
class RenderError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

} // namespace vots::render
