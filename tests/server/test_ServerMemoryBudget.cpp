// The server's --memory-budget over real loopback HTTP: a dataset whose header announces a huge volume is
// listed as not fitting and refused with 507 JSON before anything is allocated, and the others still serve.
#include "ServerFixture.h"
#include "datasets/DatasetRegistry.h"

#include "vots/fit/MemoryBudget.h"
#include "vots/fit/VolumeHeader.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace vots::test {
namespace {

constexpr const char* HUGE_NAME = "huge";
// The server holds 8- and 16-bit samples in their type, and estimates for that.
[[maybe_unused]] constexpr fit::SampleStorage HELD = server::DATASET_STORAGE;

// The tests with a budget a few tens of MB above what the process holds measure resident memory, which
// the sanitizers inflate (shadow memory, the freed-memory quarantine): they are built in normal builds
// only (the ci preset runs them), rather than skipped in the sanitizer builds.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define VOTS_RESIDENT_MEMORY_IS_INFLATED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define VOTS_RESIDENT_MEMORY_IS_INFLATED 1
#endif
#endif

/// A NRRD header announcing 100000^3 int16 samples (2 PB) over a 16-byte data file.
void addHugeDataset(const ServerWorld& world) {
    world.dir().write("data/huge.raw", std::string(16, '\0'));
    world.dir().write("data/huge.nhdr", "NRRD0004\ntype: int16\ndimension: 3\nsizes: 100000 100000 100000\n"
                                        "endian: little\nencoding: raw\ndata file: huge.raw\n");
}

nlohmann::json datasetNamed(const nlohmann::json& list, const std::string& name) {
    for (const auto& d : list["datasets"])
        if (d["name"] == name) return d;
    ADD_FAILURE() << "no dataset '" << name << "' in " << list.dump();
    return {};
}

void expect507(const httplib::Result& res, const std::string& what) {
    ASSERT_TRUE(res) << what;
    EXPECT_EQ(res->status, 507) << what << ": " << res->body;
    EXPECT_EQ(res->get_header_value("Content-Type"), "application/json") << what;
    const auto body = bodyJson(res);
    ASSERT_TRUE(body.contains("error")) << what;
    EXPECT_NE(body["error"].get<std::string>().find("memory budget"), std::string::npos) << body.dump();
}

std::string fitBody(const std::string& dataset) {
    return R"({"dataset":")" + dataset + R"(","eps":"5%"})";
}

TEST(ServerMemoryBudget, AHugeHeaderIsRefusedWith507AndOthersKeepServing) {
    ServerWorld world;
    addHugeDataset(world);
    auto options = world.options();
    options.withRenderer = false; // /render refuses before it would need a renderer
    options.memoryBudgetBytes = std::uint64_t{64} << 30;
    LoopbackServer server(options);
    auto c = server.client();

    const auto list = bodyJson(c->Get("/api/datasets"));
    EXPECT_EQ(list["memoryBudget"].get<std::uint64_t>(), std::uint64_t{64} << 30);
    const auto huge = datasetNamed(list, HUGE_NAME);
    EXPECT_FALSE(huge["fits"].get<bool>()) << huge.dump();
    EXPECT_EQ(huge["dims"], nlohmann::json::array({100000, 100000, 100000}));
    EXPECT_GT(huge["memoryNeeded"].get<std::uint64_t>(), options.memoryBudgetBytes);
    EXPECT_NE(huge["error"].get<std::string>().find("memory budget"), std::string::npos);
    EXPECT_TRUE(datasetNamed(list, BLOBS)["fits"].get<bool>());

    expect507(c->Post("/api/fit", fitBody(HUGE_NAME), "application/json"), "POST /api/fit");
    expect507(c->Get("/render?dataset=huge&size=64x64"), "GET /render");
    expect507(c->Post("/api/fit", fitBody(HUGE_NAME), "application/json"), "POST /api/fit again");

    // The others load and fit as usual on the same server.
    const auto posted = bodyJson(c->Post("/api/fit", fitBody(MRI_BRAIN), "application/json"));
    ASSERT_TRUE(posted.contains("job")) << posted.dump();
    EXPECT_EQ(waitForJob(*c, posted)["state"], "done");
    EXPECT_EQ(c->Get("/api/stats")->status, 200);
}

#ifndef VOTS_RESIDENT_MEMORY_IS_INFLATED
TEST(ServerMemoryBudget, ASmallBudgetThatIsBigEnoughServesAndOneTooSmallRefuses) {
    ServerWorld world;
    const std::string mriBrain = (world.data() / (std::string(MRI_BRAIN_FILE))).string();
    const std::uint64_t needed = fit::estimateLoadAndFitBytes(fit::volumeHeaderInfo(mriBrain), HELD);
    const std::uint64_t blobs = fit::estimateLoadAndFitBytes(
        fit::volumeHeaderInfo((world.data() / (std::string(BLOBS_FILE))).string()), HELD);
    auto options = world.quietOptions();
    {
        // Room for either dataset and its fit, with some slack for the server's own threads: far less than
        // the default budget of most of the machine.
        options.memoryBudgetBytes =
            fit::residentBytes() + std::max(needed, blobs) + (std::uint64_t{64} << 20);
        LoopbackServer server(options);
        auto c = server.client();
        const auto posted = bodyJson(c->Post("/api/fit", fitBody(MRI_BRAIN), "application/json"));
        ASSERT_TRUE(posted.contains("job")) << posted.dump();
        EXPECT_EQ(waitForJob(*c, posted)["state"], "done");
        EXPECT_TRUE(datasetNamed(bodyJson(c->Get("/api/datasets")), MRI_BRAIN)["fits"].get<bool>());
    }
    {
        // Half the estimate left: refused before loading, and again on the next request (not remembered
        // as a broken file).
        options.memoryBudgetBytes = fit::residentBytes() + needed / 2;
        LoopbackServer server(options);
        auto c = server.client();
        expect507(c->Post("/api/fit", fitBody(MRI_BRAIN), "application/json"), "POST /api/fit");
        const auto entry = datasetNamed(bodyJson(c->Get("/api/datasets")), MRI_BRAIN);
        EXPECT_FALSE(entry["fits"].get<bool>()) << entry.dump();
        EXPECT_EQ(entry["memoryNeeded"].get<std::uint64_t>(), needed);
        expect507(c->Post("/api/fit", fitBody(MRI_BRAIN), "application/json"), "POST /api/fit again");
    }
}

TEST(ServerMemoryBudget, AFitJobReservesItsMemoryUntilItEnds) {
    ServerWorld world;
    const std::string path = (world.data() / (std::string(BLOBS_FILE))).string();
    const std::uint64_t needed = fit::estimateLoadAndFitBytes(fit::volumeHeaderInfo(path), HELD);
    auto options = world.quietOptions();
    // Room for loading and one fit, not for a second fit beside it.
    options.memoryBudgetBytes = fit::residentBytes() + needed + (std::uint64_t{64} << 20);
    LoopbackServer server(options);
    auto c = server.client();
    const auto slow = [](double eps) { // tight eps: the first fit still runs when the second is asked
        return std::string(R"({"dataset":")") + BLOBS + R"(","eps":)" + std::to_string(eps) + "}";
    };
    const auto first = bodyJson(c->Post("/api/fit", slow(0.2), "application/json"));
    ASSERT_TRUE(first.contains("job")) << first.dump();
    const auto second = c->Post("/api/fit", slow(0.3), "application/json");
    expect507(second, "a second fit beside the first");
    EXPECT_NE(bodyJson(second)["error"].get<std::string>().find("a fit of dataset"), std::string::npos);
    EXPECT_EQ(waitForJob(*c, first)["state"], "done");
    // The first job's reservation is given back when it ends: the second fit is admitted now.
    const auto again = bodyJson(c->Post("/api/fit", slow(0.3), "application/json"));
    ASSERT_TRUE(again.contains("job")) << again.dump();
    EXPECT_EQ(waitForJob(*c, again)["state"], "done");
}
#endif // VOTS_RESIDENT_MEMORY_IS_INFLATED

} // namespace
} // namespace vots::test
