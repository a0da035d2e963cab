// Fast generation (docs/DESIGN.md §4, fast method): disjoint boxes, so each pixel rasterises fewer Vots.
#include "SplitMerge.h"

#include "ParallelFor.h"

#include "vots/fit/Error.h"

#include <absl/container/flat_hash_map.h>

#include <algorithm>
#include <cstdint>
#include <mutex>

namespace vots::fit {
namespace {

int longestAxis(const Box& box) {
    int axis = 0;
    for (int a = 1; a < 3; ++a)
        if (box.cells(a) > box.cells(axis)) axis = a;
    return axis;
}

void splitZone(const Box& zone, const CellMask& mask, const BoxTester& tester, std::vector<FittedBox>& out,
               const FitControl& control) {
    std::vector<Box> stack;
    if (auto tight = mask.tightBox(zone)) stack.push_back(*tight);
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
            if (auto tight = mask.tightBox(child)) {
                stack.push_back(*tight);
                tester.willTest(*tight);
            }
    }
}

// The live boxes by their low and by their high corner. A box that shares b's whole high face on an
// axis has b's low corner moved to b's high side on that axis as its own low corner; one that shares
// b's low face has b's high corner moved to b's low side as its high corner; disjoint boxes have distinct
// corners. So two hash maps find the one candidate per face in memory that follows the boxes, where a
// table of the box covering each cell would cost 4 bytes a cell (as much as the float samples) for the
// merge across zones.
class BoxCorners {
public:
    static constexpr std::uint32_t NONE = 0xffffffffu;

    explicit BoxCorners(const std::vector<FittedBox>& boxes) {
        mByLow.reserve(boxes.size());
        mByHigh.reserve(boxes.size());
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            // A merge's corners are corners of the boxes it joins, so checking these checks them all.
            for (int a = 0; a < 3; ++a)
                if (boxes[i].box.lo[a] < 0 || boxes[i].box.hi[a] >= 1 << BITS)
                    throw InputError("a box corner beyond 2^21 cells to merge");
            add(boxes[i].box, static_cast<std::uint32_t>(i));
        }
    }

    /// A live box as the maps find it: its index and the box itself, kept in the map's slot so that testing
    /// a face needs no second random read into the boxes (the merge across zones is bound by such reads).
    struct Found {
        std::uint32_t index = NONE;
        Box box;
    };
    /// The live box whose low corner is `corner`, or one with index NONE.
    Found withLow(const std::array<int, 3>& corner) const { return find(mByLow, corner, true); }
    /// The live box whose high corner is `corner`, or one with index NONE.
    Found withHigh(const std::array<int, 3>& corner) const { return find(mByHigh, corner, false); }

    /// Boxes i and j were replaced by box k.
    void merged(const Box& i, const Box& j, const Box& k, std::uint32_t kIndex) {
        for (const Box* gone : {&i, &j}) {
            mByLow.erase(keyOf(gone->lo));
            mByHigh.erase(keyOf(gone->hi));
        }
        add(k, kIndex);
    }

private:
    // The value: the box's index and its other corner (the key is one of its corners).
    struct Entry {
        std::uint32_t index;
        std::array<int, 3> other;
    };
    using Map = absl::flat_hash_map<std::uint64_t, Entry>;
    static constexpr int BITS = 21;
    // A corner packed into one integer: hashing and comparing it is a few instructions, where the array's
    // equality was a memcmp call, on the path a refit from a full cache spends most of its time in.
    static std::uint64_t keyOf(const std::array<int, 3>& corner) {
        return static_cast<std::uint64_t>(corner[0]) | static_cast<std::uint64_t>(corner[1]) << BITS |
               static_cast<std::uint64_t>(corner[2]) << (2 * BITS);
    }
    static Found find(const Map& map, const std::array<int, 3>& corner, bool cornerIsLow) {
        const auto it = map.find(keyOf(corner));
        if (it == map.end()) return {};
        const Entry& e = it->second;
        return {e.index, cornerIsLow ? Box{corner, e.other} : Box{e.other, corner}};
    }
    void add(const Box& box, std::uint32_t index) {
        mByLow[keyOf(box.lo)] = {index, box.hi};
        mByHigh[keyOf(box.hi)] = {index, box.lo};
    }
    Map mByLow, mByHigh;
};

