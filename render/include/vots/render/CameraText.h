// The one text form of a camera, shared by `vots render --cam` and the server's `cam=` URL parameter.
#pragma once

#include "vots/render/Camera.h"

#include <string>
#include <string_view>

namespace vots::render {

/// Text form: comma-separated key=value pairs, keys in any order, each at most once, missing keys
/// take the defaults of Camera:
///     az=30,el=20,zoom=1,pan=0:0,proj=ortho,fov=30
/// keys: az (degrees), el (degrees), zoom, pan (x:y), proj (ortho|persp), fov (degrees),
///       view (anterior|posterior|left|right|superior|inferior; sets az and el, so it cannot be
///       combined with az or el). A bare view name ("anterior") is accepted as the whole text.
/// Numbers are decimal (no NaN, no inf, no hex); ranges as in Camera.h. Whitespace is not allowed.
/// At most MAX_CAMERA_TEXT characters.
inline constexpr std::size_t MAX_CAMERA_TEXT = 256;

/// Throws vots::fit::InputError with a one-line message ("camera: unknown key 'foo'", ...).
Camera parseCamera(std::string_view text);

/// Canonical text with every key; shortest decimal that round-trips, so parseCamera(formatCamera(c)) == c.
std::string formatCamera(const Camera& camera);

} // namespace vots::render
