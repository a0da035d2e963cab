// A 4D dataset in the server: the listing says its frame count, /render?frame=k draws what `vots render
// --frame k` draws (byte for byte), each frame's fit has its own key, and a frame it does not hold is a 400.
#include "NiftiFloat32.h"
#include "ServerFixture.h"

#include "vots/fit/Fitter.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace vots::test {
namespace {

constexpr const char* FOUR = "pulse4d";
constexpr int FRAMES = 3;
constexpr int NX = 24, NY = 20, NZ = 14;

/// A float32 NIfTI-1 of FRAMES volumes: a ball whose brightness and radius grow with the frame, so every
/// frame draws differently.
std::string writeFourDimensional(const TempDir& dir) {
    std::vector<float> values;
    for (int t = 0; t < FRAMES; ++t)
        for (int z = 0; z < NZ; ++z)
            for (int y = 0; y < NY; ++y)
                for (int x = 0; x < NX; ++x) {
                    const double r = std::hypot(x - 11.5, y - 9.5, 1.4 * (z - 6.5));
                    const double radius = 4.0 + 2.0 * t;
                    values.push_back(static_cast<float>(
                        r < radius ? 100.0 + 150.0 * t + 20.0 * std::sin(0.5 * x + 0.3 * y) : 0.0));
                }
    return dir.write(std::string("data/") + FOUR + ".nii", niftiFloat32({NX, NY, NZ}, FRAMES, values));
}

class ServerFrames : public ::testing::Test {
protected:
    ServerWorld world;
    std::string path = writeFourDimensional(world.dir());
    LoopbackServer server{world.options()};
    std::unique_ptr<httplib::Client> c = server.client();
};

TEST_F(ServerFrames, TheListingSaysHowManyFramesEachDatasetHolds) {
    const auto listed = bodyJson(c->Get("/api/datasets"));
    std::set<std::string> seen;
    for (const auto& d : listed["datasets"]) {
        seen.insert(d["name"].get<std::string>());
        EXPECT_EQ(d["frames"], d["name"] == FOUR ? FRAMES : 1) << d.dump();
    }
    EXPECT_TRUE(seen.count(FOUR)) << listed.dump();
}

TEST_F(ServerFrames, EachFrameRendersWhatTheCliRendersForIt) {
    std::set<std::string> images;
    for (int frame = 0; frame < FRAMES; ++frame)
        for (const auto& [query, args] :
             {std::pair<std::string, std::string>{"mode=reference&cam=az=30,el=20&size=64x48",
                                                  "--mode reference --cam az=30,el=20 --size 64x48"},
              std::pair<std::string, std::string>{"eps=2%25&cam=az=30,el=20&size=64x48",
                                                  "--eps 2% --cam az=30,el=20 --size 64x48"}}) {
            const std::string target =
                std::string("/render?dataset=") + FOUR + "&frame=" + std::to_string(frame) + "&" + query;
            const auto res = c->Get(target.c_str());
            ASSERT_TRUE(res);
            ASSERT_EQ(res->status, 200) << res->body;
            const std::string out = world.dir().file("cli.png");
            const std::string command = std::string(VOTS_CLI) + " render '" + path + "' --frame " +
                                        std::to_string(frame) + " -o '" + out + "' " + args + " --fit-norm " +
                                        std::string(fit::nameOf(fit::SERVE_FIT_NORM)) + " 2>/dev/null";
            ASSERT_EQ(std::system(command.c_str()), 0) << command;
            EXPECT_EQ(res->body, fileBytes(out)) << target;
            images.insert(res->body);
        }
    // Two renderers per frame give one image each frame (grid and Vots agree on a PNG only by chance):
    // at least every frame differs from the others.
    EXPECT_GE(images.size(), static_cast<std::size_t>(FRAMES));
}

TEST_F(ServerFrames, WithoutAFrameTheQueryDrawsFrameZero) {
    const auto plain =
        c->Get((std::string("/render?dataset=") + FOUR + "&mode=reference&size=40x40").c_str());
    const auto zero =
        c->Get((std::string("/render?dataset=") + FOUR + "&frame=0&mode=reference&size=40x40").c_str());
    const auto two =
        c->Get((std::string("/render?dataset=") + FOUR + "&frame=2&mode=reference&size=40x40").c_str());
    ASSERT_TRUE(plain && zero && two);
    ASSERT_EQ(plain->status, 200);
    EXPECT_EQ(plain->body, zero->body);
    EXPECT_NE(plain->body, two->body);
}

TEST_F(ServerFrames, EachFrameIsFittedUnderItsOwnKey) {
    std::vector<std::string> keys;
    for (int frame = 0; frame < FRAMES; ++frame) {
        const std::string body =
            std::string(R"({"dataset":")") + FOUR + R"(","eps":"2%","frame":)" + std::to_string(frame) + "}";
        const auto posted = bodyJson(c->Post("/api/fit", body, "application/json"));
        ASSERT_TRUE(posted.contains("job")) << posted.dump();
        const auto done = waitForJob(*c, posted);
        EXPECT_EQ(done["state"], "done") << done.dump();
        const std::string key = done["key"].get<std::string>();
        // Frame 0 keeps the key a 3D dataset has; the others name their frame.
        EXPECT_EQ(key.find("_t"), frame == 0 ? std::string::npos : key.size() - 3) << key;
        keys.push_back(key);
    }
    EXPECT_EQ(std::set<std::string>(keys.begin(), keys.end()).size(), keys.size());
    // A second ask of a fitted frame finds the fit of that frame.
    const auto again =
        bodyJson(c->Post("/api/fit", std::string(R"({"dataset":")") + FOUR + R"(","eps":"2%","frame":1})",
                         "application/json"));
    EXPECT_EQ(again["state"], "done") << again.dump();
    EXPECT_EQ(again["key"], keys[1]);
}

TEST_F(ServerFrames, AFrameTheDatasetDoesNotHoldIsRefusedWithTheCount) {
    const auto beyond = c->Get((std::string("/render?dataset=") + FOUR + "&frame=3&mode=reference").c_str());
    ASSERT_TRUE(beyond);
    EXPECT_EQ(beyond->status, 400);
    EXPECT_NE(beyond->body.find("has no frame 3: it holds 3 frames"), std::string::npos) << beyond->body;
    const auto flat = c->Get((std::string("/render?dataset=") + BLOBS + "&frame=1&mode=reference").c_str());
    ASSERT_TRUE(flat);
    EXPECT_EQ(flat->status, 400);
    EXPECT_NE(flat->body.find("it holds 1 frame"), std::string::npos) << flat->body;
    for (const char* bad : {"-1", "x", "1.5", ""}) {
        const auto res =
            c->Get((std::string("/render?dataset=") + FOUR + "&mode=reference&frame=" + bad).c_str());
        ASSERT_TRUE(res);
        EXPECT_EQ(res->status, 400) << bad;
        EXPECT_NE(res->body.find("frame must be a whole number"), std::string::npos) << res->body;
    }
    const auto fit =
        c->Post("/api/fit", std::string(R"({"dataset":")") + FOUR + R"(","frame":7})", "application/json");
    ASSERT_TRUE(fit);
    EXPECT_EQ(fit->status, 400);
}

} // namespace
} // namespace vots::test
