// Build-time tool: writes web/js/contract.js, the viewer's copy of the C++ names, limits and tables.
//
// Usage: vots_web_contract OUT.js          writes the module
//        vots_web_contract --check FILE.js  exits 1 when FILE.js is not what this build would write
// The viewer imports the module instead of typing the rules again: the render modes, renderers and
// colour maps and which of them go together, the camera's defaults, limits and named views, the patient
// letters, and the colour map tables. Every value is asked of the functions the server itself calls
// (parseModeName, applyProjection, validateCamera's ranges, colormapTable, ...), so a rule changed in
// C++ changes the module, and the ctest that runs --check says so until the file is regenerated.
#include "vots/fit/Error.h"
#include "vots/fit/Monomials.h"
#include "vots/fit/PatientAxes.h"
#include "vots/render/Camera.h"
#include "vots/render/CameraText.h"
#include "vots/render/Colormap.h"
#include "vots/render/FrameRequest.h"
#include "vots/render/RenderMode.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace vots::render;

// Every enumerator, each listed through a switch, so that one added in C++ stops this build (-Wswitch)
// until it is listed here too.
constexpr bool listed(RenderMode m) {
    switch (m) {
    case RenderMode::Mip:
    case RenderMode::MinIp:
    case RenderMode::Aip:
    case RenderMode::Density:
        return true;
    }
    return false;
}
constexpr RenderMode RENDER_MODES[] = {RenderMode::Mip, RenderMode::MinIp, RenderMode::Aip,
                                       RenderMode::Density};
static_assert(listed(RENDER_MODES[0]));

constexpr bool listed(RendererKind k) {
    switch (k) {
    case RendererKind::Vots:
    case RendererKind::Grid:
        return true;
    }
    return false;
}
constexpr RendererKind RENDERERS[] = {RendererKind::Vots, RendererKind::Grid};
static_assert(listed(RENDERERS[0]));

constexpr bool listed(ViewPreset v) {
    switch (v) {
    case ViewPreset::Anterior:
    case ViewPreset::Posterior:
    case ViewPreset::Left:
    case ViewPreset::Right:
    case ViewPreset::Superior:
    case ViewPreset::Inferior:
        return true;
    }
    return false;
}
constexpr ViewPreset VIEWS[] = {ViewPreset::Anterior, ViewPreset::Posterior, ViewPreset::Left,
                                ViewPreset::Right,    ViewPreset::Superior,  ViewPreset::Inferior};
static_assert(listed(VIEWS[0]));

// The mode name an old link may carry that stands for a mode and a renderer (parseModeName reads it).
constexpr std::string_view LEGACY_MODE_NAMES[] = {"reference"};

// Shortest text that reads back as the same double, as JavaScript prints numbers; float noise below
// 1e-12 (cos 90 degrees) is written as 0, so the file reads as the geometry it states.
std::string number(double value) {
    if (std::fabs(value) < 1e-12) value = 0.0;
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
    return std::string(buffer, result.ptr);
}

// Appended to a string rather than `"'" + std::string(text)`: GCC 12 at -O3 warns (-Wrestrict, a known false
// positive) on a literal prepended to a temporary string.
std::string quoted(std::string_view text) {
    std::string out = "'";
    out.append(text).append("'");
    return out;
}

template <typename Range, typename Name> std::string nameList(const Range& values, Name name) {
    std::string out = "[";
    for (const auto& v : values)
        out += (out.size() > 1 ? ", " : "") + quoted(name(v));
    return out + "]";
}

std::string vector3(const std::array<double, 3>& v) {
    std::string out = "[";
    out.append(number(v[0])).append(", ").append(number(v[1])).append(", ").append(number(v[2]));
    return out + "]";
}

// The projection's word in the camera text ("ortho", "persp"), read from formatCamera's output.
std::string projectionWord(Projection projection) {
    Camera camera;
    camera.projection = projection;
    const std::string text = formatCamera(camera);
    const auto start = text.find("proj=") + 5;
    return text.substr(start, text.find(',', start) - start);
}

