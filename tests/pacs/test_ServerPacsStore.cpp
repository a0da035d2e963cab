// The viewer's Send to PACS (POST /api/pacs/{name}/store) against the real Orthanc of the pacs fixture: a
// PACS series' sweep joins its study as one new series, and bad requests are refused before any drawing.
#include "FaultProxy.h"
#include "JobPolling.h"
#include "LoopbackServer.h"
#include "OrthancState.h"
#include "TempDir.h"

#include "vots/fit/DicomSeries.h"
#include "vots/pacs/QidoSearch.h"
#include "vots/pacs/SeriesRetrieve.h"

#include <gtest/gtest.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <filesystem>
#include <set>

namespace {

namespace fs = std::filesystem;
using namespace vots;
using namespace vots::test;

// pacs_setup.sh's send-source: a study no other test counts the series of.
const std::string SEND_SERIES = "1.2.826.0.1.3680043.10.1234.207";
const std::string SEND_STUDY = SEND_SERIES + ".0";
const std::string SEND_DATASET = "orthanc-1_2_826_0_1_3680043_10_1234_207";

/// The fixture's Orthanc as the server's PACS "orthanc", at its own port or another's (a proxy's).
server::DicomWebService orthanc(bool withCredentials, const std::string& port = orthancStateFile("port")) {
    server::DicomWebService s;
    s.name = "orthanc";
    s.endpoint = pacs::parseDicomWebEndpoint("dicomweb+http://127.0.0.1:" + port + "/dicom-web");
    if (withCredentials) s.access = orthancAccess();
    return s;
}

std::set<std::string> seriesOfTheSendStudy() {
    std::set<std::string> uids;
    for (const pacs::SeriesSummary& s : pacs::searchSeries(orthancEndpoint(), orthancAccess(), SEND_STUDY))
        uids.insert(s.seriesUid);
    return uids;
}

/// Whether the send study holds a series of this description: the other tests' sweeps, stored meanwhile
/// (ctest runs them in parallel), are described otherwise.
bool sendStudyHolds(const std::string& description) {
    for (const pacs::SeriesSummary& s : pacs::searchSeries(orthancEndpoint(), orthancAccess(), SEND_STUDY))
        if (s.description == description) return true;
    return false;
}

class ServerPacsStore : public ::testing::Test {
protected:
    ServerPacsStore() { fs::create_directories(mDir.path() / "data"); }

    server::ServerOptions options(const server::DicomWebService& service) const {
        server::ServerOptions o;
        o.dataDirs = {mDir.path() / "data"};
        o.cacheDir = mDir.path() / "cache";
        o.warmUpFits = false;
        o.dicomWebServices = {service};
        return o;
    }

    /// Opens the send-source series as a dataset (PACS panel's open) and expects it done.
    static void openSendSource(httplib::Client& c) {
        const auto posted =
            c.Post(("/api/pacs/orthanc/studies/" + SEND_STUDY + "/series/" + SEND_SERIES + "/open").c_str(),
                   "{}", "application/json");
        const auto seen = pollJob(c, posted, "/api/pacs/opens/");
        ASSERT_FALSE(seen.empty());
        ASSERT_EQ(seen.back()["state"], "done") << seen.back().dump();
        ASSERT_EQ(seen.back()["dataset"], SEND_DATASET);
    }

    /// Each test sends its own thickness, so that what it stores (or must not) has a description of its own.
    static nlohmann::json sweepBody(int thickness = 10) {
        return {{"dataset", SEND_DATASET},
                {"cam", "az=0,el=0,zoom=1,pan=0:0,proj=ortho,fov=30"},
                {"mode", "mip"},
                {"thickness", thickness},
                {"step", 5},
                {"size", "48x40"},
                {"eps", "1%"}};
    }

