// What a rank does for one of rank 0's commands under `vots serve` (fit, draw, summarize), and the
// replies' wire form; see RankWork.cpp.
#pragma once

#include "RankCommands.h"

#include "vots/dist/RankPart.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/VotRenderer.h"

#include <string>
#include <vector>

namespace vots::dist {

/// What a FRAME command asks of one rank: its Vots (or planes) ready and its frame drawn. Returns the
/// frame; *readMs is the time of a read of the grid's planes or of a .vots file (0 when held), *drawMs
/// the frame's, with the upload of a fit made before it.
RankFrame drawPart(RankPart& part, const CommandBody& c, const std::string& path, render::VotRenderer& vots,
                   render::GridRenderer& grid, double* readMs, double* drawMs);

/// A drawn frame as rank 0 reads it from a DRAWN reply.
RankFrame rankFrameOf(const DrawnBody& body, const std::vector<char>& reply);

/// A rank's finished fit as the body of a FITTED reply.
FittedBody fittedBodyOf(const RankFit& done);

/// A rank > 0's reply to a command: its part, or the error that kept it from it.
std::vector<char> replyTo(MessageKind kind, const CommandBody& c, const std::string& path, RankPart& part,
                          render::VotRenderer* vots, render::GridRenderer* grid,
                          const std::string& noRenderer);

} // namespace vots::dist