// b's face on `axis` (high or low side) and n's opposite face are the same rectangle.
bool shareFace(const Box& b, const Box& n, int axis, bool high) {
    if (high ? n.lo[axis] != b.hi[axis] : n.hi[axis] != b.lo[axis]) return false;
    for (int a = 0; a < 3; ++a)
        if (a != axis && (n.lo[a] != b.lo[a] || n.hi[a] != b.hi[a])) return false;
    return true;
}

} // namespace

std::vector<FittedBox> splitZones(const CellMask& mask, const BoxTester& tester, const FitControl& control) {
    const auto cells = mask.cellDims();
    std::array<int, 3> zones{};
    for (int a = 0; a < 3; ++a)
        zones[a] = (cells[a] + ZONE_CELLS - 1) / ZONE_CELLS;
    const std::size_t zoneCount = static_cast<std::size_t>(zones[0]) * zones[1] * zones[2];
    std::vector<std::vector<FittedBox>> perZone(zoneCount);
    // A zone's split and merge work in one vector per thread, kept from zone to zone: vectors grown
    // afresh for every zone would fault in fresh pages again and again, most of a refit's page faults.
    std::vector<std::vector<FittedBox>> scratch(static_cast<std::size_t>(std::max(1, control.threads)));
    std::atomic<std::size_t> done{0};
    std::mutex progressMutex;
    parallelFor(zoneCount, control.threads, [&](std::size_t n, int thread) {
        const int ix = static_cast<int>(n % static_cast<std::size_t>(zones[0]));
        const int iy =
            static_cast<int>((n / static_cast<std::size_t>(zones[0])) % static_cast<std::size_t>(zones[1]));
        const int iz = static_cast<int>(n / (static_cast<std::size_t>(zones[0]) * zones[1]));
        Box zone;
        const int index[3] = {ix, iy, iz};
        for (int a = 0; a < 3; ++a) {
            zone.lo[a] = index[a] * ZONE_CELLS;
            zone.hi[a] = std::min(zone.lo[a] + ZONE_CELLS, cells[a]);
        }
        std::vector<FittedBox>& boxes = scratch[static_cast<std::size_t>(thread)];
        boxes.clear();
        splitZone(zone, mask, tester.leastSquaresOnly(), boxes, control);
        // Merging inside the zone first keeps most merge work parallel.
        mergeNeighbours(boxes, tester, FitControl{1, nullptr, control.cancel});
        perZone[n].assign(boxes.begin(), boxes.end());
        const std::size_t finished = done.fetch_add(1) + 1;
        if (control.progress) {
            std::lock_guard lock(progressMutex);
            control.progress(0.9 * static_cast<double>(finished) / static_cast<double>(zoneCount), "split");
        }
    });
    // One allocation, with room for the boxes the merge across zones adds: a vector that grows would
    // fault in its fresh pages again at every reallocation, on the fit's serial part.
    std::size_t total = 0;
    for (const auto& v : perZone)
        total += v.size();
    std::vector<FittedBox> all;
    all.reserve(total + total / 2);
    for (auto& v : perZone) {
        all.insert(all.end(), v.begin(), v.end());
        std::vector<FittedBox>().swap(v);
    }
    return all;
}

void mergeNeighbours(std::vector<FittedBox>& boxes, const BoxTester& tester, const FitControl& control,
                     int zoneCells) {
    const int cells = std::max(0, zoneCells);
    mergeNeighbours(boxes, tester, control, std::array<int, 3>{cells, cells, cells});
}

void mergeAcrossZones(std::vector<FittedBox>& boxes, const BoxTester& tester, const FitControl& control) {
    // Each box lies inside one zone, so inside one band.
    std::size_t bandCount = 0;
    for (const FittedBox& b : boxes)
        bandCount = std::max(bandCount, static_cast<std::size_t>(b.box.lo[2] / MERGE_BAND_CELLS) + 1);
    if (bandCount <= 1) return mergeNeighbours(boxes, tester, control, ZONE_CELLS);
    std::vector<std::vector<FittedBox>> bands(bandCount);
    for (const FittedBox& b : boxes)
        bands[static_cast<std::size_t>(b.box.lo[2] / MERGE_BAND_CELLS)].push_back(b);
    parallelFor(bandCount, control.threads, [&](std::size_t k, int) {
        mergeNeighbours(bands[k], tester, FitControl{1, nullptr, control.cancel}, ZONE_CELLS);
    });
    boxes.clear();
    for (auto& band : bands) {
        boxes.insert(boxes.end(), band.begin(), band.end());
        std::vector<FittedBox>().swap(band);
    }
    mergeNeighbours(boxes, tester, control, std::array<int, 3>{0, 0, MERGE_BAND_CELLS});
}