    TempDir mDir;
};

TEST_F(ServerPacsStore, ASweepJoinsTheSourcesStudyAsOneNewSeries) {
    LoopbackServer server(options(orthanc(true)));
    auto c = server.client();
    openSendSource(*c);
    const std::set<std::string> before = seriesOfTheSendStudy();

    const auto posted = c->Post("/api/pacs/orthanc/store", sweepBody().dump(), "application/json");
    const auto seen = pollJob(*c, posted, "/api/pacs/stores/");
    ASSERT_FALSE(seen.empty());
    const nlohmann::json& last = seen.back();
    ASSERT_EQ(last["state"], "done") << last.dump();
    const int total = last["total"];
    EXPECT_GT(total, 1);
    EXPECT_EQ(last["drawn"], total);
    EXPECT_EQ(last["stored"], total);
    EXPECT_EQ(last["description"], "MIP 10 mm / 5 mm coronal");
    for (const nlohmann::json& answer : seen) { // progress counts up to the total, never past it
        EXPECT_LE(answer["drawn"].get<int>(), total);
        EXPECT_EQ(answer["total"], total);
    }

    std::vector<pacs::SeriesSummary> added;
    for (const pacs::SeriesSummary& s : pacs::searchSeries(orthancEndpoint(), orthancAccess(), SEND_STUDY))
        if (!before.count(s.seriesUid)) added.push_back(s);
    ASSERT_EQ(added.size(), 1u);
    EXPECT_EQ(added[0].instanceCount, total);
    EXPECT_EQ(added[0].description, "MIP 10 mm / 5 mm coronal");
    EXPECT_EQ(added[0].modality, "CT");

    // Read back: a series of the source's study with one image per slab at the view's size, whose MIPs
    // through the whole sphere reach its brightest sample (less what the pixel rays miss of the peak).
    const pacs::RetrievedSeries stored =
        pacs::retrieveSeries({orthancEndpoint(), SEND_STUDY, added[0].seriesUid}, orthancAccess());
    EXPECT_EQ(fit::readDicomIdentity(stored.folder()).studyInstanceUid, SEND_STUDY);
    const fit::Volume sweep = fit::loadDicomSeries(stored.folder());
    EXPECT_EQ(sweep.dims, (std::array<int, 3>{48, 40, total}));
    const auto datasets = nlohmann::json::parse(c->Get("/api/datasets")->body)["datasets"];
    const auto source = std::find_if(datasets.begin(), datasets.end(),
                                     [](const nlohmann::json& d) { return d["name"] == SEND_DATASET; });
    ASSERT_NE(source, datasets.end());
    const float lo = (*source)["range"][0], hi = (*source)["range"][1];
    EXPECT_LE(sweep.valueRange()[1], hi + 0.01f * (hi - lo));
    EXPECT_GE(sweep.valueRange()[1], hi - 0.05f * (hi - lo));
}

TEST_F(ServerPacsStore, BadRequestsAreRefusedBeforeAnythingIsDrawn) {
    std::string ramp(8 * 8 * 8, '\0');
    for (std::size_t i = 0; i < ramp.size(); ++i)
        ramp[i] = static_cast<char>(i % 200);
    mDir.write("data/plain.nrrd",
               "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 8 8 8\nencoding: raw\n\n" + ramp);
    LoopbackServer server(options(orthanc(true)));
    auto c = server.client();
    openSendSource(*c);
    const auto status = [&](const std::string& path, const std::string& body) {
        const auto res = c->Post(path.c_str(), body, "application/json");
        return res ? res->status : -1;
    };
    const auto with = [](const char* key, const nlohmann::json& value) {
        nlohmann::json body = sweepBody(13);
        body[key] = value;
        return body.dump();
    };
    const auto without = [](const char* key) {
        nlohmann::json body = sweepBody(13);
        body.erase(key);
        return body.dump();
    };
    const std::string store = "/api/pacs/orthanc/store";
    EXPECT_EQ(status("/api/pacs/nowhere/store", sweepBody().dump()), 404);
    EXPECT_EQ(status(store, with("dataset", "no_such_dataset")), 404);
    EXPECT_EQ(status(store, with("dataset", "plain")), 409); // not DICOM: no study to join
    EXPECT_EQ(status(store, "not json"), 400);
    EXPECT_EQ(status(store, "[1,2]"), 400);
    EXPECT_EQ(status(store, without("thickness")), 400);
    EXPECT_EQ(status(store, with("thickness", "10")), 400);
    EXPECT_EQ(status(store, with("step", 0)), 400);
    EXPECT_EQ(status(store, with("step", -5)), 400);
    EXPECT_EQ(status(store, with("mode", "density")), 400);
    EXPECT_EQ(status(store, with("mode", "sideways")), 400);
    EXPECT_EQ(status(store, with("cam", "az=0,el=0,proj=persp")), 400);
    EXPECT_EQ(status(store, with("size", "0x40")), 400);
    EXPECT_EQ(status(store, with("slab", "0,5")), 400);
    EXPECT_EQ(status(store, with("colour", "red")), 400);
    EXPECT_EQ(status(store, with("step", 0.001)), 400); // far more slabs than a sweep draws
    EXPECT_FALSE(sendStudyHolds("MIP 13 mm / 5 mm coronal"));
}

TEST_F(ServerPacsStore, RefusedCredentialsAnswer401BeforeAnythingIsDrawn) {
    // The series is opened with the credentials; the server that sends it has none.
    {
        LoopbackServer opener(options(orthanc(true)));
        openSendSource(*opener.client());
    }
    LoopbackServer server(options(orthanc(false)));
    auto c = server.client();
    const auto res = c->Post("/api/pacs/orthanc/store", sweepBody(14).dump(), "application/json");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 401) << res->body;
    EXPECT_NE(nlohmann::json::parse(res->body)["error"].get<std::string>().find("credentials"),
              std::string::npos)
        << res->body;
    EXPECT_EQ(res->body.find(orthancStateFile("password")), std::string::npos);
    EXPECT_FALSE(sendStudyHolds("MIP 14 mm / 5 mm coronal"));
}

