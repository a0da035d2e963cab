// GET /turntable over loopback: a decodable VP9 WebM of N frames, frames shared with /render, 400 for bad
// input.
#include "ServerFixture.h"
#include "WebmProbe.h"

#include <fstream>
#include <string>

namespace vots::test {
namespace {

class ServerTurntable : public SharedServerTest {
protected:
    static VideoProbe probeBody(const std::string& body) {
        const std::string path = world().dir().file("turn-" + std::to_string(sCount++) + ".webm");
        std::ofstream(path, std::ios::binary) << body;
        return probeVideo(path);
    }
    static inline int sCount = 0;
};

TEST_F(ServerTurntable, AnswersADecodableWebmWhoseFramesTheRenderCacheHolds) {
    const std::string query = "dataset=blobs_64x64x64_uint8&cam=az=10,el=20&size=64x48&eps=2%25";
    auto c = client();
    const auto res = c->Get(("/turntable?" + query + "&frames=6").c_str());
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 200) << res->body;
    EXPECT_EQ(res->get_header_value("Content-Type"), "video/webm");
    EXPECT_EQ(res->get_header_value("X-Vots-Frames"), "6");
    EXPECT_EQ(res->get_header_value("X-Vots-Frame-Cache-Hits"), "0");
    const VideoProbe probe = probeBody(res->body);
    EXPECT_EQ(probe.error, "");
    EXPECT_EQ(probe.codec, "vp9");
    EXPECT_EQ(probe.framesDecoded, 6);
    EXPECT_EQ(probe.width, 64);
    EXPECT_EQ(probe.height, 48);

    // Frame 3 of the turn is az 10 + 3 * 60: the viewer's cine frame at that camera is a cache hit.
    const auto frame = c->Get("/render?dataset=blobs_64x64x64_uint8&cam=az=190,el=20&size=64x48&eps=2%25");
    ASSERT_TRUE(frame);
    EXPECT_EQ(frame->status, 200);
    EXPECT_EQ(frame->get_header_value("X-Vots-Frame-Cache"), "hit");

    // A second turn is drawn from the cache only, and gives the same bytes.
    const auto again = c->Get(("/turntable?" + query + "&frames=6").c_str());
    ASSERT_TRUE(again);
    EXPECT_EQ(again->get_header_value("X-Vots-Frame-Cache-Hits"), "6");
    EXPECT_EQ(again->body, res->body);
}

TEST_F(ServerTurntable, RefusesBadFramesAndSizesAsJson400) {
    auto c = client();
    const std::string base = "/turntable?dataset=blobs_64x64x64_uint8&size=64x64";
    for (const std::string tail :
         {"&frames=0", "&frames=100000", "&frames=-1", "&frames=x", "", "&frames=4&frames=5"}) {
        const auto res = c->Get((base + tail).c_str());
        ASSERT_TRUE(res) << tail;
        EXPECT_EQ(res->status, 400) << tail << ": " << res->body;
        EXPECT_TRUE(bodyJson(res).contains("error")) << tail;
    }
    for (const std::string query : {"dataset=blobs_64x64x64_uint8&size=2048x64&frames=4",
                                    "dataset=blobs_64x64x64_uint8&size=1x64&frames=4",
                                    "dataset=blobs_64x64x64_uint8&size=1024x1024&frames=360",
                                    "dataset=blobs_64x64x64_uint8&frames=4&bogus=1"}) {
        const auto res = c->Get(("/turntable?" + query).c_str());
        ASSERT_TRUE(res) << query;
        EXPECT_EQ(res->status, 400) << query << ": " << res->body;
        EXPECT_TRUE(bodyJson(res).contains("error")) << query;
    }
    const auto missing = c->Get("/turntable?dataset=no_such_dataset&frames=4");
    ASSERT_TRUE(missing);
    EXPECT_EQ(missing->status, 404);
}

} // namespace
} // namespace vots::test
