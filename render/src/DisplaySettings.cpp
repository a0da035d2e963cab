// Window/level parsing and the CPU statement of the display mapping (display.frag does the same).
#include "vots/render/DisplaySettings.h"

#include "vots/fit/Error.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>
#include <system_error>

namespace vots::render {

DisplaySettings windowForRange(float lo, float hi, Colormap map) {
    DisplaySettings s;
    s.level = 0.5f * (lo + hi);
    s.width = std::max(hi - lo, 1e-6f * std::max(1.f, std::abs(lo) + std::abs(hi)));
    s.colormap = map;
    return s;
}

DisplaySettings parseWindow(std::string_view text, Colormap map) {
    auto bad = [&](const std::string& why) {
        return fit::InputError("window '" + std::string(text.substr(0, 64)) + "': " + why +
                               " (expected level,width, e.g. 400,2000)");
    };
    const std::size_t comma = text.find(',');
    if (comma == std::string_view::npos) throw bad("missing comma");
    float values[2];
    const std::string_view parts[2] = {text.substr(0, comma), text.substr(comma + 1)};
    for (int i = 0; i < 2; ++i) {
        const std::string_view p = parts[i];
        if (p.empty() || p.find_first_not_of("0123456789+-.eE") != std::string_view::npos)
            throw bad("not a decimal number");
        const char* first = p.data() + (p[0] == '+' ? 1 : 0);
        const auto [end, ec] = std::from_chars(first, p.data() + p.size(), values[i]);
        if (ec != std::errc() || end != p.data() + p.size() || !std::isfinite(values[i]))
            throw bad("not a finite number");
    }
    if (!(values[1] > 0.f)) throw bad("width must be > 0");
    DisplaySettings s;
    s.level = values[0];
    s.width = values[1];
    s.colormap = map;
    return s;
}

} // namespace vots::render
