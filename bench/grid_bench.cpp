// Times the grid renderer per mode on one volume and camera: median frame times (render + readback).
#include "vots/fit/Error.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/render/CameraText.h"
#include "vots/render/EglContext.h"
#include "vots/render/GridRenderer.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

namespace {

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"Median frame times of the grid renderer for each mode"};
    std::string volumePath = "data/cranium.nhdr", cameraText = "az=30,el=20";
    std::vector<std::string> modes{"mip", "minip", "aip"};
    int size = 512, frames = 5;
    app.add_option("--volume", volumePath, "volume file");
    app.add_option("--cam", cameraText, "camera");
    app.add_option("--size", size, "image side in pixels")->check(CLI::Range(1, 8192));
    app.add_option("--frames", frames, "timed frames per mode (after one warm-up)")
        ->check(CLI::Range(1, 100));
    app.add_option("--modes", modes, "modes to time (comma list)")->delimiter(',');
    CLI11_PARSE(app, argc, argv);
    try {
        auto context = vots::render::EglContext::createOrThrow();
        const vots::fit::Volume volume = vots::fit::loadVolume(volumePath);
        vots::render::GridRenderer grid;
        grid.upload(volume);
        const vots::render::Camera camera = vots::render::parseCamera(cameraText);
        std::cout << "renderer: " << context->renderer() << ", volume " << volumePath << " " << volume.dims[0]
                  << "x" << volume.dims[1] << "x" << volume.dims[2] << ", " << size << "x" << size << ", cam "
                  << cameraText << ", medians of " << frames
                  << "\n\n| mode | frame ms | draw ms |\n|---|---|---|\n";
        for (const std::string& name : modes) {
            const vots::render::RenderMode mode = vots::render::parseModeName(name).mode;
            std::vector<double> frame, draw;
            for (int i = 0; i <= frames; ++i) {
                const auto t0 = std::chrono::steady_clock::now();
                (void)grid.render(camera, size, size, mode);
                const double ms =
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
                if (i == 0) continue; // warm-up: shader compile, target allocation
                frame.push_back(ms);
                draw.push_back(grid.lastFrameStats().gpuMs);
            }
            std::printf("| %s | %.1f | %.1f |\n", name.c_str(), median(frame), median(draw));
        }
    } catch (const vots::fit::InputError& e) {
        std::cerr << "grid_bench: " << e.what() << "\n";
        return 2;
    }
    return 0;
}
