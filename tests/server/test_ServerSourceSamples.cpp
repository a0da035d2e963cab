// The server holds an 8- or 16-bit study in its source type: the registry loads it compact, with the
// range, CRC and grid images of the float-held volume, a memory estimate of what it holds, and /render
// gives the bytes of `vots render`.
#include "ServerFixture.h"
#include "datasets/DatasetRegistry.h"
#include "datasets/MemoryAdmission.h"

#include "vots/fit/Fitter.h"
#include "vots/fit/MemoryBudget.h"
#include "vots/fit/VolumeHeader.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/render/CameraText.h"
#include "vots/render/EglContext.h"
#include "vots/render/GridRenderer.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

namespace vots::test {
namespace {

constexpr const char* CT16 = "ct16";
constexpr std::array<int, 3> CT16_DIMS{37, 30, 23}; // x odd: rows of int16 do not fill 4 bytes

/// An int16 CT-like NRRD (air, tissue, a bright ridge) in `folder`; returns its path.
std::string writeInt16Study(const TempDir& dir, const std::string& folder) {
    std::filesystem::create_directories(dir.path() / folder);
    std::string samples;
    for (int z = 0; z < CT16_DIMS[2]; ++z)
        for (int y = 0; y < CT16_DIMS[1]; ++y)
            for (int x = 0; x < CT16_DIMS[0]; ++x) {
                const double r = std::hypot(x - 18.0, y - 14.5, 1.3 * (z - 11.0));
                const double value = r > 12.0 ? -1000.0 : 40.0 + 30.0 * std::sin(0.7 * x + 0.4 * z);
                const auto sample = static_cast<std::int16_t>(z == 9 && r < 8.0 ? 2500.0 : value);
                samples.append(reinterpret_cast<const char*>(&sample), sizeof sample); // little endian
            }
    dir.write(folder + "/" + CT16 + ".raw", samples);
    return dir.write(folder + "/" + CT16 + ".nhdr",
                     "NRRD0004\ntype: int16\ndimension: 3\nsizes: 37 30 23\nspacings: 0.8 0.8 1.5\n"
                     "endian: little\nencoding: raw\ndata file: " +
                         std::string(CT16) + ".raw\n");
}

TEST(ServerSourceSamples, AnInt16StudyIsHeldCompactWithItsFloatTwinsFacts) {
    TempDir dir;
    const std::string path = writeInt16Study(dir, "data");
    server::MemoryAdmission memory(std::uint64_t{64} << 30);
    server::DatasetRegistry registry({dir.path() / "data"}, memory);
    const auto dataset = registry.find(CT16);
    const fit::Volume& held = *dataset->volume;
    ASSERT_TRUE(held.isCompact());
    ASSERT_TRUE(std::holds_alternative<std::vector<std::int16_t>>(held.compact));
    EXPECT_TRUE(held.values.empty());
    EXPECT_EQ(held.heldSamples(), held.sampleCount());

    const fit::Volume floats = fit::loadVolume(path);
    EXPECT_EQ(dataset->range, floats.valueRange());
    EXPECT_EQ(dataset->background, fit::defaultBackground(floats));
    // The disk cache is keyed by it: the same file gives the same key however it is held.
    EXPECT_EQ(dataset->contentCrc, floats.contentCrc());
    EXPECT_TRUE(dataset->isCt);

    // What it holds is 2 bytes a sample, and the estimates say so (and less than for floats).
    const fit::VolumeHeaderInfo header = fit::volumeHeaderInfo(path);
    EXPECT_EQ(fit::estimateLoadedVolumeBytes(header, fit::SampleStorage::Source), 2 * header.sampleCount());
    EXPECT_EQ(dataset->loadAndFitBytes, fit::estimateLoadAndFitBytes(header, fit::SampleStorage::Source));
    EXPECT_LT(dataset->loadAndFitBytes, fit::estimateLoadAndFitBytes(header, fit::SampleStorage::Float));
    EXPECT_EQ(dataset->fitBytes, dataset->loadAndFitBytes - 2 * header.sampleCount());
}

TEST(ServerSourceSamples, TheCompactStudyDrawsBitForBitAsTheFloatLoadedOne) {
    TempDir dir;
    const std::string path = writeInt16Study(dir, "data");
    server::MemoryAdmission memory(std::uint64_t{64} << 30);
    server::DatasetRegistry registry({dir.path() / "data"}, memory);
    const auto dataset = registry.find(CT16);
    ASSERT_TRUE(dataset->volume->isCompact());
    const fit::Volume floats = fit::loadVolume(path, std::nullopt, fit::SampleStorage::Float);

    std::string error;
    const auto context = render::EglContext::create(&error);
    ASSERT_TRUE(context) << "no EGL context: " << error;
    render::GridRenderer fromCompact, fromFloats;
    fromCompact.upload(*dataset->volume);
    fromFloats.upload(floats);
    for (const char* text : {"anterior", "az=30,el=20", "az=-50,el=-30,zoom=1.4,proj=persp,fov=40"})
        for (const render::RenderMode mode :
             {render::RenderMode::Mip, render::RenderMode::MinIp, render::RenderMode::Aip}) {
            const render::Camera cam = render::parseCamera(text);
            const render::FloatImage a = fromCompact.render(cam, 64, 48, mode);
            const render::FloatImage b = fromFloats.render(cam, 64, 48, mode);
            ASSERT_EQ(a.pixels.size(), b.pixels.size());
            EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)), 0)
                << text << " " << render::renderModeName(mode);
        }
}

TEST(ServerSourceSamples, RenderAndFitOfTheCompactStudyMatchTheCli) {
    ServerWorld world;
    const std::string path = writeInt16Study(world.dir(), "data");
    LoopbackServer server(world.options());
    auto c = server.client();
    const auto posted = bodyJson(c->Post("/api/fit", R"({"dataset":"ct16","eps":"2%"})", "application/json"));
    ASSERT_TRUE(posted.contains("job")) << posted.dump();
    EXPECT_EQ(waitForJob(*c, posted)["state"], "done");
    // `vots render` loads the samples as floats: the same PNG bytes from the grid and from the Vots.
    for (const auto& [query, args] :
         {std::pair<std::string, std::string>{"mode=reference&cam=az=30,el=20&size=80x64",
                                              "--mode reference --cam az=30,el=20 --size 80x64"},
          std::pair<std::string, std::string>{"eps=2%25&cam=az=30,el=20&size=80x64",
                                              "--eps 2% --cam az=30,el=20 --size 80x64"}}) {
        const auto res = c->Get(("/render?dataset=ct16&" + query).c_str());
        ASSERT_TRUE(res);
        EXPECT_EQ(res->status, 200) << res->body;
        const std::string out = world.dir().file("cli.png");
        const std::string command = std::string(VOTS_CLI) + " render '" + path + "' -o '" + out + "' " +
                                    args + " --fit-norm " + std::string(fit::nameOf(fit::SERVE_FIT_NORM)) +
                                    " 2>/dev/null"; // the server's norm
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
        EXPECT_EQ(res->body, fileBytes(out)) << query;
    }
}

} // namespace
} // namespace vots::test
