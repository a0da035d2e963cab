// render_bench: steady-state frame times of Vot MIP (walk, raster and splat strategies) vs the reference
// ray caster, measured interleaved in one run, as markdown rows.
//
//   render_bench VOLUME [--vots FILE | --eps-percent P[,P...] | --eps E] [--degree N] [--fit-norm N] [--size
//   N]
//                [--frames N] [--warmup N] [--strategy both|walk|raster]
//                [--walk-shader auto|fragment|compute] [--no-cull] [--bands] [--png-dir DIR]
// Each round renders one frame with every renderer being compared (reference, raster, walk), so load
// from other processes hits all of them alike; the table gives per-renderer medians over --frames
// rounds after --warmup rounds, each frame glFinish-synchronised, and the ratios of those medians.
// Readback (R32F), the display pass (on the CPU) and PNG encoding are timed separately for the default
// strategy. Prints LP_NUM_THREADS and the GL renderer. --png-dir writes each view's images there.
#include "BenchTiming.h"

#include "vots/fit/Error.h"
#include "vots/fit/Fitter.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/fit/VotSpaceFile.h"
#include "vots/meta/VotSpaceRead.h"
#include "vots/render/Camera.h"
#include "vots/render/CameraText.h"
#include "vots/render/DisplayPass.h"
#include "vots/render/EglContext.h"
#include "vots/render/FrameRequest.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/Png.h"
#include "vots/render/VotRenderer.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

