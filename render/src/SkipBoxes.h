// Skip boxes: Vot boxes grown over neighbours a culled Vot's bound also culls; empty blocks over background.
#pragma once

#include "VotWalkGrid.h"

#include "vots/render/GpuLayout.h"

#include <atomic>
#include <cstdint>
#include <vector>

namespace vots::render {

/// Cells a skip box may grow beyond its Vot's box on each side. Wider growth lets a culled Vot step over
/// more but costs more work per upload, which is why the growth runs after the first frame
/// (bench/RESULTS.md compares limits).
inline constexpr int MAX_SKIP_GROWTH = 16;

/// For every Vot, then every empty block, its box grown one cell layer at a
/// time (+x, +y, +z, -x, -y, -z in turn) by up to MAX_SKIP_GROWTH cells per side while the new layer
/// holds only background cells and, for a Vot, Vots whose upperBound is at most its own: where the
/// walk culls the Vot (or meets the empty block), it may step over the whole grown box. Empty blocks
/// may overlap once grown; each cell still names one block that contains it (cell indices from the
/// Vot count up are background). Returns an empty vector soon after `cancel` becomes true.
/// What the growth reads, owned by it, so that a new upload never waits for a cancelled growth.
struct SkipGrowthInput {
    VotWalkGrid grid;                // the walk grid: each cell's block, the empty blocks
    std::vector<CellBlock> votBoxes; // per Vot, in GPU order
    std::vector<float> votBounds;    // per Vot: upperBound
};

std::vector<CellBlock> growSkipBoxes(const SkipGrowthInput& input, const std::atomic<bool>& cancel);

} // namespace vots::render
