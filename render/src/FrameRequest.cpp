// The frame rules shared by `vots render` and GET /render: size text, default window, which renderer.
#include "vots/render/FrameRequest.h"

#include "vots/render/GridRenderer.h"
#include "vots/render/VotRenderer.h"

#include "vots/fit/Error.h"

#include <charconv>
#include <stdexcept>

namespace vots::render {
std::optional<int> parsePlainInt(std::string_view text) {
    if (text.empty() || text.size() > 9) return std::nullopt;
    int value = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc() || ptr != end) return std::nullopt;
    return value;
}

fit::FitOptions renderFitOptions(float eps, int degree, std::optional<float> background, fit::Certify certify,
                                 fit::FitNorm norm) {
    fit::FitOptions options;
    options.eps = eps;
    options.degree = degree;
    options.background = background;
    options.certify = certify;
    options.norm = norm;
    return options;
}

SizeParse parseFrameSize(std::string_view text, int maxSide) {
    SizeParse size;
    const auto x = text.find('x');
    if (x == std::string_view::npos) {
        size.problem = SizeProblem::NotWxH;
        return size;
    }
    const auto w = parsePlainInt(text.substr(0, x));
    const auto h = parsePlainInt(text.substr(x + 1));
    if (!w || !h) {
        size.problem = SizeProblem::NotWholeNumbers;
        return size;
    }
    size.width = *w;
    size.height = *h;
    if (*w < 1 || *h < 1 || *w > maxSide || *h > maxSide) size.problem = SizeProblem::OutOfRange;
    return size;
}

void applyProjection(FrameRequest& frame, std::optional<std::string_view> mode,
                     std::optional<std::string_view> renderer, std::optional<std::string_view> slab) {
    ModeName name;
    if (mode) name = parseModeName(*mode);
    frame.mode = name.mode;
    frame.renderer =
        renderer ? parseRendererName(*renderer) : name.impliedRenderer.value_or(RendererKind::Vots);
    if (name.impliedRenderer && frame.renderer != *name.impliedRenderer)
        throw fit::InputError("mode 'reference' is mip on the grid renderer; it cannot take renderer '" +
                              std::string(*renderer) + "'");
    if (frame.mode == RenderMode::Density && frame.renderer == RendererKind::Grid)
        throw fit::InputError("mode 'density' shows Vot sizes: it needs renderer 'vots'");
    frame.slab.reset();
    if (slab) frame.slab = parseSlab(*slab);
    if (frame.slab && frame.mode == RenderMode::Density)
        throw fit::InputError("mode 'density' shows the smallest Vot along each whole ray; it takes no slab");
}

DisplaySettings displayFor(const FrameRequest& frame, std::array<float, 2> fullRange) {
    if (frame.window) return *frame.window;
    return windowForRange(fullRange[0], fullRange[1], frame.colormap);
}

RgbaImage renderFrame(const FrameRequest& frame, VotRenderer* vots, GridRenderer* grid,
                      std::optional<std::array<float, 2>> volumeRange,
                      const std::function<bool()>& abandoned) {
    Renderer* const renderer = frame.renderer == RendererKind::Grid ? static_cast<Renderer*>(grid) : vots;
    if (!renderer) throw std::logic_error("renderFrame: no renderer for this frame");
    std::array<float, 2> range = volumeRange ? *volumeRange : renderer->valueRange();
    if (frame.mode == RenderMode::Density) range = vots->densityRange();
    RenderOptions options{frame.mode, frame.slab};
    options.abandoned = abandoned;
    return renderer->renderRgba(frame.camera, frame.width, frame.height, displayFor(frame, range), options);
}

} // namespace vots::render