namespace {

using vots::bench::Clock;
using vots::bench::interleavedMedians;
using vots::bench::median;
using vots::bench::msOf;
using vots::render::VotRenderer;

// Pixels where two MIP images differ by more than tol (finite vs non-finite counts as different).
std::size_t countDifferent(const vots::render::FloatImage& a, const vots::render::FloatImage& b, float tol) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        const float x = a.pixels[i], y = b.pixels[i];
        if (std::isfinite(x) != std::isfinite(y) || (std::isfinite(x) && std::abs(x - y) > tol)) ++n;
    }
    return n;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"Vot MIP (walk, raster; with --splat the CPU splat) vs reference ray caster frame times"};
    std::string volumePath, votsPath, strategyName = "both", pngDir, walkShaderName = "auto";
    std::vector<double> epsPercents;
    double epsAbs = 0.0;
    int degree = 3, size = 512, frames = 11, warmup = 2;
    bool noCull = false;
    bool noReference = false;
    std::vector<std::string> onlyViews;
    app.add_option("volume", volumePath, "volume file (reference renderer, and fitting)")->required();
    app.add_option("--vots", votsPath, ".vots file to render instead of fitting");
    app.add_option("--eps-percent", epsPercents, "fit at these percentages of the value range (comma list)")
        ->delimiter(',');
    app.add_option("--eps", epsAbs, "fit at this absolute eps (data units)");
    app.add_option("--degree", degree, "fit degree");
    std::string norm{vots::fit::nameOf(vots::fit::DEFAULT_FIT_NORM)};
    app.add_option("--fit-norm", norm, "fit norm: minimax or lsq (docs/DESIGN.md §3)")
        ->check(CLI::IsMember(vots::fit::acceptedNames<vots::fit::FitNorm>()));
    app.add_option("--size", size, "image side in pixels");
    app.add_option("--frames", frames, "timed rounds (median over them)");
    app.add_option("--warmup", warmup, "untimed rounds first");
    app.add_option("--strategy", strategyName, "Vot MIP strategies to time: both, walk or raster")
        ->check(CLI::IsMember({"both", "walk", "raster"}));
    app.add_option(
           "--walk-shader", walkShaderName,
           "stage that runs the walk: auto (compute on a GPU, fragment on llvmpipe), fragment or compute")
        ->check(CLI::IsMember({"auto", "fragment", "compute"}));
    bool bands = false;
    app.add_flag("--bands", bands,
                 "also time the walk drawn in bands that ask to go on, as the viewer's stills are (never "
                 "abandoned), in the same rounds");
    bool splat = false;
    app.add_flag(
        "--splat", splat,
        "also time the MIP splat on the CPU's cores (VotRenderer::Strategy::Splat) in the same rounds, "
        "against the walk");
    app.add_flag("--no-cull", noCull, "no bound culling (raster draws every Vot, walk evaluates every Vot)");
    app.add_option("--view", onlyViews, "time only these views (anterior, oblique, persp; comma list)")
        ->delimiter(',');
    app.add_flag("--no-reference", noReference,
                 "do not time the reference ray caster (for profiling the Vot MIP alone)");
    app.add_option("--png-dir", pngDir, "write reference / raster / walk PNGs of each view here");
    CLI11_PARSE(app, argc, argv);
    const bool timeWalk = strategyName != "raster", timeRaster = strategyName != "walk";

    try {
        auto context = vots::render::EglContext::createOrThrow();
        const vots::fit::Volume volume = vots::fit::loadVolume(volumePath);
        const auto range = volume.valueRange();
        vots::render::GridRenderer grid;
        if (!noReference) grid.upload(volume); // a 3000-slice grid is 1.5 GB of texture: only when timed
        const char* threads = std::getenv("LP_NUM_THREADS");
        std::cout << "renderer: " << context->renderer()
                  << ", LP_NUM_THREADS=" << (threads ? threads : "(unset)") << ", volume " << volumePath
                  << " " << volume.dims[0] << "x" << volume.dims[1] << "x" << volume.dims[2] << ", " << size
                  << "x" << size << ", medians of " << frames << " interleaved rounds after " << warmup
                  << ", culling " << (noCull ? "off" : "on") << ", walk shader " << walkShaderName << "\n\n";
        std::cout
            << "| eps | view | Vots | strategy used | reference ms | raster ms | walk ms | ref / walk | "
               "raster / walk | pixels walk != raster | readback ms | display ms | PNG ms | bounds "
               "ahead ms |\n"
               "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";

        std::vector<double> epsList;
        if (!votsPath.empty())
            epsList.push_back(-1.0);
        else if (epsAbs > 0)
            epsList.push_back(epsAbs);
        else
            for (double p : epsPercents.empty() ? std::vector<double>{1.0} : epsPercents)
                epsList.push_back(p * 0.01 * (range[1] - range[0]));

        for (const double epsWanted : epsList) {
            vots::fit::VotSpace space;
            double fitSeconds = 0.0, eps = epsWanted;
            if (epsWanted < 0) {
                space = vots::meta::readVotSpaceFile(votsPath);
                eps = space.eps;
            } else {
                const vots::fit::FitOptions options = vots::render::renderFitOptions(
                    static_cast<float>(eps), degree, vots::fit::defaultBackground(volume),
                    vots::render::RENDER_FIT_CERTIFY, vots::fit::parseName<vots::fit::FitNorm>(norm));
                const auto t0 = Clock::now();
                space = vots::fit::fitVotSpace(volume, options).space;
                fitSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
            }
            VotRenderer walk, raster, splatter;
            // Each set before its upload: a splat's upload leaves the walk's grid for the first frame that
            // walks.
            walk.setStrategy(VotRenderer::Strategy::Walk);
            raster.setStrategy(VotRenderer::Strategy::Raster);
            splatter.setStrategy(VotRenderer::Strategy::Splat);
            const double splatUploadMs = splat ? msOf([&] { splatter.upload(space); }) : NAN;
            const double walkUploadMs = msOf([&] { walk.upload(space); });
            const double rasterUploadMs = msOf([&] { raster.upload(space); });
            walk.setCulling(!noCull);
            if (const auto shader = vots::render::parseWalkShader(walkShaderName))
                walk.setWalkShader(*shader);
            raster.setCulling(!noCull);
            // The steady state: what the first frame of a Vot-Space starts in the background is done.
            const double pendingMs = msOf([&] { walk.finishPendingWork(); });
            std::cerr << "eps " << eps << ": " << space.vots.size() << " Vots, fit " << fitSeconds
                      << " s, upload " << walkUploadMs << " ms (walk), " << rasterUploadMs << " ms (raster), "
                      << splatUploadMs << " ms (splat), walk skip boxes after the first frame " << pendingMs
                      << " ms\n";
            const bool walks = walk.mipStrategy() == VotRenderer::Strategy::Walk;

            const std::pair<const char*, const char*> views[] = {
                {"anterior", "anterior"},
                {"oblique", "az=30,el=20,zoom=1,pan=0:0,proj=ortho,fov=30"},
                {"persp", "az=-40,el=15,zoom=1.5,proj=persp,fov=40"}};
            for (const auto& [name, text] : views) {
                const vots::render::Camera camera = vots::render::parseCamera(text);
                if (!onlyViews.empty() &&
                    std::find(onlyViews.begin(), onlyViews.end(), name) == onlyViews.end())
                    continue;
                std::vector<std::function<void()>> fns{[&] {
                    if (!noReference) grid.render(camera, size, size);
                }};
                if (timeRaster) fns.emplace_back([&] { raster.render(camera, size, size); });
                if (timeWalk) fns.emplace_back([&] { walk.render(camera, size, size); });
                vots::render::RenderOptions banded;
                banded.abandoned = [] { return false; };
                if (timeWalk && bands) fns.emplace_back([&] { walk.render(camera, size, size, banded); });
                if (timeWalk && splat) fns.emplace_back([&] { splatter.render(camera, size, size); });
                const std::vector<double> ms = interleavedMedians(warmup, frames, fns);
                const double refMs = noReference ? NAN : ms[0];
                const double rasterMs = timeRaster ? ms[1] : NAN;
                const std::size_t extra = (bands ? 1 : 0) + (splat ? 1 : 0);
                const double walkMs = timeWalk ? ms[fns.size() - 1 - extra] : NAN;
                if (timeWalk && bands)
                    std::printf("walk in bands, %s: %.1f ms against %.1f ms whole (%.3f)\n", name,
                                ms[fns.size() - extra], walkMs, ms[fns.size() - extra] / walkMs);
                if (timeWalk && splat) {
                    const auto a = walk.render(camera, size, size), b = splatter.render(camera, size, size);
                    std::printf("splat, %s: %.1f ms against the walk's %.1f ms (walk / splat %.2f), pixels "
                                "splat != walk (1e-3 of the range): %zu\n",
                                name, ms.back(), walkMs, walkMs / ms.back(),
                                countDifferent(a, b, 1e-3f * float(range[1] - range[0])));
                }

                VotRenderer& main = timeWalk ? walk : raster;
                std::vector<double> readback, ahead;
                for (int i = 0; i < 5; ++i) {
                    (void)main.render(camera, size, size);
                    readback.push_back(main.lastFrameStats().readbackMs);
                    ahead.push_back(main.lastFrameStats().boundsAheadMs);
                }
                const auto display = vots::render::windowForRange(range[0], range[1]);
                vots::render::RgbaImage rgba;
                std::vector<double> displayMs, pngMs;
                for (int i = 0; i < 5; ++i) {
                    const vots::render::FloatImage frame = main.render(camera, size, size);
                    displayMs.push_back(msOf([&] { rgba = vots::render::applyDisplay(frame, display); }));
                    pngMs.push_back(msOf([&] { (void)vots::render::encodePng(rgba); }));
                }
                std::string differ = "-";
                if (timeWalk && timeRaster) {
                    const auto a = walk.render(camera, size, size), b = raster.render(camera, size, size);
                    differ = std::to_string(countDifferent(a, b, 1e-3f * float(range[1] - range[0])));
                    if (!pngDir.empty()) {
                        const std::string stem =
                            pngDir + "/eps" + std::to_string(int(std::lround(eps))) + "_" + name;
                        vots::render::writePng(stem + "_walk.png", vots::render::applyDisplay(a, display));
                        vots::render::writePng(stem + "_raster.png", vots::render::applyDisplay(b, display));
                        if (!noReference) // the grid is uploaded only when timed
                            vots::render::writePng(
                                stem + "_reference.png",
                                vots::render::applyDisplay(grid.render(camera, size, size), display));
                    }
                }
                std::printf("| %.4g | %s | %zu | %s | %.1f | %.1f | %.1f | %.2f | %.2f | %s | %.2f | %.2f | "
                            "%.1f | %.2f |\n",
                            eps, name, space.vots.size(),
                            timeWalk ? (walks ? "walk" : "raster (fallback)") : "raster", refMs, rasterMs,
                            walkMs, refMs / walkMs, rasterMs / walkMs, differ.c_str(), median(readback),
                            median(displayMs), median(pngMs), median(ahead));
                std::fflush(stdout);
            }
        }
    } catch (const std::exception& e) {
        std::cerr << "render_bench: " << e.what() << '\n';
        return 1;
    }
    return 0;
}
