// libFuzzer target: render::parseCamera must parse or throw InputError, and its output must round-trip.
#include "vots/fit/Error.h"
#include "vots/render/CameraText.h"

#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        const vots::render::Camera camera = vots::render::parseCamera(text);
        // CameraText.h promises parseCamera(formatCamera(c)) == c for every camera it accepts.
        const vots::render::Camera again = vots::render::parseCamera(vots::render::formatCamera(camera));
        if (vots::render::formatCamera(again) != vots::render::formatCamera(camera)) std::abort();
    } catch (const vots::fit::InputError&) {
    }
    return 0;
}
