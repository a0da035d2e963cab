// Fast generation (DESIGN §4, "faster strategies"): disjoint boxes, so each pixel rasterises fewer Vots.
#include "SplitMerge.h"

#include "ParallelFor.h"

#include <algorithm>
#include <mutex>
#include <unordered_map>

namespace vots::fit {
namespace {

int longestAxis(const Box& box) {
    int axis = 0;
    for (int a = 1; a < 3; ++a)
        if (box.cells(a) > box.cells(axis)) axis = a;
    return axis;
}

void splitBrick(const Box& brick, const CellMask& mask, const BoxTester& tester, std::vector<FittedBox>& out,
                const FitControl& control) {
    std::vector<Box> stack;
    if (auto tight = mask.tightBox(brick)) stack.push_back(*tight);
    while (!stack.empty()) {
        control.checkCancel();
        const Box box = stack.back();
        stack.pop_back();
        BoxOutcome outcome = tester.test(box);
        if (outcome.accepted) {
            out.push_back({box, outcome});
            continue;
        }
        const int axis = longestAxis(box);
        const int mid = box.lo[axis] + box.cells(axis) / 2;
        Box first = box, second = box;
        first.hi[axis] = mid;
        second.lo[axis] = mid;
        for (const Box& child : {first, second})
            if (auto tight = mask.tightBox(child)) stack.push_back(*tight);
    }
}

/// A face of a box: the plane on `axis` plus the extents on the other two axes.
struct FaceKey {
    int axis, plane, lo1, hi1, lo2, hi2;
    friend bool operator==(const FaceKey&, const FaceKey&) = default;
};
struct FaceHash {
    std::size_t operator()(const FaceKey& k) const noexcept {
        std::size_t h = 1469598103934665603ull;
        for (int v : {k.axis, k.plane, k.lo1, k.hi1, k.lo2, k.hi2})
            h = (h ^ static_cast<std::size_t>(v)) * 1099511628211ull;
        return h;
    }
};

FaceKey faceOf(const Box& box, int axis, bool high) {
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    return {axis, high ? box.hi[axis] : box.lo[axis], box.lo[a1], box.hi[a1], box.lo[a2], box.hi[a2]};
}

} // namespace

std::vector<FittedBox> splitBricks(const CellMask& mask, const BoxTester& tester, const FitControl& control) {
    const auto cells = mask.cellDims();
    std::array<int, 3> bricks{};
    for (int a = 0; a < 3; ++a)
        bricks[a] = (cells[a] + BRICK_CELLS - 1) / BRICK_CELLS;
    const std::size_t brickCount = static_cast<std::size_t>(bricks[0]) * bricks[1] * bricks[2];
    std::vector<std::vector<FittedBox>> perBrick(brickCount);
    std::atomic<std::size_t> done{0};
    std::mutex progressMutex;
    parallelFor(brickCount, control.threads, [&](std::size_t b, int) {
        const int bx = static_cast<int>(b % static_cast<std::size_t>(bricks[0]));
        const int by =
            static_cast<int>((b / static_cast<std::size_t>(bricks[0])) % static_cast<std::size_t>(bricks[1]));
        const int bz = static_cast<int>(b / (static_cast<std::size_t>(bricks[0]) * bricks[1]));
        Box brick;
        const int index[3] = {bx, by, bz};
        for (int a = 0; a < 3; ++a) {
            brick.lo[a] = index[a] * BRICK_CELLS;
            brick.hi[a] = std::min(brick.lo[a] + BRICK_CELLS, cells[a]);
        }
        splitBrick(brick, mask, tester, perBrick[b], control);
        // Merging inside the brick first keeps most merge work parallel.
        mergeNeighbours(perBrick[b], tester, FitControl{1, nullptr, control.cancel});
        const std::size_t finished = done.fetch_add(1) + 1;
        if (control.progress) {
            std::lock_guard lock(progressMutex);
            control.progress(0.9 * static_cast<double>(finished) / static_cast<double>(brickCount), "split");
        }
    });
    std::vector<FittedBox> all;
    for (auto& v : perBrick)
        all.insert(all.end(), v.begin(), v.end());
    return all;
}

void mergeNeighbours(std::vector<FittedBox>& boxes, const BoxTester& tester, const FitControl& control) {
    std::vector<bool> alive(boxes.size(), true);
    std::unordered_map<FaceKey, std::size_t, FaceHash> lowFaces, highFaces;
    auto enter = [&](std::size_t i) {
        for (int a = 0; a < 3; ++a) {
            lowFaces[faceOf(boxes[i].box, a, false)] = i;
            highFaces[faceOf(boxes[i].box, a, true)] = i;
        }
    };
    auto leave = [&](std::size_t i) {
        for (int a = 0; a < 3; ++a) {
            lowFaces.erase(faceOf(boxes[i].box, a, false));
            highFaces.erase(faceOf(boxes[i].box, a, true));
        }
        alive[i] = false;
    };
    for (std::size_t i = 0; i < boxes.size(); ++i)
        enter(i);
    std::vector<std::size_t> work(boxes.size());
    for (std::size_t i = 0; i < work.size(); ++i)
        work[i] = i;
    while (!work.empty()) {
        control.checkCancel();
        const std::size_t i = work.back();
        work.pop_back();
        if (!alive[i]) continue;
        for (int a = 0; a < 3 && alive[i]; ++a)
            for (bool high : {true, false}) {
                // My high face meets a neighbour's low face at the same plane and extents, or vice versa.
                const auto& faces = high ? lowFaces : highFaces;
                const auto it = faces.find(faceOf(boxes[i].box, a, high));
                if (it == faces.end() || it->second == i) continue;
                const std::size_t j = it->second;
                Box merged = boxes[i].box;
                merged.lo[a] = std::min(boxes[i].box.lo[a], boxes[j].box.lo[a]);
                merged.hi[a] = std::max(boxes[i].box.hi[a], boxes[j].box.hi[a]);
                BoxOutcome outcome = tester.test(merged);
                if (!outcome.accepted) continue;
                leave(i);
                leave(j);
                boxes.push_back({merged, outcome});
                alive.push_back(true);
                enter(boxes.size() - 1);
                work.push_back(boxes.size() - 1);
                break;
            }
    }
    std::vector<FittedBox> kept;
    for (std::size_t i = 0; i < boxes.size(); ++i)
        if (alive[i]) kept.push_back(boxes[i]);
    boxes = std::move(kept);
}

} // namespace vots::fit
