// projection_bench: frame times of every projection (mip, minip, aip), Vots against the grid, with and
// without a thick slab, interleaved in one run, as markdown rows.
//
//   projection_bench VOLUME --vots FILE [--size N] [--frames N] [--warmup N] [--cam TEXT] [--slab O,T]
// Each round draws one frame of every (mode, renderer, slab) combination, so load from other processes
// hits all of them alike; each frame is glFinish-synchronised (FloatImage readback included). The
// ratios are against the Vot MIP of the same slab setting.
#include "BenchTiming.h"

#include "vots/fit/Error.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/fit/VotSpaceFile.h"
#include "vots/meta/VotSpaceRead.h"
#include "vots/render/CameraText.h"
#include "vots/render/EglContext.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/Slab.h"
#include "vots/render/VotRenderer.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    using namespace vots::render;
    CLI::App app{"Frame times of mip, minip and aip: Vots against the grid, with and without a slab"};
    std::string volumePath, votsPath, cam = "az=30,el=20", slabText = "0,20";
    int size = 512, frames = 7, warmup = 1;
    app.add_option("volume", volumePath, "the volume (grid renderer)")->required();
    app.add_option("--vots", votsPath, "its fitted .vots file (Vot renderer)")->required();
    app.add_option("--size", size, "image side in pixels");
    app.add_option("--frames", frames, "timed rounds (median over them)");
    app.add_option("--warmup", warmup, "untimed rounds first");
    app.add_option("--cam", cam, "camera text, as `vots render --cam`");
    app.add_option("--slab", slabText, "the slab timed beside whole rays, OFFSET,THICKNESS in mm");
    CLI11_PARSE(app, argc, argv);
    try {
        auto context = EglContext::createOrThrow();
        const Camera camera = parseCamera(cam);
        const Slab slab = parseSlab(slabText);
        VotRenderer vots;
        vots.upload(vots::meta::readVotSpaceFile(votsPath));
        vots.render(camera, size, size);
        vots.finishPendingWork(); // the steady state: skip boxes grown
        GridRenderer grid;
        grid.upload(vots::fit::loadVolume(volumePath));
        const char* threads = std::getenv("LP_NUM_THREADS");
        std::cout << "renderer: " << context->renderer()
                  << ", LP_NUM_THREADS=" << (threads ? threads : "(unset)") << ", " << volumePath << ", cam "
                  << cam << ", " << size << "x" << size << ", medians of " << frames
                  << " interleaved rounds after " << warmup << "\n\n"
                  << "| mode | slab | vots ms | grid ms | vots / vots mip | grid / vots |\n"
                  << "|---|---|---|---|---|---|\n";
        struct Row {
            RenderMode mode;
            std::optional<Slab> slab;
        };
        std::vector<Row> rows;
        for (const std::optional<Slab>& s : {std::optional<Slab>{}, std::optional<Slab>{slab}})
            for (RenderMode mode : {RenderMode::Mip, RenderMode::MinIp, RenderMode::Aip})
                rows.push_back({mode, s});
        std::vector<std::function<void()>> draws;
        std::vector<bool> gridDraws; // false where the grid renderer refuses the combination
        for (const Row& row : rows) {
            const RenderOptions options{row.mode, row.slab};
            draws.push_back([&vots, &camera, size, options] { vots.render(camera, size, size, options); });
            bool gridCan = true;
            try {
                grid.render(camera, 8, 8, options);
            } catch (const vots::fit::InputError&) {
                gridCan = false;
            }
            gridDraws.push_back(gridCan);
            draws.push_back(gridCan ? std::function<void()>([&grid, &camera, size, options] {
                grid.render(camera, size, size, options);
            })
                                    : std::function<void()>([] {}));
        }
        const std::vector<double> ms = vots::bench::interleavedMedians(warmup, frames, draws);
        for (std::size_t i = 0; i < rows.size(); ++i) {
            const double votsMs = ms[2 * i], gridMs = ms[2 * i + 1];
            const double votsMip = ms[2 * (i / 3 * 3)];
            char line[256];
            if (gridDraws[i])
                std::snprintf(line, sizeof line, "| %s | %s | %.1f | %.1f | %.2f | %.2f |\n",
                              std::string(renderModeName(rows[i].mode)).c_str(),
                              rows[i].slab ? formatSlab(*rows[i].slab).c_str() : "off", votsMs, gridMs,
                              votsMs / votsMip, gridMs / votsMs);
            else
                std::snprintf(line, sizeof line, "| %s | %s | %.1f | n/a | %.2f | n/a |\n",
                              std::string(renderModeName(rows[i].mode)).c_str(),
                              rows[i].slab ? formatSlab(*rows[i].slab).c_str() : "off", votsMs,
                              votsMs / votsMip);
            std::cout << line;
        }
    } catch (const std::exception& e) {
        std::cerr << "projection_bench: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
