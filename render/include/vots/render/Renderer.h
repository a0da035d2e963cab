// The interface both renderers share (Vots and the sampled grid), so callers draw frames through one type.
#pragma once

#include "vots/render/Camera.h"
#include "vots/render/DisplayPass.h"
#include "vots/render/DisplaySettings.h"
#include "vots/render/FrameStats.h"
#include "vots/render/Image.h"
#include "vots/render/RenderMode.h"
#include "vots/render/Slab.h"

#include <array>
#include <exception>

namespace vots::render {

/// Thrown by a frame whose RenderOptions::abandoned answered true between two of its bands.
class FrameAbandoned : public std::exception {
public:
    const char* what() const noexcept override { return "frame abandoned: its client asked for another"; }
};

/// What a frame needs from a renderer once its data is uploaded. Every implementation needs a current
/// EglContext for its whole life, and throws fit::InputError for a mode it cannot draw.
class Renderer {
public:
    virtual ~Renderer() = default;

    virtual bool hasData() const = 0;
    virtual const SceneBounds& bounds() const = 0;
    /// The range of the values the renderer draws (its default display window).
    virtual std::array<float, 2> valueRange() const = 0;

    virtual FloatImage render(const Camera& camera, int width, int height, const RenderOptions& options) = 0;
    /// render() followed by the display pass (applyDisplay).
    RgbaImage renderRgba(const Camera& camera, int width, int height, const DisplaySettings& display,
                         const RenderOptions& options = RenderMode::Mip) {
        return applyDisplay(render(camera, width, height, options), display);
    }
    /// Times and counts of the last frame.
    virtual const FrameStats& lastFrameStats() const = 0;

protected:
    Renderer() = default;
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;
};

} // namespace vots::render
