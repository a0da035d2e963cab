// .vots files in the data folder as datasets of their own over loopback: listed with their kind, drawn
// byte for byte as `vots render FILE.vots` draws them, 409 for what needs the volume, sized before loading.
#include "ServerFixture.h"
#include "datasets/DatasetRegistry.h"

#include "vots/fit/VotSpaceFile.h"
#include "vots/meta/VotSpaceRead.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace vots::test {
namespace {

/// A data folder with head.vots (fitted from the MRI by the real CLI), a copy of it under the name of a
/// volume (the volume must win) and a .vots file that is not one (left out).
class ServerVotsDataset : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        sWorld = new ServerWorld();
        const std::string head = (sWorld->data() / "head.vots").string();
        const std::string fit = std::string(VOTS_CLI) + " fit '" + VOTS_TEST_DATA_DIR + "/" + MRI_BRAIN_FILE +
                                "' -o '" + head + "' --eps 3% --degree 2 2>/dev/null";
        ASSERT_EQ(std::system(fit.c_str()), 0) << fit;
        std::filesystem::copy_file(head, sWorld->data() / (std::string(BLOBS) + ".vots"));
        sWorld->dir().write("data/broken.vots", "VOTS but not a Vot-Space");
        sVotCount = meta::readVotSpaceFile(head).vots.size();
        sServer = new LoopbackServer(sWorld->options());
    }
    static void TearDownTestSuite() {
        delete sServer;
        delete sWorld;
    }
    static std::unique_ptr<httplib::Client> client() { return sServer->client(); }

    static nlohmann::json listed(const std::string& name) {
        const nlohmann::json list = bodyJson(client()->Get("/api/datasets")); // outlives the loop
        for (const auto& d : list["datasets"])
            if (d["name"] == name) return d;
        return nullptr;
    }
    static std::string cliRender(const std::string& args) {
        const std::string out = sWorld->dir().file("cli-" + std::to_string(sCount++) + ".png");
        return cliRenderBytes((sWorld->data() / "head.vots").string(), out, args);
    }
    static std::string serverRender(const std::string& query) {
        const auto res = client()->Get(("/render?" + query).c_str());
        if (!res) return "no response";
        EXPECT_EQ(res->status, 200) << query << ": " << res->body;
        EXPECT_EQ(res->get_header_value("X-Vots-Vot-Count"), std::to_string(sVotCount)) << "the file's Vots";
        return res->body;
    }
    /// The status and the JSON error of a refused request.
    static std::pair<int, std::string> refusal(const httplib::Result& res) {
        if (!res) return {0, "no response"};
        EXPECT_EQ(res->get_header_value("Content-Type"), "application/json");
        const auto body = nlohmann::json::parse(res->body, nullptr, false);
        return {res->status,
                body.is_object() && body["error"].is_string() ? body["error"].get<std::string>() : ""};
    }

    static inline ServerWorld* sWorld = nullptr;
    static inline LoopbackServer* sServer = nullptr;
    static inline int sCount = 0;
    static inline std::size_t sVotCount = 0;
};

TEST_F(ServerVotsDataset, ListedWithItsKindAndTheFilesEps) {
    const fit::VotSpace space = meta::readVotSpaceFile((sWorld->data() / "head.vots").string());
    const auto head = listed("head");
    ASSERT_TRUE(head.is_object()) << "head.vots is not listed";
    EXPECT_EQ(head["kind"], "vots");
    EXPECT_FLOAT_EQ(head["eps"].get<float>(), space.eps);
    EXPECT_FLOAT_EQ(head["defaultEps"].get<float>(), space.eps);
    EXPECT_EQ(head["votCount"].get<std::size_t>(), space.vots.size());
    EXPECT_EQ(head["dims"], nlohmann::json(space.dims));
    // The MRI's value range as the fit saw it (its int16 samples: -610 to 30393), from the file's meta block.
    EXPECT_EQ(head["range"][0].get<float>(), -610.f);
    EXPECT_EQ(head["range"][1].get<float>(), 30393.f);

    const auto volume = listed(BLOBS);
    ASSERT_TRUE(volume.is_object());
    EXPECT_EQ(volume["kind"], "volume") << "a volume wins over a .vots file of the same name";
    EXPECT_EQ(volume["dims"], nlohmann::json({64, 64, 64}));
    EXPECT_TRUE(listed("broken").is_null()) << "a .vots file that does not load is left out";
}

TEST_F(ServerVotsDataset, RenderEqualsTheCliOnTheFileByteForByte) {
    EXPECT_EQ(serverRender("dataset=head&cam=az=30,el=20&size=96x80"),
              cliRender("--cam az=30,el=20 --size 96x80"));
    EXPECT_EQ(serverRender("dataset=head&cam=view%3Danterior&size=64x64&mode=density&colormap=hot"),
              cliRender("--view anterior --size 64x64 --mode density --colormap hot"));
    // The file's own eps, as the viewer sends it back from /api/datasets, is no refit.
    const std::string eps = listed("head")["eps"].dump();
    EXPECT_EQ(serverRender("dataset=head&cam=az=-40,el=10&size=72x72&window=8000,16000&eps=" + eps),
              cliRender("--cam az=-40,el=10 --size 72x72 --window 8000,16000"));
}

TEST_F(ServerVotsDataset, ReferenceAndAnotherEpsAnswer409WithTheReason) {
    auto [status, error] = refusal(client()->Get("/render?dataset=head&size=32x32&mode=reference"));
    EXPECT_EQ(status, 409);
    EXPECT_NE(error.find("reference"), std::string::npos) << error;
    EXPECT_NE(error.find("Vot-Space file"), std::string::npos) << error;

    std::tie(status, error) = refusal(client()->Get("/render?dataset=head&size=32x32&eps=50%25"));
    EXPECT_EQ(status, 409);
    EXPECT_NE(error.find("refit"), std::string::npos) << error;

    std::tie(status, error) =
        refusal(client()->Post("/api/fit", R"({"dataset":"head","eps":"2%"})", "application/json"));
    EXPECT_EQ(status, 409);
    EXPECT_NE(error.find("refitted"), std::string::npos) << error;

    // A volume keeps both.
    const auto volume =
        client()->Get((std::string("/render?dataset=") + BLOBS + "&size=32x32&mode=reference").c_str());
    ASSERT_TRUE(volume);
    EXPECT_EQ(volume->status, 200);
}

TEST(ServerVotsDatasetMemory, AVotsFileIsSizedFromItsFileBeforeItIsRead) {
    ServerWorld world;
    // Sparse: announces far more than the budget without taking the disk; reading it would be the bug.
    const auto huge = world.data() / "huge.vots";
    std::ofstream(huge).put('V');
    std::filesystem::resize_file(huge, std::uint64_t{100} << 30);
    auto options = world.options();
    options.memoryBudgetBytes = std::uint64_t{64} << 30;
    LoopbackServer server(options);
    auto c = server.client();
    nlohmann::json entry;
    const nlohmann::json list = bodyJson(c->Get("/api/datasets"));
    for (const auto& d : list["datasets"])
        if (d["name"] == "huge") entry = d;
    ASSERT_TRUE(entry.is_object()) << "a refused .vots file is listed as refused";
    EXPECT_EQ(entry["fits"], false);
    EXPECT_EQ(entry["kind"], "vots");
    const auto res = c->Get("/render?dataset=huge&size=16x16");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 507) << res->body;
    EXPECT_GT(server::estimateVotsLoadBytes(std::uint64_t{100} << 30), std::uint64_t{100} << 30);
}

} // namespace
} // namespace vots::test
