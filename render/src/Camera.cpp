// Orbit camera maths: presets, validation, scene bounds and the index->clip matrix (see Camera.h).
#include "vots/render/Camera.h"

#include "vots/fit/Error.h"
#include "vots/fit/Volume.h"
#include "vots/fit/VotSpace.h"
#include "vots/render/Image.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include <cmath>
#include <string>

namespace vots::render {

namespace {

constexpr std::array<std::pair<ViewPreset, const char*>, 6> VIEWS{{{ViewPreset::Anterior, "anterior"},
                                                                   {ViewPreset::Posterior, "posterior"},
                                                                   {ViewPreset::Left, "left"},
                                                                   {ViewPreset::Right, "right"},
                                                                   {ViewPreset::Superior, "superior"},
                                                                   {ViewPreset::Inferior, "inferior"}}};

SceneBounds boundsFrom(const std::array<int, 3>& dims, const std::array<double, 3>& origin,
                       const std::array<double, 3>& spacing,
                       const std::array<std::array<double, 3>, 3>& axes) {
    SceneBounds b;
    b.dims = dims;
    b.origin = origin;
    b.spacing = spacing;
    b.axes = axes;
    b.lo = origin;
    b.hi = origin;
    // Each axis moves every world coordinate by axes[a][c] * extent: the box of the corners is the origin
    // widened by each axis's contribution on its own side (for the identity, exactly origin .. end).
    for (int c = 0; c < 3; ++c) {
        for (int a = 0; a < 3; ++a) {
            const double step = axes[a][c] * (spacing[a] * std::max(dims[a] - 1, 1));
            if (step < 0.0) b.lo[c] += step;
            if (step > 0.0) b.hi[c] += step;
        }
    }
    return b;
}

void checkRange(const char* name, double value, CameraRange range) {
    if (!std::isfinite(value) || value < range.lo || value > range.hi)
        throw fit::InputError("camera: " + std::string(name) + " must be a finite number in [" +
                              std::to_string(range.lo) + ", " + std::to_string(range.hi) + "]");
}

} // namespace

Camera cameraForView(ViewPreset view) {
    Camera c;
    switch (view) {
    case ViewPreset::Anterior:
        break;
    case ViewPreset::Posterior:
        c.azimuthDeg = 180.0;
        break;
    case ViewPreset::Left:
        c.azimuthDeg = 90.0;
        break;
    case ViewPreset::Right:
        c.azimuthDeg = -90.0;
        break;
    case ViewPreset::Superior:
        c.elevationDeg = 90.0;
        break;
    case ViewPreset::Inferior:
        c.elevationDeg = -90.0;
        break;
    }
    return c;
}

std::string_view viewName(ViewPreset view) {
    for (const auto& [v, name] : VIEWS)
        if (v == view) return name;
    return "anterior";
}

std::optional<ViewPreset> findView(std::string_view name) {
    for (const auto& [v, n] : VIEWS)
        if (name == n) return v;
    return std::nullopt;
}

SceneBounds sceneBounds(const fit::VotSpace& space) {
    return boundsFrom(space.dims, space.origin, space.spacing, space.patientAxes);
}
SceneBounds sceneBounds(const fit::Volume& volume) {
    return boundsFrom(volume.dims, volume.origin, volume.spacing, volume.patientAxes);
}

void validateCamera(const Camera& c) {
    checkRange("az", c.azimuthDeg, AZIMUTH_RANGE_DEG);
    checkRange("el", c.elevationDeg, ELEVATION_RANGE_DEG);
    checkRange("zoom", c.zoom, ZOOM_RANGE);
    checkRange("pan x", c.panX, PAN_RANGE);
    checkRange("pan y", c.panY, PAN_RANGE);
    checkRange("fov", c.fovDeg, FOV_RANGE_DEG);
}

CameraMatrices computeCameraMatrices(const Camera& camera, const SceneBounds& bounds, int width, int height) {
    validateCamera(camera);
    checkImageSize(width, height);
    const glm::dvec3 lo(bounds.lo[0], bounds.lo[1], bounds.lo[2]);
    const glm::dvec3 hi(bounds.hi[0], bounds.hi[1], bounds.hi[2]);
    const glm::dvec3 centre = 0.5 * (lo + hi);
    const double radius = std::max(0.5 * glm::length(hi - lo), 1e-9);

    const double az = glm::radians(camera.azimuthDeg), el = glm::radians(camera.elevationDeg);
    const glm::dvec3 toEye(std::sin(az) * std::cos(el), -std::cos(az) * std::cos(el), std::sin(el));
    const glm::dvec3 up(-std::sin(az) * std::sin(el), std::cos(az) * std::sin(el),
                        std::cos(el)); // d toEye / d el
    const glm::dvec3 right = glm::cross(-toEye, up);
    const double aspect = double(width) / double(height);
    const double halfFov = 0.5 * glm::radians(camera.fovDeg);

    glm::dmat4 projection;
    double distance, halfHeight, nearPlane, farPlane;
    if (camera.projection == Projection::Orthographic) {
        halfHeight = radius / camera.zoom;
        distance = 2.0 * radius; // the eye stays outside the scene; the sphere spans depths [R, 3R]
        nearPlane = 0.5 * radius;
        farPlane = 3.5 * radius;
        projection = glm::ortho(-halfHeight * aspect, halfHeight * aspect, -halfHeight, halfHeight, nearPlane,
                                farPlane);
    } else {
        distance = radius / (camera.zoom * std::sin(halfFov));
        halfHeight = distance * std::tan(halfFov);
        // Inside the scene the near plane moves close to the eye; far/near stays <= ~1e4 for float rays.
        nearPlane = std::max(distance - 1.01 * radius, 1e-3 * radius);
        farPlane = distance + 1.01 * radius;
        projection = glm::perspective(2.0 * halfFov, aspect, nearPlane, farPlane);
    }
    const glm::dvec3 target = centre + halfHeight * (camera.panX * right + camera.panY * up);
    const glm::dvec3 eye = target + distance * toEye;
    const glm::dmat4 view = glm::lookAt(eye, target, up);

    glm::dmat4 indexToWorld(1.0); // column a: grid axis a in world; column 3: the origin
    for (int a = 0; a < 3; ++a) {
        for (int c = 0; c < 3; ++c)
            indexToWorld[a][c] = bounds.axes[a][c] * bounds.spacing[a];
        indexToWorld[3][a] = bounds.origin[a];
    }
    const glm::dmat4 indexToClip = projection * view * indexToWorld;
    const glm::dmat4 clipToIndex = glm::inverse(indexToClip);

    CameraMatrices m;
    const double* a = glm::value_ptr(indexToClip);
    const double* b = glm::value_ptr(clipToIndex);
    for (int i = 0; i < 16; ++i) {
        m.indexToClip[i] = a[i];
        m.clipToIndex[i] = b[i];
    }
    m.eyeWorld = {eye.x, eye.y, eye.z};
    m.nearWorld = nearPlane;
    m.farWorld = farPlane;
    m.mirrored = glm::determinant(glm::dmat3(indexToWorld)) < 0.0;
    return m;
}

} // namespace vots::render
