// The project's one exception class, in two kinds a caller must tell apart: bad input and a graphics failure.
#pragma once

#include <stdexcept>
#include <string>

namespace vots::fit {

/// Whose failure it is, which decides the exit code and the HTTP status.
enum class ErrorKind {
    Input,    // anything the user handed us that we cannot accept (a malformed file, an absurd parameter)
    Graphics, // the graphics stack failed: no EGL context, a shader that does not compile, a framebuffer
};

/// what() is one user-facing line that names the problem (and the file, where there is one).
template <ErrorKind Kind> class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Bad input: the command line exits 2, the server answers 400.
using InputError = Error<ErrorKind::Input>;
/// The renderer cannot draw on this machine; bad user input (sizes, names, camera text) is an InputError.
using GraphicsError = Error<ErrorKind::Graphics>;

} // namespace vots::fit
