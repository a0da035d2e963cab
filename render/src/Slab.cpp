// Parses thick-slab requests and places the slab's two planes in grid index space.
#include "vots/render/Slab.h"

#include "vots/fit/Error.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace vots::render {

namespace {
std::optional<double> parseFinite(std::string_view text) {
    if (text.empty() || text.size() > 32) return std::nullopt;
    double value = 0.0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
    return value;
}

std::string exact(double value) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", value);
    return text;
}
} // namespace

Slab parseSlab(std::string_view text) {
    const auto comma = text.find(',');
    const auto bad = [&] {
        return fit::InputError("slab '" + std::string(text.substr(0, 64)) +
                               "' is not OFFSET,THICKNESS in mm (two finite numbers, thickness > 0)");
    };
    if (comma == std::string_view::npos) throw bad();
    const auto offset = parseFinite(text.substr(0, comma));
    const auto thickness = parseFinite(text.substr(comma + 1));
    if (!offset || !thickness || !(*thickness > 0.0) || std::abs(*offset) > 1e9 || *thickness > 1e9)
        throw bad();
    return Slab{*offset, *thickness};
}

std::string formatSlab(const Slab& slab) {
    return exact(slab.offsetMm) + ',' + exact(slab.thicknessMm);
}

SlabPlanes slabPlanesInIndexSpace(const Slab& slab, const Camera& camera, const SceneBounds& bounds) {
    constexpr double DEG = 3.14159265358979323846 / 180.0;
    const double az = camera.azimuthDeg * DEG, el = camera.elevationDeg * DEG;
    // The camera looks from e (Camera.h) towards the centre: forward = -e.
    const std::array<double, 3> forward{-std::sin(az) * std::cos(el), std::cos(az) * std::cos(el),
                                        -std::sin(el)};
    SlabPlanes planes;
    double offset = 0.0;
    for (int w = 0; w < 3; ++w)
        offset += forward[w] * (bounds.origin[w] - 0.5 * (bounds.lo[w] + bounds.hi[w]));
    for (int a = 0; a < 3; ++a) {
        double along = 0.0;
        for (int w = 0; w < 3; ++w)
            along += forward[w] * bounds.axes[a][w];
        planes.normal[a] = along * bounds.spacing[a];
    }
    planes.offset = offset;
    planes.lo = slab.offsetMm - 0.5 * slab.thicknessMm;
    planes.hi = slab.offsetMm + 0.5 * slab.thicknessMm;
    return planes;
}

} // namespace vots::render
