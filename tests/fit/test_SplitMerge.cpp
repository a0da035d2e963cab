// The merge across zone borders (white box, fit/src): trying only the faces that can meet a box not yet
// tried must reach the same cover as trying every face of every box, and leave no mergeable pair.
#include "SplitMerge.h"
#include "SyntheticFields.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace vots::fit;
using vots::test::sampleVolume;

namespace {

bool shareWholeFace(const Box& a, const Box& b) {
    for (int axis = 0; axis < 3; ++axis) {
        if (a.hi[axis] != b.lo[axis] && b.hi[axis] != a.lo[axis]) continue;
        bool same = true;
        for (int other = 0; other < 3; ++other)
            if (other != axis && (a.lo[other] != b.lo[other] || a.hi[other] != b.hi[other])) same = false;
        if (same) return true;
    }
    return false;
}

Box unite(const Box& a, const Box& b) {
    Box u;
    for (int axis = 0; axis < 3; ++axis) {
        u.lo[axis] = std::min(a.lo[axis], b.lo[axis]);
        u.hi[axis] = std::max(a.hi[axis], b.hi[axis]);
    }
    return u;
}

// Three zones along x, two along y and z, a smooth field with noise and empty corners, so the split
// leaves boxes of many sizes on every zone plane.
Volume zonesVolume() {
    std::mt19937 rng(7);
    std::normal_distribution<double> noise(0.0, 3.0);
    return sampleVolume({81, 50, 41}, [&](int x, int y, int z) {
        if (x + y < 12) return -1000.0;
        return 400.0 * std::sin(0.09 * x) * std::cos(0.13 * y - 0.07 * z) + 0.2 * x * z + noise(rng);
    });
}

} // namespace

TEST(SplitMerge, MergeAcrossZonesMatchesTryingEveryFaceAndLeavesNoMergeablePair) {
    const Volume volume = zonesVolume();
    const BoxFitter fitter(volume, 3, Certify::Cells);
    const EpsField eps(30.f);
    FitCounters counters;
    const BoxTester tester(fitter, eps, counters, nullptr);
    const CellMask mask(volume, -900.f);
    const FitControl control{2, nullptr, nullptr};

    std::vector<FittedBox> perZone = splitZones(mask, tester, control);
    std::vector<FittedBox> everyFace = perZone;
    mergeNeighbours(perZone, tester, control, ZONE_CELLS);
    mergeNeighbours(everyFace, tester, control);

    ASSERT_GT(perZone.size(), 100u) << "the field should need many boxes";
    ASSERT_EQ(perZone.size(), everyFace.size());
    for (std::size_t i = 0; i < perZone.size(); ++i)
        ASSERT_EQ(perZone[i].box, everyFace[i].box) << "box " << i;

    std::size_t crossing = 0, pairs = 0;
    for (std::size_t i = 0; i < perZone.size(); ++i) {
        const Box& a = perZone[i].box;
        for (int axis = 0; axis < 3; ++axis)
            if (a.lo[axis] / ZONE_CELLS != (a.hi[axis] - 1) / ZONE_CELLS) ++crossing;
        for (std::size_t j = i + 1; j < perZone.size(); ++j) {
            if (!shareWholeFace(a, perZone[j].box)) continue;
            ++pairs;
            EXPECT_FALSE(tester.test(unite(a, perZone[j].box)).accepted)
                << "boxes " << i << " and " << j << " could still merge";
        }
    }
    EXPECT_GT(crossing, 0u) << "some merges should cross a zone plane";
    EXPECT_GT(pairs, 0u);
}

// Taller than two merge slabs: the slabs are merged on their own threads, then across the slab planes.
TEST(SplitMerge, MergeAcrossZonesInSlabsIsTheSameOnAnyThreadCountAndLeavesNoMergeablePair) {
    std::mt19937 rng(11);
    std::normal_distribution<double> noise(0.0, 2.0);
    const Volume volume = sampleVolume({34, 27, 2 * MERGE_BAND_CELLS + 40}, [&](int x, int y, int z) {
        if (x + y < 6) return -1000.0;
        return 300.0 * std::sin(0.11 * x + 0.01 * z) * std::cos(0.13 * y) + 0.5 * z + noise(rng);
    });
    const BoxFitter fitter(volume, 3, Certify::Cells);
    const EpsField eps(30.f);
    FitCounters counters;
    const BoxTester tester(fitter, eps, counters, nullptr);
    const CellMask mask(volume, -900.f);

    const std::vector<FittedBox> split = splitZones(mask, tester, FitControl{2, nullptr, nullptr});
    std::vector<FittedBox> oneThread = split, twoThreads = split;
    mergeAcrossZones(oneThread, tester, FitControl{1, nullptr, nullptr});
    mergeAcrossZones(twoThreads, tester, FitControl{2, nullptr, nullptr});
    ASSERT_GT(oneThread.size(), 50u) << "the field should need many boxes";
    ASSERT_EQ(oneThread.size(), twoThreads.size());
    for (std::size_t i = 0; i < oneThread.size(); ++i)
        ASSERT_EQ(oneThread[i].box, twoThreads[i].box) << "box " << i;

    std::size_t crossingSlabs = 0;
    for (std::size_t i = 0; i < oneThread.size(); ++i) {
        const Box& a = oneThread[i].box;
        if (a.lo[2] / MERGE_BAND_CELLS != (a.hi[2] - 1) / MERGE_BAND_CELLS) ++crossingSlabs;
        for (std::size_t j = i + 1; j < oneThread.size(); ++j) {
            const Box& b = oneThread[j].box;
            bool overlap = true;
            for (int axis = 0; axis < 3; ++axis)
                if (a.hi[axis] <= b.lo[axis] || b.hi[axis] <= a.lo[axis]) overlap = false;
            EXPECT_FALSE(overlap) << "boxes " << i << " and " << j << " overlap";
            if (shareWholeFace(a, b)) {
                EXPECT_FALSE(tester.test(unite(a, b)).accepted)
                    << "boxes " << i << " and " << j << " could still merge";
            }
        }
    }
    EXPECT_GT(crossingSlabs, 0u) << "some merges should cross a slab plane";
}
