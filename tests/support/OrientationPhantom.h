// A phantom with markers at the patient's left, anterior and superior, stored in any axis order, and
// writers for it (NIfTI, NRRD); another writer (DICOM) plugs in by taking a PhantomGrid.
#pragma once

#include "vots/fit/PatientAxes.h"
#include "vots/fit/Volume.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace vots::test {

/// Marker values: three flat-topped balls of distinct brightness (and size), so each one is found in a
/// rendered MIP by its exact value (trilinear interpolation of equal samples returns that value).
constexpr float LEFT_MARKER = 300.f;     // at the patient's left (+x in LPS)
constexpr float ANTERIOR_MARKER = 200.f; // at the patient's front (-y in LPS)
constexpr float SUPERIOR_MARKER = 100.f; // at the top of the head (+z in LPS)
constexpr float PHANTOM_BODY = 20.f;     // a dim ellipsoid holding them, so the anatomy has a body

/// Patient extent in grid points along L, P, S (distinct, so a permutation shows in the dims). Odd, so
/// the grid points are the patient positions k * spacing, k in [-(n-1)/2, (n-1)/2], for every order.
constexpr std::array<int, 3> PHANTOM_PATIENT_POINTS{33, 29, 25};
constexpr double PHANTOM_SPACING = 1.5;

/// The phantom in one storage order: grid axis a grows along patientAxes[a] (a signed permutation of
/// L, P, S), origin is grid point (0,0,0) in LPS millimetres.
struct PhantomGrid {
    std::array<int, 3> dims{};
    std::array<double, 3> spacing{PHANTOM_SPACING, PHANTOM_SPACING, PHANTOM_SPACING};
    std::array<double, 3> origin{};
    fit::PatientAxes patientAxes{};
    std::vector<float> values; // x fastest
};

/// The field at an LPS position in millimetres.
inline float phantomValue(const std::array<double, 3>& p) {
    const auto inBall = [&](double cx, double cy, double cz, double r) {
        const double dx = p[0] - cx, dy = p[1] - cy, dz = p[2] - cz;
        return dx * dx + dy * dy + dz * dz <= r * r;
    };
    const double s = PHANTOM_SPACING;
    if (inBall(15 * s * 0.7, 0, 0, 4.5 * s)) return LEFT_MARKER;
    if (inBall(0, -14 * s * 0.7, 0, 3.5 * s)) return ANTERIOR_MARKER;
    if (inBall(0, 0, 12 * s * 0.7, 2.5 * s)) return SUPERIOR_MARKER;
    const double ex = p[0] / (15 * s), ey = p[1] / (13 * s), ez = p[2] / (11 * s);
    return ex * ex + ey * ey + ez * ez <= 1.0 ? PHANTOM_BODY : 0.f;
}

/// The phantom stored with grid axes along `patientAxes` (each +-L, +-P or +-S, each once).
inline PhantomGrid phantomGrid(const fit::PatientAxes& patientAxes) {
    PhantomGrid g;
    g.patientAxes = patientAxes;
    std::array<int, 3> along{}; // the patient axis (0 L, 1 P, 2 S) of each grid axis
    for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c)
            if (patientAxes[a][c] != 0.0) along[a] = c;
    for (int a = 0; a < 3; ++a)
        g.dims[a] = PHANTOM_PATIENT_POINTS[along[a]];
    for (int c = 0; c < 3; ++c) {
        g.origin[c] = 0.0;
        for (int a = 0; a < 3; ++a) // index 0 sits at the end the axis grows away from
            g.origin[c] -= patientAxes[a][c] * PHANTOM_SPACING * (g.dims[a] - 1) / 2.0;
    }
    g.values.resize(static_cast<std::size_t>(g.dims[0]) * g.dims[1] * g.dims[2]);
    std::size_t n = 0;
    for (int k = 0; k < g.dims[2]; ++k)
        for (int j = 0; j < g.dims[1]; ++j)
            for (int i = 0; i < g.dims[0]; ++i) {
                const std::array<int, 3> index{i, j, k};
                std::array<double, 3> p = g.origin;
                for (int a = 0; a < 3; ++a)
                    for (int c = 0; c < 3; ++c)
                        p[c] += patientAxes[a][c] * PHANTOM_SPACING * index[a];
                g.values[n++] = phantomValue(p);
            }
    return g;
}

