// Parses thick-slab requests and places the slab's two planes in grid index space.
#include "vots/render/Slab.h"

#include "vots/fit/Error.h"

#include "NumberText.h"

#include <cmath>
#include <cstdio>

namespace vots::render {

namespace {
std::string exact(double value) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", value);
    return text;
}
} // namespace

Slab parseSlab(std::string_view text) {
    const auto pair = detail::parseFinitePair(text);
    if (!pair || !((*pair)[1] > 0.0))
        throw fit::InputError("slab '" + std::string(text.substr(0, 64)) +
                              "' is not OFFSET,THICKNESS in mm (two finite numbers, thickness > 0)");
    return Slab{(*pair)[0], (*pair)[1]};
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
