// N ranks' parts run in one process and composited give the frame one renderer draws from the union of
// their fits with the whole volume's fill, on a volume whose air differs between the ranks' cells.
#include "AirStepVolume.h"
#include "TempDir.h"

#include "vots/dist/CompositeOp.h"
#include "vots/dist/FrameComposite.h"
#include "vots/dist/RankPart.h"
#include "vots/dist/WholeFill.h"

#include "vots/fit/Fitter.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/fit/VotSpaceFile.h"
#include "vots/meta/FitMeta.h"
#include "vots/meta/VotSpaceRead.h"
#include "vots/render/EglContext.h"
#include "vots/render/VotRenderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace vots::test {
namespace {

constexpr float EPS = 20.f; // data units
constexpr int DEGREE = 3;
constexpr fit::FitNorm NORM = fit::FitNorm::Minimax;

/// The frame one process draws of the union of the ranks' fits (each of its cells' planes, with the
/// options RankPart fits with), shown with the whole volume's fill.
fit::VotSpace unionOfRankFits(const std::string& path, int ranks, std::array<float, 2> range,
                              std::optional<float> fill) {
    fit::VotSpace all;
    for (int r = 0; r < ranks; ++r) {
        const dist::RankCells cells = dist::cellsOfRankInVolume(path, r, ranks);
        const fit::PlanesOfGrid read =
            dist::loadPlanesOfCells(path, cells, std::nullopt, fit::SampleStorage::Source, "");
        fit::FitOptions options;
        options.eps = EPS;
        options.degree = DEGREE;
        options.background = fit::defaultBackground(range);
        options.certify = render::RENDER_FIT_CERTIFY;
        options.norm = NORM;
        fit::VotSpace space = fit::fitVotSpace(read.planes, options).space;
        dist::placeCellsFitInGrid(space, cells, read.whole);
        if (r == 0) {
            all = space;
            all.vots.clear();
        }
        all.vots.insert(all.vots.end(), space.vots.begin(), space.vots.end());
    }
    all.backgroundFill = fill;
    return all;
}

struct Ranks {
    std::vector<std::unique_ptr<dist::RankPart>> parts;
    std::vector<std::unique_ptr<render::VotRenderer>> renderers;
    std::vector<dist::RankFit> fits;
};

Ranks fitOnRanks(const std::string& path, int ranks, std::array<float, 2> range) {
    Ranks out;
    for (int r = 0; r < ranks; ++r) {
        out.parts.push_back(std::make_unique<dist::RankPart>(r, ranks, dist::RankSetup{}));
        out.renderers.push_back(std::make_unique<render::VotRenderer>());
        out.fits.push_back(out.parts.back()->fit(path, 0, EPS, DEGREE, NORM, range));
    }
    return out;
}

render::FloatImage composited(Ranks& ranks, const render::FrameRequest& frame) {
    std::optional<dist::FrameComposite> composite;
    for (std::size_t r = 0; r < ranks.parts.size(); ++r) {
        dist::RankFrame drawn = ranks.parts[r]->draw(frame, *ranks.renderers[r]);
        if (composite)
            composite->add(drawn);
        else
            composite.emplace(frame.mode, std::move(drawn));
    }
    return composite->finish();
}

double largestDifference(const render::FloatImage& a, const render::FloatImage& b) {
    double largest = 0.0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        if (std::isinf(a.pixels[i]) || std::isinf(b.pixels[i])) {
            if (a.pixels[i] != b.pixels[i]) return INFINITY;
            continue;
        }
        largest = std::max(largest, std::abs(double(a.pixels[i]) - double(b.pixels[i])));
    }
    return largest;
}

class RanksInOneProcess : public ::testing::Test {
protected:
    static void SetUpTestSuite() { context = render::EglContext::create(&contextError); }
    static void TearDownTestSuite() { context.reset(); }
    /// The air-step volume written to the test's folder, its value range, and the anterior 128x128 frame.
    void SetUp() override {
        ASSERT_TRUE(context) << "the ranks' parts draw with a headless EGL context: " << contextError;
        path = dir.file("air-step.nrrd");
        writeAirStepVolume(path);
        range = fit::loadVolume(path).valueRange();
        frame.camera = render::cameraForView(render::ViewPreset::Anterior);
        frame.width = frame.height = 128;
    }
    static std::unique_ptr<render::EglContext> context;
    static std::string contextError;
    TempDir dir;
    std::string path;
    std::array<float, 2> range{0.f, 0.f};
    render::FrameRequest frame;
};
std::unique_ptr<render::EglContext> RanksInOneProcess::context;
std::string RanksInOneProcess::contextError;