/// Storage orders the tests use: LPS, RAS (x and y flipped), and a permuted one (slices along -P, rows
/// along S, columns along -L), like a coronal series stored right to left.
constexpr fit::PatientAxes LPS_ORDER = fit::IDENTITY_PATIENT_AXES;
constexpr fit::PatientAxes RAS_ORDER{{{-1.0, 0.0, 0.0}, {0.0, -1.0, 0.0}, {0.0, 0.0, 1.0}}};
constexpr fit::PatientAxes PERMUTED_ORDER{{{0.0, 0.0, 1.0}, {-1.0, 0.0, 0.0}, {0.0, -1.0, 0.0}}};

namespace phantom_detail {
template <typename T> void put(std::string& bytes, std::size_t offset, T value) {
    std::memcpy(bytes.data() + offset, &value, sizeof(T)); // host order: NIfTI marks it by sizeof_hdr
}
inline void writeFile(const std::string& path, const std::string& header, const std::vector<float>& values) {
    std::ofstream out(path, std::ios::binary);
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    out.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(values.size() * 4));
    if (!out) throw std::runtime_error("cannot write " + path);
}
} // namespace phantom_detail

/// NIfTI-1 float32 with an sform (RAS, as NIfTI requires) and qform_code 0.
inline void writePhantomNifti(const PhantomGrid& g, const std::string& path) {
    using phantom_detail::put;
    std::string h(352, '\0');
    put<std::int32_t>(h, 0, 348);
    const std::int16_t dim[4] = {3, static_cast<std::int16_t>(g.dims[0]),
                                 static_cast<std::int16_t>(g.dims[1]), static_cast<std::int16_t>(g.dims[2])};
    for (std::size_t i = 0; i < 4; ++i)
        put<std::int16_t>(h, 40 + 2 * i, dim[i]);
    for (std::size_t i = 4; i < 8; ++i)
        put<std::int16_t>(h, 40 + 2 * i, 1);
    put<std::int16_t>(h, 70, 16); // float32
    put<std::int16_t>(h, 72, 32);
    put<float>(h, 76, 1.f);
    for (std::size_t a = 0; a < 3; ++a)
        put<float>(h, 80 + 4 * a, static_cast<float>(g.spacing[a]));
    put<float>(h, 108, 352.f);
    put<std::int16_t>(h, 254, 1); // sform_code: scanner anatomical
    const double rasSign[3] = {-1.0, -1.0, 1.0};
    for (std::size_t row = 0; row < 3; ++row) {
        for (std::size_t a = 0; a < 3; ++a)
            put<float>(h, 280 + 16 * row + 4 * a,
                       static_cast<float>(rasSign[row] * g.patientAxes[a][row] * g.spacing[a]));
        put<float>(h, 292 + 16 * row, static_cast<float>(rasSign[row] * g.origin[row]));
    }
    std::memcpy(h.data() + 344, "n+1\0", 4);
    phantom_detail::writeFile(path, h, g.values);
}

/// Attached raw NRRD with `space` (left-posterior-superior or right-anterior-superior) and `space
/// directions`.
inline void writePhantomNrrd(const PhantomGrid& g, const std::string& path, bool rasSpace) {
    const double sign[3] = {rasSpace ? -1.0 : 1.0, rasSpace ? -1.0 : 1.0, 1.0};
    const auto vec = [&](const std::array<double, 3>& v, bool scaled, int a) {
        std::string out = "(";
        for (int c = 0; c < 3; ++c) {
            const double value = sign[c] * v[c] * (scaled ? g.spacing[a] : 1.0);
            if (c) out += ",";
            out += std::to_string(value == 0.0 ? 0.0 : value);
        }
        return out + ")";
    };
    std::string h = std::string("NRRD0004\ntype: float\ndimension: 3\nsizes: ") + std::to_string(g.dims[0]) +
                    " " + std::to_string(g.dims[1]) + " " + std::to_string(g.dims[2]) +
                    "\nspace: " + (rasSpace ? "right-anterior-superior" : "left-posterior-superior") +
                    "\nspace directions:";
    for (int a = 0; a < 3; ++a)
        h.append(" ").append(vec(g.patientAxes[a], true, a));
    h.append("\nspace origin: ")
        .append(vec(g.origin, false, 0))
        .append("\nendian: little\nencoding: raw\n\n");
    phantom_detail::writeFile(path, h, g.values);
}

} // namespace vots::test
