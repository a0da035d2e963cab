// Frames of a 4D dataset held within a bound: cycling more frames than it holds keeps the held frames'
// bytes within it (least recently used dropped first), and every frame still draws what it drew first.
#include "NiftiFloat32.h"
#include "ServerFixture.h"

#include "vots/fit/MemoryBudget.h"
#include "vots/fit/VolumeHeader.h"

#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace vots::test {
namespace {

constexpr const char* CINE = "cine4d";
constexpr int FRAMES = 8;
constexpr int HELD = 3; // frames beside frame 0 the bound holds
constexpr int NX = 20, NY = 18, NZ = 12;

/// A float32 NIfTI-1 of FRAMES volumes: a ball that moves along x with the frame, so every frame draws
/// differently.
std::string writeCine(const TempDir& dir) {
    std::vector<float> values;
    for (int t = 0; t < FRAMES; ++t)
        for (int z = 0; z < NZ; ++z)
            for (int y = 0; y < NY; ++y)
                for (int x = 0; x < NX; ++x) {
                    const double r = std::hypot(x - 4.0 - 1.5 * t, y - 8.5, z - 5.5);
                    values.push_back(static_cast<float>(r < 4 ? 200.0 + 10.0 * t : 0.0));
                }
    return dir.write(std::string("data/") + CINE + ".nii", niftiFloat32({NX, NY, NZ}, FRAMES, values));
}

class ServerFrameEviction : public ::testing::Test {
protected:
    ServerWorld world;
    std::string path = writeCine(world.dir());
    std::uint64_t frameBytes =
        fit::estimateLoadedVolumeBytes(fit::volumeHeaderInfo(path), fit::SampleStorage::Source);
    server::ServerOptions options = [this] {
        server::ServerOptions o = world.options();
        o.heldFrameBytes = HELD * frameBytes;
        o.frameCacheBytes = 0; // every request draws from the frame's samples, none from an image kept
        o.warmUpFits = false;
        return o;
    }();
    LoopbackServer server{options};
    std::unique_ptr<httplib::Client> c = server.client();

    std::string draw(int frame) {
        const std::string target = std::string("/render?dataset=") + CINE +
                                   "&frame=" + std::to_string(frame) +
                                   "&mode=reference&cam=az=20,el=10&size=48x40";
        const auto res = c->Get(target.c_str());
        EXPECT_TRUE(res);
        if (!res) return {};
        EXPECT_EQ(res->status, 200) << res->body;
        return res->body;
    }
    nlohmann::json held() { return bodyJson(c->Get("/api/stats"))["heldFrames"]; }
};

TEST_F(ServerFrameEviction, CyclingMoreFramesThanTheBoundHoldsKeepsTheHeldBytesWithinIt) {
    std::map<int, std::string> first;
    for (int round = 0; round < 2; ++round)
        for (int frame = 0; frame < FRAMES; ++frame) {
            const std::string image = draw(frame);
            if (round == 0)
                first[frame] = image;
            else
                EXPECT_EQ(image, first[frame]) << "frame " << frame << " drew otherwise after it was dropped";
            const nlohmann::json now = held();
            EXPECT_EQ(now["boundBytes"].get<std::uint64_t>(), HELD * frameBytes);
            EXPECT_LE(now["bytes"].get<std::uint64_t>(), HELD * frameBytes) << now.dump();
            EXPECT_LE(now["frames"].size(), static_cast<std::size_t>(HELD)) << now.dump();
        }
    std::set<std::string> distinct;
    for (const auto& [frame, image] : first)
        distinct.insert(image);
    EXPECT_EQ(distinct.size(), static_cast<std::size_t>(FRAMES)) << "the frames do not draw apart";
    // The last three asked are held, the least recently used first.
    EXPECT_EQ(held()["frames"], nlohmann::json({"cine4d/5", "cine4d/6", "cine4d/7"}));
    draw(5); // used again: frame 6 is now the least recently used and goes first
    draw(1);
    EXPECT_EQ(held()["frames"], nlohmann::json({"cine4d/7", "cine4d/5", "cine4d/1"}));
}

} // namespace
} // namespace vots::test
