// The messages of `vots serve` under mpirun: rank 0's commands and the other ranks' replies, each a
// RankMessage of one kind with a fixed body.
#pragma once

#include "vots/dist/RankMessage.h"
#include "vots/dist/RankPart.h"

#include "vots/render/FrameRequest.h"

#include <array>
#include <cstdint>

namespace vots::dist {

inline constexpr int COMMAND_TAG = 7101;
inline constexpr int REPLY_TAG = 7102;

/// The kinds of message; commands go to the other ranks, replies come back.
enum MessageKind : std::uint32_t {
    QUIT = 1,    // command: leave the loop (answered QUIT_TAKEN)
    ALIVE = 2,   // command: rank 0's heartbeat (not answered)
    SUMMARY = 3, // command: summarize the volume (answered SUMMARIZED)
    FIT = 4,     // command: fit the cells (answered FITTED)
    FRAME = 5,   // command: draw the frame (answered DRAWN)
    QUIT_TAKEN = 101,
    SUMMARIZED = 102,
    FITTED = 103,
    DRAWN = 104,
    FAILED = 105, // any command: the tail is the error's text
};

/// Every command's body; the tail is the volume's (or .vots file's) path.
struct CommandBody {
    render::FrameRequest frame;           // FRAME
    float eps = 0.f;                      // FIT, FRAME of the Vots: RankPart::cellsFitId's
    std::int32_t degree = 3;              // likewise
    std::int32_t norm = 0;                // likewise: fit::FitNorm
    std::array<float, 2> range{0.f, 0.f}; // FIT: the whole volume's min and max
    std::int32_t votsFile = 0;            // FRAME: the path is a .vots file's
    std::int32_t hasFill = 0;             // FRAME of a fit: the whole volume's fill (wholeVolumeFill)
    float fill = 0.f;
    std::int32_t volumeFrame = 0; // SUMMARY, FIT, FRAME: the 3D volume of a 4D file the path names
};

struct FailedBody {
    std::int32_t kind = 0; // FailureKind
};

struct FittedBody {
    std::uint64_t backgroundCells = 0;
    double backgroundValueSum = 0.0;
    std::uint64_t votCount = 0;
    double fitMs = 0.0;
    double heldFitMs = 0.0;
};

/// The tail: the frame's floats, then the aip's lengths (withLengths).
struct DrawnBody {
    std::int32_t width = 0;
    std::int32_t height = 0;
    std::int32_t withLengths = 0;
    std::int32_t fromGrid = 0;
    std::int32_t withDisplayRange = 0;
    std::array<float, 2> displayRange{0.f, 0.f}; // RankFrame::displayRange (withDisplayRange)
    std::uint64_t votCount = 0;                  // of the Vots drawn (0 for the grid)
    double readMs = 0.0;    // a read of the grid's planes or of a .vots file (0 when held)
    double heldFitMs = 0.0; // what the fit the frame was drawn from took
    double frameMs = 0.0;
};

struct EmptyBody {
    std::int32_t unused = 0;
};

} // namespace vots::dist