TEST_F(RanksInOneProcess, CompositeTheFrameOfTheUnionOfTheirFitsWithTheWholeVolumesFill) {
    for (const int count : {2, 3}) {
        Ranks ranks = fitOnRanks(path, count, range);
        std::vector<dist::BackgroundSums> sums;
        for (const dist::RankFit& f : ranks.fits)
            sums.push_back(f.background);
        const std::optional<float> fill = dist::wholeVolumeFill(sums);
        ASSERT_TRUE(fill);
        // The volume tells the fills apart: the lowest rank's own air is not the whole's.
        EXPECT_NE(dist::wholeVolumeFill({sums.front()}), fill) << count << " ranks";
        for (int r = 0; r < count; ++r)
            ranks.parts[static_cast<std::size_t>(r)]->uploadFit(
                path, 0, EPS, DEGREE, NORM, fill, *ranks.renderers[static_cast<std::size_t>(r)]);

        render::VotRenderer one;
        one.upload(unionOfRankFits(path, count, range, fill));
        for (const render::RenderMode mode :
             {render::RenderMode::Mip, render::RenderMode::MinIp, render::RenderMode::Aip}) {
            frame.mode = mode;
            const render::FloatImage expected = one.render(frame.camera, frame.width, frame.height, mode);
            const render::FloatImage got = composited(ranks, frame);
            ASSERT_EQ(got.pixels.size(), expected.pixels.size());
            const std::string what =
                std::string(render::renderModeName(mode)) + " on " + std::to_string(count) + " ranks";
            if (mode == render::RenderMode::Aip) {
                // The mean's integrals are summed per rank in double and divided once: a float rounding
                // apart from the walk's one sum along the whole ray.
                EXPECT_LE(largestDifference(got, expected), 1e-6 * (range[1] - range[0])) << what;
            } else {
                EXPECT_EQ(got.pixels, expected.pixels) << what; // bit for bit
            }
        }
    }
}

TEST_F(RanksInOneProcess, EachRanksOwnFillWouldChangeTheMinipOfThisVolume) {
    frame.mode = render::RenderMode::MinIp;

    Ranks whole = fitOnRanks(path, 2, range);
    Ranks own = fitOnRanks(path, 2, range);
    const std::optional<float> fill =
        dist::wholeVolumeFill({whole.fits[0].background, whole.fits[1].background});
    for (std::size_t r = 0; r < 2; ++r) {
        whole.parts[r]->uploadFit(path, 0, EPS, DEGREE, NORM, fill, *whole.renderers[r]);
        own.parts[r]->uploadFit(path, 0, EPS, DEGREE, NORM, dist::wholeVolumeFill({own.fits[r].background}),
                                *own.renderers[r]);
    }
    EXPECT_NE(composited(own, frame).pixels, composited(whole, frame).pixels)
        << "a volume whose ranks' air differs shows the fill each rank draws with";
}

TEST_F(RanksInOneProcess, DrawAVotsFileAsOneProcessDrawsIt) {
    fit::FitOptions options;
    options.eps = EPS;
    options.certify = render::RENDER_FIT_CERTIFY;
    const fit::Volume whole = fit::loadVolume(path);
    options.background = fit::defaultBackground(range);
    fit::FitResult fitted = fit::fitVotSpace(whole, options); // boxes across the ranks' faces
    fit::VotSpace& space = fitted.space;
    // The meta block as `vots fit` writes it: each rank's reader restores the fill from it.
    meta::FitProvenance provenance;
    provenance.volume = &whole;
    provenance.options = options;
    provenance.stats = fitted.stats;
    provenance.backgroundFill = space.backgroundFill;
    space.metaJson = meta::buildFitMeta(provenance);
    const std::string file = dir.file("air-step.vots");
    fit::writeVotSpaceFile(file, space);
    ASSERT_EQ(meta::readVotSpaceFile(file).backgroundFill, space.backgroundFill);
    const dist::RankSetup setup;
    render::VotRenderer one;
    one.upload(space);
    frame.camera = render::cameraForView(render::ViewPreset::Left);
    for (const render::RenderMode mode : {render::RenderMode::Mip, render::RenderMode::Density}) {
        frame.mode = mode;
        Ranks ranks;
        for (int r = 0; r < 3; ++r) {
            ranks.parts.push_back(std::make_unique<dist::RankPart>(r, 3, setup));
            ranks.renderers.push_back(std::make_unique<render::VotRenderer>());
            ranks.parts.back()->ensureVotsFile(file, dist::compositesCutRays(mode), *ranks.renderers.back());
        }
        // Each Vot is drawn by the one rank whose cells its box starts in: the max (the smallest box) over
        // the ranks is the whole file's, bit for bit.
        EXPECT_EQ(composited(ranks, frame).pixels,
                  one.render(frame.camera, frame.width, frame.height, mode).pixels)
            << render::renderModeName(mode);
    }
}

} // namespace
} // namespace vots::test