void mergeNeighbours(std::vector<FittedBox>& boxes, const BoxTester& tester, const FitControl& control,
                     const std::array<int, 3>& planeCells) {
    if (boxes.size() >= BoxCorners::NONE) throw InputError("too many boxes to merge");
    std::vector<bool> alive(boxes.size(), true);
    BoxCorners corners(boxes);
    const bool everyFace = planeCells[0] <= 0 && planeCells[1] <= 0 && planeCells[2] <= 0;
    auto onPlane = [&](int a, int coordinate) {
        return planeCells[a] > 0 && coordinate % planeCells[a] == 0;
    };
    auto onAnyPlane = [&](const Box& b) {
        for (int a = 0; a < 3; ++a)
            if (onPlane(a, b.lo[a]) || onPlane(a, b.hi[a])) return true;
        return false;
    };
    // A box from an earlier merge has already been tried against every neighbour it shares no plane
    // with and refused; only its faces on a plane can meet a box it has not been tried with. A box
    // this merge makes is new to all its neighbours.
    const std::size_t firstNew = everyFace ? 0 : boxes.size();
    auto faceIsNew = [&](std::size_t i, int a, bool high) {
        return i >= firstNew || onPlane(a, high ? boxes[i].box.hi[a] : boxes[i].box.lo[a]);
    };
    std::vector<std::size_t> work;
    work.reserve(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i)
        if (everyFace || onAnyPlane(boxes[i].box)) work.push_back(i);
    while (!work.empty()) {
        control.checkCancel();
        const std::size_t i = work.back();
        work.pop_back();
        if (!alive[i]) continue;
        // Every face's union first, so that their cache lookups are in flight together; nothing changes
        // until one of them is accepted, and then box i is gone.
        struct Candidate {
            std::uint32_t neighbour;
            Box merged;
        };
        std::array<Candidate, 6> candidates;
        int count = 0;
        const Box box = boxes[i].box;
        for (int a = 0; a < 3; ++a)
            for (bool high : {true, false}) {
                if (!faceIsNew(i, a, high)) continue;
                // The only box that can share this whole face has a corner on the face's plane.
                std::array<int, 3> corner = high ? box.lo : box.hi;
                corner[a] = high ? box.hi[a] : box.lo[a];
                const BoxCorners::Found n = high ? corners.withLow(corner) : corners.withHigh(corner);
                const std::uint32_t j = n.index;
                if (j == BoxCorners::NONE || j == i || !shareFace(box, n.box, a, high)) continue;
                Box merged = box;
                merged.lo[a] = std::min(box.lo[a], n.box.lo[a]);
                merged.hi[a] = std::max(box.hi[a], n.box.hi[a]);
                tester.willTest(merged);
                candidates[static_cast<std::size_t>(count++)] = {j, merged};
            }
        for (int c = 0; c < count; ++c) {
            const auto [j, merged] = candidates[static_cast<std::size_t>(c)];
            BoxOutcome outcome = tester.test(merged);
            if (!outcome.accepted) continue;
            alive[i] = alive[j] = false;
            boxes.push_back({merged, outcome});
            alive.push_back(true);
            corners.merged(boxes[i].box, boxes[j].box, merged, static_cast<std::uint32_t>(boxes.size() - 1));
            work.push_back(boxes.size() - 1);
            break;
        }
    }
    // Compacted in place, in the same order: a new vector of the survivors would be as many fresh pages
    // again.
    std::size_t keep = 0;
    for (std::size_t i = 0; i < boxes.size(); ++i)
        if (alive[i]) boxes[keep++] = boxes[i];
    boxes.resize(keep);
}

} // namespace vots::fit
