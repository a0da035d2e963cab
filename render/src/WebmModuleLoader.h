// Finds and loads the vots_webm module (FFmpeg's encoder) on first use: only a WebM writer pays for FFmpeg.
#pragma once

#include "webm/WebmModule.h"

namespace vots::render {

/// The module's entry points.
struct WebmModule {
    decltype(&vots_webm_create) create = nullptr;
    decltype(&vots_webm_add_frame) addFrame = nullptr;
    decltype(&vots_webm_finish) finish = nullptr;
    decltype(&vots_webm_destroy) destroy = nullptr;
};

/// Loads the module on the first call and keeps it for the process's life. Tried in turn: the file
/// $VOTS_WEBM_MODULE names (when set, the only one), the installed place relative to the executable
/// (bin/../lib/vots), and this build tree's module. Throws std::runtime_error naming every path tried
/// and why each failed; a later call tries again.
const WebmModule& webmModule();

} // namespace vots::render