// Whether applyProjection takes this mode with this renderer: the rule the server keeps.
bool accepts(RenderMode mode, std::string_view renderer) {
    FrameRequest frame;
    try {
        applyProjection(frame, renderModeName(mode), renderer, std::nullopt);
        return true;
    } catch (const vots::fit::InputError&) {
        return false;
    }
}

// Image right, up and the view direction in the world for a named view, read off the camera's own
// matrices: for an orthographic camera over the unit box (index = world), rows 0, 1 and 2 of
// index -> clip are right, up and forward, each scaled.
struct ViewAxes {
    std::array<double, 3> right, up, forward;
};
ViewAxes axesOf(ViewPreset view) {
    const CameraMatrices m = computeCameraMatrices(cameraForView(view), SceneBounds{}, 1, 1);
    auto row = [&](int r) {
        std::array<double, 3> v{m.indexToClip[r], m.indexToClip[4 + r], m.indexToClip[8 + r]};
        const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        for (double& x : v)
            x /= length;
        return v;
    };
    return {row(0), row(1), row(2)};
}

std::string colourHex(const std::array<std::uint8_t, 4>& rgba) {
    static const char* const DIGITS = "0123456789abcdef";
    std::string out = "#";
    for (int k = 0; k < 3; ++k) {
        out += DIGITS[rgba[k] >> 4];
        out += DIGITS[rgba[k] & 15];
    }
    return out;
}

