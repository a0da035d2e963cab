// Strict parser and canonical formatter for the camera text form (`--cam`, URL `cam=`); see CameraText.h.
#include "vots/fit/Error.h"
#include "vots/render/CameraText.h"

#include <charconv>
#include <set>
#include <string>
#include <system_error>

namespace vots::render {

namespace {

[[noreturn]] void reject(const std::string& why) {
    throw fit::InputError("camera: " + why);
}

// Plain decimal only: from_chars would also take "inf", "nan" and hex, which we refuse by shape.
double parseNumber(std::string_view key, std::string_view text) {
    const std::string shown = "'" + std::string(key) + "=" + std::string(text) + "'";
    if (text.empty()) reject("empty value in " + shown);
    for (char ch : text)
        if (!((ch >= '0' && ch <= '9') || ch == '-' || ch == '+' || ch == '.' || ch == 'e' || ch == 'E'))
            reject("not a decimal number in " + shown);
    double value = 0.0;
    const char* first = text.data();
    if (*first == '+') ++first; // from_chars does not accept a leading '+'
    const auto [end, ec] = std::from_chars(first, text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size()) reject("not a decimal number in " + shown);
    return value;
}

std::string formatNumber(double value) {
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value); // shortest round-trip form
    return std::string(buffer, result.ptr);
}

} // namespace

Camera parseCamera(std::string_view text) {
    if (text.size() > MAX_CAMERA_TEXT)
        reject("text longer than " + std::to_string(MAX_CAMERA_TEXT) + " characters");
    if (text.empty()) reject("empty text");
    if (const auto view = findView(text)) return cameraForView(*view);

    Camera camera;
    std::set<std::string, std::less<>> seen;
    std::size_t pos = 0;
    while (pos <= text.size()) {
        const std::size_t comma = std::min(text.find(',', pos), text.size());
        const std::string_view item = text.substr(pos, comma - pos);
        pos = comma + 1;
        const std::size_t eq = item.find('=');
        if (item.empty()) reject("empty item (stray comma)");
        if (eq == std::string_view::npos) reject("'" + std::string(item) + "' is not key=value");
        const std::string_view key = item.substr(0, eq), value = item.substr(eq + 1);
        if (!seen.insert(std::string(key)).second) reject("key '" + std::string(key) + "' given twice");

        if (key == "az") {
            camera.azimuthDeg = parseNumber(key, value);
        } else if (key == "el") {
            camera.elevationDeg = parseNumber(key, value);
        } else if (key == "zoom") {
            camera.zoom = parseNumber(key, value);
        } else if (key == "fov") {
            camera.fovDeg = parseNumber(key, value);
        } else if (key == "pan") {
            const std::size_t colon = value.find(':');
            if (colon == std::string_view::npos) reject("pan must be x:y, got '" + std::string(value) + "'");
            camera.panX = parseNumber("pan x", value.substr(0, colon));
            camera.panY = parseNumber("pan y", value.substr(colon + 1));
        } else if (key == "proj") {
            if (value == "ortho")
                camera.projection = Projection::Orthographic;
            else if (value == "persp")
                camera.projection = Projection::Perspective;
            else
                reject("proj must be ortho or persp, got '" + std::string(value) + "'");
        } else if (key == "view") {
            const auto view = findView(value);
            if (!view) reject("unknown view '" + std::string(value) + "'");
            const Camera preset = cameraForView(*view);
            camera.azimuthDeg = preset.azimuthDeg;
            camera.elevationDeg = preset.elevationDeg;
        } else {
            reject("unknown key '" + std::string(key) + "' (known: az, el, zoom, pan, proj, fov, view)");
        }
        if (comma == text.size()) break;
    }
    if (seen.count("view") && (seen.count("az") || seen.count("el")))
        reject("view cannot be combined with az or el");
    validateCamera(camera);
    return camera;
}

std::string formatCamera(const Camera& c) {
    return "az=" + formatNumber(c.azimuthDeg) + ",el=" + formatNumber(c.elevationDeg) +
           ",zoom=" + formatNumber(c.zoom) + ",pan=" + formatNumber(c.panX) + ":" + formatNumber(c.panY) +
           ",proj=" + (c.projection == Projection::Orthographic ? "ortho" : "persp") +
           ",fov=" + formatNumber(c.fovDeg);
}

} // namespace vots::render