TEST_F(ServerPacsStore, AStoreThePacsRefusesEndsFailedWith502AndStoresNothing) {
    const FaultProxy proxy(mDir.path(), {"--refuse-store"});
    LoopbackServer server(options(orthanc(true, proxy.port())));
    auto c = server.client();
    openSendSource(*c); // the proxy passes the retrieve
    const nlohmann::json body = sweepBody(12);
    const auto posted = c->Post("/api/pacs/orthanc/store", body.dump(), "application/json");
    const auto seen = pollJob(*c, posted, "/api/pacs/stores/");
    ASSERT_FALSE(seen.empty());
    const nlohmann::json& last = seen.back();
    ASSERT_EQ(last["state"], "failed") << last.dump();
    EXPECT_EQ(last["status"], 502) << last.dump();
    EXPECT_FALSE(last["error"].get<std::string>().empty());
    EXPECT_EQ(last["drawn"], last["total"]); // every slab was drawn; the store was refused
    EXPECT_EQ(last["stored"], 0);
    EXPECT_NE(proxy.log().find("REFUSED"), std::string::npos) << proxy.log();
    EXPECT_EQ(last["description"], "MIP 12 mm / 5 mm coronal");
    EXPECT_FALSE(sendStudyHolds("MIP 12 mm / 5 mm coronal"));
}

TEST_F(ServerPacsStore, ASendCancelledWhileDrawingEndsCancelledAndStoresNothing) {
    LoopbackServer server(options(orthanc(true)));
    auto c = server.client();
    openSendSource(*c);
    nlohmann::json body = sweepBody(1); // many slabs, so that the cancel comes while they are drawn
    body["step"] = 0.05;
    body["size"] = "256x256";
    const auto posted = c->Post("/api/pacs/orthanc/store", body.dump(), "application/json");
    ASSERT_TRUE(posted);
    ASSERT_EQ(posted->status, 202) << posted->body;
    const std::string id = std::to_string(nlohmann::json::parse(posted->body)["id"].get<std::uint64_t>());
    const auto cancelled = c->Post(("/api/pacs/stores/" + id + "/cancel").c_str(), "{}", "application/json");
    ASSERT_TRUE(cancelled);
    EXPECT_EQ(cancelled->status, 200) << cancelled->body;
    const auto seen = pollJob(*c, posted, "/api/pacs/stores/");
    ASSERT_FALSE(seen.empty());
    const nlohmann::json& last = seen.back();
    ASSERT_EQ(last["state"], "cancelled") << last.dump();
    EXPECT_EQ(last["status"], nullptr) << last.dump();
    EXPECT_LT(last["drawn"].get<int>(), last["total"].get<int>());
    EXPECT_EQ(last["stored"], 0);
    EXPECT_EQ(last["description"], "MIP 1 mm / 0.05 mm coronal");
    EXPECT_FALSE(sendStudyHolds("MIP 1 mm / 0.05 mm coronal"));

    const auto unknown = c->Post("/api/pacs/stores/999999/cancel", "{}", "application/json");
    ASSERT_TRUE(unknown);
    EXPECT_EQ(unknown->status, 404) << unknown->body;
}

} // namespace