std::string generate() {
    std::ostringstream out;
    out << "// Generated by vots_web_contract (render/tools/WebContract.cpp) from the C++ rules; do not "
           "edit.\n"
           "// Regenerate: cmake --build BUILD --target web_contract (the ctest "
           "WebViewer.ContractIsGenerated\n"
           "// fails while this file differs from what the build would write).\n\n";

    out << "// Names the server reads in mode=, renderer= and colormap=, and a request's defaults.\n";
    out << "export const MODES = Object.freeze(" << nameList(RENDER_MODES, renderModeName) << ");\n";
    out << "export const RENDERERS = Object.freeze(" << nameList(RENDERERS, rendererName) << ");\n";
    out << "export const COLORMAPS = Object.freeze(" << nameList(ALL_COLORMAPS, colormapName) << ");\n";
    const FrameRequest defaults;
    out << "export const DEFAULT_MODE = " << quoted(renderModeName(defaults.mode)) << ";\n";
    out << "export const DEFAULT_RENDERER = " << quoted(rendererName(defaults.renderer)) << ";\n";
    out << "export const DEFAULT_COLORMAP = " << quoted(colormapName(defaults.colormap)) << ";\n\n";

    out << "// Old mode names that also choose the renderer.\n";
    out << "export const LEGACY_MODES = Object.freeze({\n";
    for (std::string_view name : LEGACY_MODE_NAMES) {
        const ModeName read = parseModeName(name);
        out << "  " << name << ": Object.freeze({ mode: " << quoted(renderModeName(read.mode))
            << ", renderer: " << quoted(rendererName(read.impliedRenderer.value_or(defaults.renderer)))
            << " }),\n";
    }
    out << "});\n\n";

    std::vector<RenderMode> gridModes;
    for (RenderMode mode : RENDER_MODES)
        if (accepts(mode, rendererName(RendererKind::Grid))) gridModes.push_back(mode);
    out << "// The modes the grid renderer draws (the others answer 400 there).\n";
    out << "export const GRID_MODES = Object.freeze(" << nameList(gridModes, renderModeName) << ");\n\n";

    out << "// The highest Taylor degree a fit takes (degree=0..MAX_DEGREE).\n";
    out << "export const MAX_DEGREE = " << vots::fit::monomialDegree(vots::fit::MONOMIAL_COUNT - 1) << ";\n";
    out << "// The longest side GET /render draws, in pixels.\n";
    out << "export const MAX_SERVED_SIDE = " << MAX_SERVED_SIDE << ";\n\n";

    const Camera camera;
    out << "// The camera: its text form's projection words, its defaults and the ranges the server "
           "accepts.\n";
    out << "export const PROJECTIONS = Object.freeze({ ortho: "
        << quoted(projectionWord(Projection::Orthographic))
        << ", persp: " << quoted(projectionWord(Projection::Perspective)) << " });\n";
    out << "export const DEFAULT_CAMERA = Object.freeze({ az: " << number(camera.azimuthDeg)
        << ", el: " << number(camera.elevationDeg) << ", zoom: " << number(camera.zoom)
        << ", panX: " << number(camera.panX) << ", panY: " << number(camera.panY)
        << ", proj: " << quoted(projectionWord(camera.projection)) << ", fov: " << number(camera.fovDeg)
        << " });\n";
    auto range = [](CameraRange r) { return "Object.freeze([" + number(r.lo) + ", " + number(r.hi) + "])"; };
    out << "export const CAMERA_LIMITS = Object.freeze({\n"
        << "  az: " << range(AZIMUTH_RANGE_DEG) << ",\n"
        << "  el: " << range(ELEVATION_RANGE_DEG) << ",\n"
        << "  zoom: " << range(ZOOM_RANGE) << ",\n"
        << "  pan: " << range(PAN_RANGE) << ",\n"
        << "  fov: " << range(FOV_RANGE_DEG) << ",\n"
        << "});\n\n";

    out << "// Named views (degrees), and the world directions (LPS) of image right, image up and the view\n"
           "// direction the server's camera gives each.\n";
    out << "export const VIEWS = Object.freeze({\n";
    for (ViewPreset view : VIEWS) {
        const Camera c = cameraForView(view);
        out << "  " << viewName(view) << ": Object.freeze({ az: " << number(c.azimuthDeg)
            << ", el: " << number(c.elevationDeg) << " }),\n";
    }
    out << "});\n";
    out << "export const VIEW_AXES = Object.freeze({\n";
    for (ViewPreset view : VIEWS) {
        const ViewAxes a = axesOf(view);
        out << "  " << viewName(view) << ": { right: " << vector3(a.right) << ", up: " << vector3(a.up)
            << ", forward: " << vector3(a.forward) << " },\n";
    }
    out << "});\n\n";

    out << "// Patient letters of the world's +x, +y, +z (first) and -x, -y, -z (second): DICOM's LPS.\n";
    out << "export const PATIENT_LETTERS = Object.freeze([\n";
    for (int c = 0; c < 3; ++c) {
        std::array<double, 3> axis{0.0, 0.0, 0.0};
        axis[static_cast<std::size_t>(c)] = 1.0;
        const std::string positive = vots::fit::patientDirectionName(axis);
        axis[static_cast<std::size_t>(c)] = -1.0;
        out << "  Object.freeze([" << quoted(positive) << ", "
            << quoted(vots::fit::patientDirectionName(axis)) << "]),\n";
    }
    out << "]);\n\n";

    out << "// Each colour map's 256 sRGB colours, entry 0 at the window's low end "
           "(render/src/Colormap.cpp).\n";
    out << "export const COLORMAP_TABLES = Object.freeze({\n";
    for (Colormap map : ALL_COLORMAPS) {
        const ColormapTable& table = colormapTable(map);
        out << "  " << colormapName(map) << ": Object.freeze([";
        for (std::size_t i = 0; i < table.size(); ++i) {
            if (table[i][3] != 255)
                throw std::runtime_error("colour maps are opaque; the module has no alpha");
            out << (i % 8 == 0 ? "\n    " : " ") << quoted(colourHex(table[i])) << ",";
        }
        out << "\n  ]),\n";
    }
    out << "});\n";
    return out.str();
}

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return {};
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

} // namespace

int main(int argc, char** argv) {
    try {
        const std::string module = generate();
        if (argc == 3 && std::string_view(argv[1]) == "--check") {
            if (readFile(argv[2]) == module) return 0;
            std::cerr << argv[2]
                      << " is not what vots_web_contract writes from the C++ rules of this build;\n"
                      << "regenerate it: cmake --build BUILD --target web_contract, and commit the result\n";
            return 1;
        }
        if (argc != 2) {
            std::cerr << "usage: vots_web_contract OUT.js | --check FILE.js\n";
            return 2;
        }
        std::ofstream out(argv[1], std::ios::binary);
        out << module;
        if (!out.flush()) throw std::runtime_error(std::string("cannot write ") + argv[1]);
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "vots_web_contract: " << e.what() << "\n";
        return 1;
    }
}
