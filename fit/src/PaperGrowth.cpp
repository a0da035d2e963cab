// Seed-and-grow, faithful to the paper: extend one face by one layer, keep it if F(T) <= eps, until stuck.
#include "PaperGrowth.h"

#include "ParallelFor.h"

#include <algorithm>
#include <mutex>

namespace vots::fit {
namespace {

FittedBox growSeed(const Box& seed, const std::array<int, 3>& pointDims, const BoxTester& tester) {
    FittedBox current{seed, tester.test(seed)};
    bool blocked[6] = {false, false, false, false, false, false};
    bool grew = true;
    while (grew) {
        grew = false;
        // Faces in the fixed order +x, -x, +y, -y, +z, -z, one layer per attempt.
        for (int face = 0; face < 6; ++face) {
            if (blocked[face]) continue;
            const int axis = face / 2;
            const bool high = face % 2 == 0;
            Box candidate = current.box;
            if (high) {
                if (candidate.hi[axis] + 1 >= pointDims[axis]) {
                    blocked[face] = true;
                    continue;
                }
                ++candidate.hi[axis];
            } else {
                if (candidate.lo[axis] == 0) {
                    blocked[face] = true;
                    continue;
                }
                --candidate.lo[axis];
            }
            BoxOutcome outcome = tester.test(candidate);
            if (outcome.accepted) {
                current = {candidate, outcome};
                grew = true;
            } else {
                blocked[face] = true;
            }
        }
    }
    return current;
}

/// Sorts by box and keeps one candidate per box: neighbouring seeds often grow into the same box.
void removeDuplicateBoxes(std::vector<FittedBox>& boxes) {
    auto less = [](const FittedBox& a, const FittedBox& b) {
        return a.box.lo != b.box.lo ? a.box.lo < b.box.lo : a.box.hi < b.box.hi;
    };
    std::sort(boxes.begin(), boxes.end(), less);
    boxes.erase(std::unique(boxes.begin(), boxes.end(),
                            [](const FittedBox& a, const FittedBox& b) { return a.box == b.box; }),
                boxes.end());
}

} // namespace

std::vector<FittedBox> growSeeds(const CellMask& mask, const BoxTester& tester, const FitControl& control) {
    const auto cells = mask.cellDims();
    const std::array<int, 3> pointDims{cells[0] + 1, cells[1] + 1, cells[2] + 1};
    const std::size_t layers = static_cast<std::size_t>(cells[2]);
    std::vector<std::vector<FittedBox>> perLayer(layers);
    std::atomic<std::size_t> done{0};
    std::mutex progressMutex;
    parallelFor(layers, control.threads, [&](std::size_t k, int) {
        auto& out = perLayer[k];
        for (int j = 0; j < cells[1]; ++j)
            for (int i = 0; i < cells[0]; ++i) {
                if (mask.isBackground(i, j, static_cast<int>(k))) continue;
                control.checkCancel();
                const Box seed{{i, j, static_cast<int>(k)}, {i + 1, j + 1, static_cast<int>(k) + 1}};
                out.push_back(growSeed(seed, pointDims, tester));
            }
        removeDuplicateBoxes(out);
        const std::size_t finished = done.fetch_add(1) + 1;
        if (control.progress) {
            std::lock_guard lock(progressMutex);
            control.progress(0.9 * static_cast<double>(finished) / static_cast<double>(layers), "grow");
        }
    });
    std::vector<FittedBox> all;
    for (auto& v : perLayer)
        all.insert(all.end(), v.begin(), v.end());
    removeDuplicateBoxes(all);
    return all;
}

} // namespace vots::fit
