// Colour map tables built from formulas and anchors at first use (no copied tables).
#include "vots/render/Colormap.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace vots::render {

namespace {

using Rgb = std::array<double, 3>; // linear-light or sRGB, 0..1, as named at each use

double clamp01(double v) {
    return std::clamp(v, 0.0, 1.0);
}

// "hot": red rises over the first third, green over the second, blue over the last.
Rgb hot(double t) {
    return {clamp01(3.0 * t), clamp01(3.0 * t - 1.0), clamp01(3.0 * t - 2.0)};
}

// "bone": seven parts grey plus one part hot with its channels reversed (a bluish grey).
Rgb bone(double t) {
    const Rgb h = hot(t);
    return {(7.0 * t + h[2]) / 8.0, (7.0 * t + h[1]) / 8.0, (7.0 * t + h[0]) / 8.0};
}

// sRGB <-> linear and linear sRGB <-> OKLab (Björn Ottosson's published matrices, 2020).
double toLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
double toSrgb(double c) {
    return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

Rgb linearToOklab(const Rgb& c) {
    const double l = std::cbrt(0.4122214708 * c[0] + 0.5363325363 * c[1] + 0.0514459929 * c[2]);
    const double m = std::cbrt(0.2119034982 * c[0] + 0.6806995451 * c[1] + 0.1073969566 * c[2]);
    const double s = std::cbrt(0.0883024619 * c[0] + 0.2817188376 * c[1] + 0.6299787005 * c[2]);
    return {0.2104542553 * l + 0.7936177850 * m - 0.0040720468 * s,
            1.9779984951 * l - 2.4285922050 * m + 0.4505937099 * s,
            0.0259040371 * l + 0.7827717662 * m - 0.8086757660 * s};
}

Rgb oklabToLinear(const Rgb& lab) {
    const double l = std::pow(lab[0] + 0.3963377774 * lab[1] + 0.2158037573 * lab[2], 3.0);
    const double m = std::pow(lab[0] - 0.1055613458 * lab[1] - 0.0638541728 * lab[2], 3.0);
    const double s = std::pow(lab[0] - 0.0894841775 * lab[1] - 1.2914855480 * lab[2], 3.0);
    return {4.0767416621 * l - 3.3077115913 * m + 0.2309699292 * s,
            -1.2684380046 * l + 2.6097574011 * m - 0.3413193965 * s,
            -0.0041960863 * l - 0.7034186147 * m + 1.7076147010 * s};
}

// A viridis-like map: the five published viridis key colours at t = 0, 1/4, 1/2, 3/4, 1, joined by a
// Catmull-Rom spline in OKLab, so lightness rises smoothly and near-uniformly between them.
Rgb viridis(double t) {
    static const std::array<Rgb, 5> ANCHORS_SRGB{{{0x44 / 255.0, 0x01 / 255.0, 0x54 / 255.0},
                                                  {0x3b / 255.0, 0x52 / 255.0, 0x8b / 255.0},
                                                  {0x21 / 255.0, 0x91 / 255.0, 0x8c / 255.0},
                                                  {0x5e / 255.0, 0xc9 / 255.0, 0x62 / 255.0},
                                                  {0xfd / 255.0, 0xe7 / 255.0, 0x25 / 255.0}}};
    std::array<Rgb, 5> lab;
    for (std::size_t i = 0; i < lab.size(); ++i)
        lab[i] = linearToOklab(
            {toLinear(ANCHORS_SRGB[i][0]), toLinear(ANCHORS_SRGB[i][1]), toLinear(ANCHORS_SRGB[i][2])});
    const double x = clamp01(t) * 4.0;
    const int seg = std::min(static_cast<int>(x), 3);
    const double u = x - seg;
    auto at = [&](int i) { return lab[static_cast<std::size_t>(std::clamp(i, 0, 4))]; };
    const Rgb p0 = at(seg - 1), p1 = at(seg), p2 = at(seg + 1), p3 = at(seg + 2);
    Rgb out;
    for (int k = 0; k < 3; ++k)
        out[k] = 0.5 * (2.0 * p1[k] + (-p0[k] + p2[k]) * u +
                        (2.0 * p0[k] - 5.0 * p1[k] + 4.0 * p2[k] - p3[k]) * u * u +
                        (-p0[k] + 3.0 * p1[k] - 3.0 * p2[k] + p3[k]) * u * u * u);
    const Rgb linear = oklabToLinear(out);
    return {toSrgb(clamp01(linear[0])), toSrgb(clamp01(linear[1])), toSrgb(clamp01(linear[2]))};
}

ColormapTable build(Colormap map) {
    ColormapTable table{};
    for (int i = 0; i < 256; ++i) {
        const double t = i / 255.0;
        Rgb c{t, t, t};
        if (map == Colormap::Bone) c = bone(t);
        if (map == Colormap::Hot) c = hot(t);
        if (map == Colormap::Viridis) c = viridis(t);
        for (int k = 0; k < 3; ++k)
            table[i][k] = static_cast<std::uint8_t>(std::lround(255.0 * clamp01(c[k])));
        table[i][3] = 255;
    }
    return table;
}

} // namespace

const ColormapTable& colormapTable(Colormap map) {
    static const std::array<ColormapTable, 4> TABLES{build(Colormap::Grey), build(Colormap::Bone),
                                                     build(Colormap::Hot), build(Colormap::Viridis)};
    return TABLES[static_cast<std::size_t>(map)];
}

} // namespace vots::render
