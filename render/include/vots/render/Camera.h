// Orbit camera around the volume centre (world coordinates), six anatomical presets, ortho/perspective.
#pragma once

#include <array>
#include <optional>
#include <string_view>

namespace vots::fit {
struct Volume;
struct VotSpace;
} // namespace vots::fit

namespace vots::render {

/// World convention (DICOM LPS): +x = patient left, +y = posterior, +z = superior. Index space
/// maps to world by world = origin + sum_a patientAxes[a] * spacing[a] * index[a], so anisotropic grids
/// keep their proportions and a grid stored in any order (or obliquely) lands the same way round in the
/// patient. A volume whose file says nothing about orientation has the identity axes: index space taken
/// as LPS. Rays are traced in index space through this affine map, so no orientation resamples the grid.
///
/// The camera orbits the centre of the volume's world box. With e the unit vector from the centre
/// to the eye:  e = (sin(az) cos(el), -cos(az) cos(el), sin(el)).
///   az = 0,   el = 0   anterior view  (eye at -y, looking along +y, patient left on image right)
///   az = 180, el = 0   posterior view
///   az = 90,  el = 0   left view      (eye at +x, looking along -x)
///   az = -90, el = 0   right view
///   el = 90            superior view (eye above, looking down -z; posterior at the image top)
///   el = -90           inferior view (anterior at the image top)
/// Image up is d e / d el (= +z for el = 0); image right = forward x up.
///
/// Framing: R is the radius of the world box's bounding sphere. zoom = 1 fits that sphere into the
/// image height; zoom = 2 shows half as much. Orthographic: visible half-height R / zoom.
/// Perspective: eye distance R / (zoom * sin(fov/2)); large zoom puts the eye inside the volume.
/// pan = (px, py) moves the look-at point by px, py visible half-heights along image right / up.
enum class Projection { Orthographic, Perspective };

enum class ViewPreset { Anterior, Posterior, Left, Right, Superior, Inferior };

struct Camera {
    double azimuthDeg = 0.0;   // [-360, 360]
    double elevationDeg = 0.0; // [-90, 90]
    double zoom = 1.0;         // [0.01, 1000]
    double panX = 0.0;         // [-100, 100] visible half-heights
    double panY = 0.0;         // [-100, 100]
    Projection projection = Projection::Orthographic;
    double fovDeg = 30.0; // vertical field of view for perspective, [1, 150]; kept for ortho too

    friend bool operator==(const Camera&, const Camera&) = default;
};

/// The inclusive ranges validateCamera accepts (the web viewer clamps to the same ones, generated from
/// these).
struct CameraRange {
    double lo;
    double hi;
};
inline constexpr CameraRange AZIMUTH_RANGE_DEG{-360.0, 360.0};
inline constexpr CameraRange ELEVATION_RANGE_DEG{-90.0, 90.0};
inline constexpr CameraRange ZOOM_RANGE{0.01, 1000.0};
inline constexpr CameraRange PAN_RANGE{-100.0, 100.0}; // both pan x and pan y
inline constexpr CameraRange FOV_RANGE_DEG{1.0, 150.0};

/// az/el of a preset, everything else default.
Camera cameraForView(ViewPreset view);
/// "anterior", "posterior", "left", "right", "superior", "inferior".
std::string_view viewName(ViewPreset view);
/// The preset with this name, or nullopt.
std::optional<ViewPreset> findView(std::string_view name);

/// The world-space box the camera frames (the bounding box of the grid's corners in patient space) and
/// the grid's index -> world map.
struct SceneBounds {
    std::array<double, 3> lo{0.0, 0.0, 0.0};
    std::array<double, 3> hi{1.0, 1.0, 1.0};
    std::array<double, 3> origin{0.0, 0.0, 0.0}; // world = origin + sum_a axes[a] * spacing[a] * index[a]
    std::array<double, 3> spacing{1.0, 1.0, 1.0};
    std::array<std::array<double, 3>, 3> axes{{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}};
    std::array<int, 3> dims{2, 2, 2}; // grid points per axis
};

SceneBounds sceneBounds(const fit::VotSpace& space);
SceneBounds sceneBounds(const fit::Volume& volume);

/// Column-major 4x4 matrices (OpenGL convention) for one camera, scene and image size.
struct CameraMatrices {
    std::array<double, 16> indexToClip{}; // projection * view * (index -> world)
    std::array<double, 16> clipToIndex{}; // its inverse: rays are rebuilt from it per pixel
    std::array<double, 3> eyeWorld{};     // eye position (perspective) or a point behind the view (ortho)
    double nearWorld = 0.0;               // near plane distance from the eye, world units
    double farWorld = 0.0;
    // The grid's axes form a left-handed set in world space (patient axes such as left-anterior-superior):
    // a box's faces then wind the other way on screen, so its back faces are the clockwise ones.
    bool mirrored = false;
};

/// Throws vots::fit::InputError for an invalid camera or image size.
CameraMatrices computeCameraMatrices(const Camera& camera, const SceneBounds& bounds, int width, int height);

/// Throws vots::fit::InputError naming the first field out of range or not finite.
void validateCamera(const Camera& camera);

} // namespace vots::render
