// turntableCamera: evenly spaced azimuths, kept inside the camera's [-360, 360].
#include "vots/render/Turntable.h"

#include <stdexcept>

namespace vots::render {

Camera turntableCamera(const Camera& start, int frames, int index, std::optional<double> elevationDeg) {
    if (frames < 1 || index < 0 || index >= frames) throw std::invalid_argument("turntableCamera: bad index");
    Camera camera = start;
    double azimuth = start.azimuthDeg + index * (360.0 / frames);
    if (azimuth > 360.0) azimuth -= 360.0;
    camera.azimuthDeg = azimuth;
    if (elevationDeg) camera.elevationDeg = *elevationDeg;
    return camera;
}

} // namespace vots::render
