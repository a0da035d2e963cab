// Reads the number pairs of slab and sweep requests (NumberText.h).
#include "NumberText.h"

#include <charconv>
#include <cmath>

namespace vots::render::detail {

std::optional<double> parseFinite(std::string_view text) {
    if (text.empty() || text.size() > 32) return std::nullopt;
    double value = 0.0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
    return value;
}

std::optional<std::array<double, 2>> parseFinitePair(std::string_view text) {
    const auto comma = text.find(',');
    if (comma == std::string_view::npos) return std::nullopt;
    const auto first = parseFinite(text.substr(0, comma));
    const auto second = parseFinite(text.substr(comma + 1));
    if (!first || !second || std::abs(*first) > 1e9 || std::abs(*second) > 1e9) return std::nullopt;
    return std::array<double, 2>{*first, *second};
}

} // namespace vots::render::detail
