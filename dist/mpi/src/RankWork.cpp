// What a rank does for one of rank 0's commands under `vots serve`, and the replies' wire form: shared by
// rank 0 (its own part of a fit or frame) and the other ranks (MpiFrameRanks.cpp's loop).
#include "RankWork.h"

#include "MpiPolling.h"

#include "vots/dist/CompositeOp.h"
#include "vots/dist/Failure.h"
#include "vots/fit/Error.h"

#include <chrono>
#include <stdexcept>

namespace vots::dist {
namespace {

double msSince(PollClock::time_point start) {
    return std::chrono::duration<double, std::milli>(PollClock::now() - start).count();
}

/// The norm a command names; an unknown one is a bad message.
fit::FitNorm normOf(const CommandBody& c) {
    if (c.norm != static_cast<std::int32_t>(fit::FitNorm::Lsq) &&
        c.norm != static_cast<std::int32_t>(fit::FitNorm::Minimax))
        throw BadRankMessage("a command with an unknown fit norm " + std::to_string(c.norm));
    return static_cast<fit::FitNorm>(c.norm);
}

} // namespace

RankFrame drawPart(RankPart& part, const CommandBody& c, const std::string& path, render::VotRenderer& vots,
                   render::GridRenderer& grid, double* readMs, double* drawMs) {
    const auto start = PollClock::now();
    *readMs = 0.0;
    if (c.frame.renderer == render::RendererKind::Grid) {
        *readMs = part.ensureGrid(path, c.volumeFrame, grid);
        grid.useNoDataValue(c.range[0]); // the whole volume's lowest finite sample, as one process draws
    } else if (c.votsFile) {
        *readMs = part.ensureVotsFile(path, compositesCutRays(c.frame.mode), vots);
    } else {
        const std::optional<float> fill = c.hasFill ? std::optional<float>(c.fill) : std::nullopt;
        part.uploadFit(path, c.volumeFrame, c.eps, c.degree, normOf(c), fill, vots);
    }
    RankFrame drawn = c.frame.renderer == render::RendererKind::Grid ? RankPart::drawGrid(c.frame, grid)
                                                                     : part.draw(c.frame, vots);
    *drawMs = msSince(start) - *readMs;
    return drawn;
}

namespace {

std::vector<char> drawnReply(const RankFrame& drawn, const RankPart& part, double readMs, double frameMs) {
    DrawnBody body;
    const bool fromGrid = drawn.source == RankSource::Grid;
    body.width = drawn.frame.width;
    body.height = drawn.frame.height;
    body.withLengths = drawn.lengths ? 1 : 0;
    body.fromGrid = fromGrid ? 1 : 0;
    body.withDisplayRange = drawn.displayRange ? 1 : 0;
    body.displayRange = drawn.displayRange.value_or(std::array<float, 2>{0.f, 0.f});
    body.votCount = fromGrid ? 0 : part.votCount();
    body.heldFitMs = fromGrid ? 0.0 : part.fitMs();
    body.readMs = readMs;
    body.frameMs = frameMs;
    std::vector<float> floats = drawn.frame.pixels;
    if (drawn.lengths)
        floats.insert(floats.end(), drawn.lengths->pixels.begin(), drawn.lengths->pixels.end());
    return messageOf(DRAWN, body, floats.data(), floats.size() * sizeof(float));
}

} // namespace

RankFrame rankFrameOf(const DrawnBody& body, const std::vector<char>& reply) {
    if (body.width < 0 || body.height < 0) throw BadRankMessage("a rank's frame has a negative size");
    const std::size_t pixels = static_cast<std::size_t>(body.width) * static_cast<std::size_t>(body.height);
    const std::vector<float> floats = floatTailOf(reply, pixels * (body.withLengths ? 2 : 1));
    const auto image = [&](std::size_t first) {
        const auto begin = floats.begin() + static_cast<std::ptrdiff_t>(first);
        return render::FloatImage{body.width, body.height,
                                  std::vector<float>(begin, begin + static_cast<std::ptrdiff_t>(pixels))};
    };
    RankFrame drawn{image(0), std::nullopt, body.fromGrid ? RankSource::Grid : RankSource::Vots,
                    std::nullopt};
    if (body.withLengths) drawn.lengths = image(pixels);
    if (body.withDisplayRange) drawn.displayRange = body.displayRange;
    return drawn;
}

FittedBody fittedBodyOf(const RankFit& done) {
    return {done.background.cells, done.background.valueSum, done.votCount, done.fitMs, done.heldFitMs};
}

/// A rank > 0's reply to a command: its part, or the error that kept it from it.
std::vector<char> replyTo(MessageKind kind, const CommandBody& c, const std::string& path, RankPart& part,
                          render::VotRenderer* vots, render::GridRenderer* grid,
                          const std::string& noRenderer) {
    try {
        switch (kind) {
        case SUMMARY:
            return messageOf(SUMMARIZED, part.summarize(path, c.volumeFrame));
        case FIT:
            return messageOf(
                FITTED, fittedBodyOf(part.fit(path, c.volumeFrame, c.eps, c.degree, normOf(c), c.range)));
        case FRAME: {
            if (!vots || !grid) throw std::runtime_error(noRenderer);
            double readMs = 0.0, frameMs = 0.0;
            const RankFrame drawn = drawPart(part, c, path, *vots, *grid, &readMs, &frameMs);
            return drawnReply(drawn, part, readMs, frameMs);
        }
        default:
            throw BadRankMessage("a command of unknown kind " + std::to_string(kind));
        }
    } catch (...) {
        const std::exception_ptr failure = std::current_exception();
        const std::string text = failureTextOf(failure);
        return messageOf(FAILED, FailedBody{static_cast<std::int32_t>(failureKindOf(failure))}, text.data(),
                         text.size());
    }
}

} // namespace vots::dist
