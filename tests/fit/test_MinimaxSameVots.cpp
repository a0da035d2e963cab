// Minimax fits give the same Vots on any thread count and from a box cache; least squares gives its old Vots.
#include "MinimaxChecks.h"

#include "vots/fit/Fitter.h"
#include "vots/fit/Verify.h"

#include <gtest/gtest.h>

#include <zlib.h>

#include <cstring>
#include <string>

using namespace vots::fit;
using namespace vots::test;

namespace {

/// CRC-32 of the Vots as the file's records hold them (box, expansion point, err, coefficients).
std::uint32_t recordsCrc(const VotSpace& space) {
    uLong crc = crc32(0L, Z_NULL, 0);
    for (const Vot& v : space.vots) {
        unsigned char record[120];
        std::memcpy(record, v.box.lo.data(), 12);
        std::memcpy(record + 12, v.box.hi.data(), 12);
        std::memcpy(record + 24, v.p.data(), 12);
        std::memcpy(record + 36, &v.err, 4);
        std::memcpy(record + 40, v.c.data(), 80);
        crc = crc32(crc, record, sizeof record);
    }
    return static_cast<std::uint32_t>(crc);
}

void expectSameVots(const VotSpace& a, const VotSpace& b, const std::string& what) {
    ASSERT_EQ(a.vots.size(), b.vots.size()) << what;
    for (std::size_t i = 0; i < a.vots.size(); ++i) {
        ASSERT_EQ(a.vots[i].box, b.vots[i].box) << what << ", Vot " << i;
        ASSERT_EQ(a.vots[i].p, b.vots[i].p) << what << ", Vot " << i;
        ASSERT_EQ(a.vots[i].c, b.vots[i].c) << what << ", Vot " << i;
        ASSERT_EQ(a.vots[i].err, b.vots[i].err) << what << ", Vot " << i;
    }
}

} // namespace

TEST(Minimax, SameVotsOnOneAndTwoThreads) {
    const Volume volume = loadShared("cranium-quarter_64x64x108_int16.nrrd");
    const auto range = volume.valueRange();
    for (const Certify certify : {Certify::Samples, Certify::Cells}) {
        FitOptions o = options(0.02f * (range[1] - range[0]), 3, FitNorm::Minimax, certify);
        o.background = defaultBackground(volume);
        o.threads = 1;
        const FitResult one = fitVotSpace(volume, o);
        o.threads = 2;
        const FitResult two = fitVotSpace(volume, o);
        expectSameVots(one.space, two.space, std::string("certify ") + std::string(nameOf(certify)));
    }
}

TEST(Minimax, RefitsFromABoxCacheGiveTheVotsOfAFreshFit) {
    // What a search learned at one eps answers another only where the search there would end the same: the
    // Vots of every refit, coefficients included, are a fresh fit's, up and down the eps scale.
    const Volume volume = loadShared("mri-brain_33x41x25_int16.nrrd");
    const auto range = volume.valueRange();
    for (const Certify certify : {Certify::Samples, Certify::Cells}) {
        FitCache cache;
        std::size_t hits = 0;
        for (const float percent : {2.f, 5.f, 3.f, 1.f, 3.f}) {
            FitOptions o = options(percent / 100.f * (range[1] - range[0]), 3, FitNorm::Minimax, certify);
            o.background = defaultBackground(volume);
            const FitResult refit = fitVotSpace(volume, o, &cache);
            const FitResult fresh = fitVotSpace(volume, o);
            hits += refit.stats.cacheHits;
            const std::string what = std::string(nameOf(certify)) + " at " + std::to_string(percent) + " %";
            expectSameVots(refit.space, fresh.space, what);
            // Every sample within the new eps, by the verifier (independent of the fitter and its cache).
            EXPECT_TRUE(verifyVotSpace(refit.space, volume).ok) << what;
        }
        EXPECT_GT(hits, 0u);
    }
}

TEST(Minimax, ACellsRefitDownTheScaleOfTheQuarterCraniumIsAFreshFit) {
    // Whether a search prices the cell points before its samples are within bounds depends on eps, so a
    // record kept at 2 % could steer a refit at 1.7 % away from the fresh search: the CT's boxes, unlike the
    // small MRI's, meet that case (the server's slider goes down the scale like this).
    const Volume volume = loadShared("cranium-quarter_64x64x108_int16.nrrd");
    const auto range = volume.valueRange();
    FitCache cache;
    for (const float percent : {2.f, 1.7f}) {
        FitOptions o = options(percent / 100.f * (range[1] - range[0]), 3, FitNorm::Minimax, Certify::Cells);
        o.background = defaultBackground(volume);
        const FitResult refit = fitVotSpace(volume, o, &cache);
        const FitResult fresh = fitVotSpace(volume, o);
        expectSameVots(refit.space, fresh.space, "cells at " + std::to_string(percent) + " %");
    }
}

TEST(Minimax, LeastSquaresGivesTheVotsItGaveBeforeTheNormCouldBeChosen) {
    // CRC-32 of the records of `vots fit` before --fit-norm existed (the commit before it, same options).
    struct Golden {
        const char* file;
        float eps;
        int degree;
        Certify certify;
        bool background; // auto, or none
        bool focus;      // 30,30,50 radius 12, eps-focus 5
        std::size_t vots;
        std::uint32_t crc;
    };
    const Golden goldens[] = {
        {"cranium-quarter_64x64x108_int16.nrrd", 40.f, 3, Certify::Samples, true, false, 32956, 0x245a26f8u},
        {"cranium-quarter_64x64x108_int16.nrrd", 40.f, 3, Certify::Cells, true, false, 37654, 0x2c0a15deu},
        {"cranium-quarter_64x64x108_int16.nrrd", 25.f, 2, Certify::Samples, true, true, 87692, 0x72bd6da3u},
        {"mri-brain_33x41x25_int16.nrrd", 30.f, 1, Certify::Cells, false, false, 30720, 0xd3607839u},
        {"mri-brain_33x41x25_int16.nrrd", 12.f, 3, Certify::Samples, false, false, 27818, 0xf5e1849au},
    };
    for (const Golden& g : goldens) {
        const Volume volume = loadShared(g.file);
        FitOptions o = options(g.eps, g.degree, FitNorm::Lsq, g.certify);
        if (g.background) o.background = defaultBackground(volume);
        if (g.focus) o.focus = FocusRegion{{30.0, 30.0, 50.0}, 12.0, 5.f};
        const FitResult fit = fitVotSpace(volume, o);
        EXPECT_EQ(fit.space.vots.size(), g.vots) << g.file << " eps " << g.eps;
        EXPECT_EQ(recordsCrc(fit.space), g.crc) << g.file << " eps " << g.eps;
    }
}
