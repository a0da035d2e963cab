// The server's PACS browser against the real Orthanc of the pacs fixture: searches, opening a series as a
// dataset (progress, the same images as the folder, the disk cache), and the statuses of failures.
#include "FaultProxy.h"
#include "JobPolling.h"
#include "LoopbackServer.h"
#include "OrthancState.h"
#include "TempDir.h"

#include <gtest/gtest.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

namespace {

namespace fs = std::filesystem;
using namespace vots;
using namespace vots::test;

const std::string RAMP_STUDY = std::string(RAMP_SERIES) + ".0";
const std::string CRANIUM_STUDY = std::string(CRANIUM_SERIES) + ".0";

server::DicomWebService service(const std::string& name, const std::string& port, bool withCredentials) {
    server::DicomWebService s;
    s.name = name;
    s.endpoint = pacs::parseDicomWebEndpoint("dicomweb+http://127.0.0.1:" + port + "/dicom-web");
    if (withCredentials) s.access = orthancAccess();
    return s;
}

/// A loopback port with nothing listening on it: bound for a moment to learn a free one, then closed.
std::string closedPort() {
    const int sock = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t length = sizeof address;
    if (sock < 0 || bind(sock, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
        getsockname(sock, reinterpret_cast<sockaddr*>(&address), &length) != 0)
        throw std::runtime_error("cannot find a free port");
    close(sock);
    return std::to_string(ntohs(address.sin_port));
}

/// A loopback port that takes connections (the kernel completes them) and never answers a byte.
class SilentPort {
public:
    SilentPort() {
        mSocket = socket(AF_INET, SOCK_STREAM, 0);
        sockaddr_in address{};
        address.sin_family = AF_INET;
        address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        socklen_t length = sizeof address;
        if (mSocket < 0 || bind(mSocket, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
            listen(mSocket, 16) != 0 ||
            getsockname(mSocket, reinterpret_cast<sockaddr*>(&address), &length) != 0)
            throw std::runtime_error("cannot listen on a loopback port");
        mPort = std::to_string(ntohs(address.sin_port));
    }
    ~SilentPort() { close(mSocket); }
    SilentPort(const SilentPort&) = delete;
    SilentPort& operator=(const SilentPort&) = delete;
    const std::string& port() const { return mPort; }

private:
    int mSocket = -1;
    std::string mPort;
};

class ServerPacs : public ::testing::Test {
protected:
    ServerPacs() {
        fs::create_directories(mDir.path() / "data");
        // The same files as a folder dataset: what an opened series must look like.
        fs::create_directory_symlink(fs::path(orthancState()) / "series" / "ramp",
                                     mDir.path() / "data" / "ramp");
    }

    server::ServerOptions options(const std::vector<server::DicomWebService>& services) const {
        server::ServerOptions o;
        o.dataDirs = {mDir.path() / "data"};
        o.cacheDir = mDir.path() / "cache";
        o.warmUpFits = false;
        o.dicomWebServices = services;
        return o;
    }

    /// POSTs the open and polls it until it ends; returns every answer seen.
    static std::vector<nlohmann::json> openSeries(httplib::Client& c, const std::string& service,
                                                  const std::string& study, const std::string& series) {
        const auto posted =
            c.Post(("/api/pacs/" + service + "/studies/" + study + "/series/" + series + "/open").c_str(),
                   "{}", "application/json");
        return pollJob(c, posted, "/api/pacs/opens/");
    }

    /// The retrieved series' folder holds this process's spool folder alone, and that is empty.
    bool keptNothing() const {
        const fs::path root = mDir.path() / "cache" / "dicomweb";
        const fs::path spool = root / ("spool-" + std::to_string(getpid()));
        for (const auto& entry : fs::directory_iterator(root))
            if (entry.path() != spool) return false;
        return fs::is_empty(spool);
    }

    TempDir mDir;
};

TEST_F(ServerPacs, ListsTheServicesWithoutCredentials) {
    LoopbackServer server(options({service("orthanc", orthancStateFile("port"), true)}));
    const auto res = server.client()->Get("/api/pacs");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 200);
    const auto body = nlohmann::json::parse(res->body);
    ASSERT_EQ(body["services"].size(), 1u);
    EXPECT_EQ(body["services"][0]["name"], "orthanc");
    EXPECT_EQ(body["services"][0]["url"],
              "dicomweb+http://127.0.0.1:" + orthancStateFile("port") + "/dicom-web");
    EXPECT_EQ(res->body.find(orthancStateFile("password")), std::string::npos);
}

TEST_F(ServerPacs, AServerWithoutAPacsListsNoneAndWritesNothingForThem) {
    LoopbackServer server(options({}));
    auto c = server.client();
    const auto res = c->Get("/api/pacs");
    ASSERT_TRUE(res);
    EXPECT_EQ(nlohmann::json::parse(res->body)["services"].size(), 0u);
    const auto search = c->Get("/api/pacs/orthanc/studies");
    ASSERT_TRUE(search);
    EXPECT_EQ(search->status, 404) << search->body;
    EXPECT_FALSE(fs::exists(mDir.path() / "cache" / "dicomweb"));
}

TEST_F(ServerPacs, SearchesStudiesAndListsTheirSeries) {
    LoopbackServer server(options({service("orthanc", orthancStateFile("port"), true)}));
    auto c = server.client();
    const auto all = c->Get("/api/pacs/orthanc/studies?modality=CT&patientName=Vots*");
    ASSERT_TRUE(all);
    ASSERT_EQ(all->status, 200) << all->body;
    const auto studies = nlohmann::json::parse(all->body)["studies"];
    const auto cranium = std::find_if(studies.begin(), studies.end(),
                                      [](const nlohmann::json& s) { return s["studyUid"] == CRANIUM_STUDY; });
    ASSERT_NE(cranium, studies.end());
    EXPECT_EQ((*cranium)["instanceCount"], 108);
    EXPECT_EQ((*cranium)["patientName"], "Vots^Phantom");

    const auto none = c->Get("/api/pacs/orthanc/studies?modality=MR");
    ASSERT_TRUE(none);
    EXPECT_EQ(nlohmann::json::parse(none->body)["studies"].size(), 0u);
    const auto old = c->Get("/api/pacs/orthanc/studies?dateTo=1900-01-01");
    ASSERT_TRUE(old);
    EXPECT_EQ(nlohmann::json::parse(old->body)["studies"].size(), 0u);

    const auto series = c->Get(("/api/pacs/orthanc/studies/" + RAMP_STUDY + "/series").c_str());
    ASSERT_TRUE(series);
    ASSERT_EQ(series->status, 200) << series->body;
    const auto list = nlohmann::json::parse(series->body)["series"];
    ASSERT_EQ(list.size(), 1u);
    EXPECT_EQ(list[0]["seriesUid"], RAMP_SERIES);
    EXPECT_EQ(list[0]["description"], "ramp");
    EXPECT_EQ(list[0]["modality"], "CT");
    EXPECT_EQ(list[0]["instanceCount"], 20);
}

TEST_F(ServerPacs, AnOpenedSeriesRendersAsTheSameFilesFromAFolder) {
    LoopbackServer server(options({service("orthanc", orthancStateFile("port"), true)}));
    auto c = server.client();
    const auto seen = openSeries(*c, "orthanc", RAMP_STUDY, RAMP_SERIES);
    ASSERT_FALSE(seen.empty());
    const nlohmann::json& last = seen.back();
    ASSERT_EQ(last["state"], "done") << last.dump();
    EXPECT_EQ(last["received"], 20);
    EXPECT_EQ(last["total"], 20);
    EXPECT_EQ(last["fromCache"], false);
    const std::string dataset = last["dataset"];
    EXPECT_EQ(dataset, "orthanc-1_2_826_0_1_3680043_10_1234_201");
    for (const nlohmann::json& answer : seen) // progress never runs backwards
        EXPECT_LE(answer["received"].get<int>(), 20);

    const auto datasets = c->Get("/api/datasets");
    ASSERT_TRUE(datasets);
    EXPECT_NE(datasets->body.find(dataset), std::string::npos);
    for (const char* query : {"&size=48x48&mode=reference&renderer=grid", "&size=48x48&eps=1%25&mode=mip",
                              "&size=48x48&eps=1%25&mode=minip&cam=az=30,el=20"}) {
        const auto pacsFrame = c->Get(("/render?dataset=" + dataset + query).c_str());
        const auto folderFrame = c->Get((std::string("/render?dataset=ramp") + query).c_str());
        ASSERT_TRUE(pacsFrame && folderFrame);
        ASSERT_EQ(pacsFrame->status, 200) << pacsFrame->body;
        ASSERT_EQ(folderFrame->status, 200) << folderFrame->body;
        EXPECT_EQ(pacsFrame->get_header_value("Content-Type"), "image/png");
        EXPECT_GT(pacsFrame->body.size(), 200u) << query;
        EXPECT_EQ(pacsFrame->body, folderFrame->body) << query;
    }
}

TEST_F(ServerPacs, ASecondOpenReadsTheKeptSeriesWithoutARetrieve) {
    FaultProxy proxy(mDir.path());
    {
        LoopbackServer server(options({service("orthanc", proxy.port(), true)}));
        const auto seen = openSeries(*server.client(), "orthanc", CRANIUM_STUDY, CRANIUM_SERIES);
        ASSERT_FALSE(seen.empty());
        ASSERT_EQ(seen.back()["state"], "done") << seen.back().dump();
        EXPECT_EQ(seen.back()["fromCache"], false);
    }
    EXPECT_EQ(proxy.seriesRetrieves(CRANIUM_SERIES), 1);
    // A new server over the same cache folder lists the kept series at once, asking the PACS nothing;
    // opened again, the series is announced (unchanged), not retrieved again.
    const std::string requestsBefore = proxy.log();
    LoopbackServer server(options({service("orthanc", proxy.port(), true)}));
    auto c = server.client();
    const auto listed = c->Get("/api/datasets");
    ASSERT_TRUE(listed);
    EXPECT_NE(listed->body.find("orthanc-1_2_826_0_1_3680043_10_1234_202"), std::string::npos)
        << listed->body;
    EXPECT_EQ(proxy.log(), requestsBefore);
    const auto seen = openSeries(*c, "orthanc", CRANIUM_STUDY, CRANIUM_SERIES);
    ASSERT_FALSE(seen.empty());
    ASSERT_EQ(seen.back()["state"], "done") << seen.back().dump();
    EXPECT_EQ(seen.back()["fromCache"], true);
    EXPECT_EQ(seen.back()["received"], 108);
    EXPECT_EQ(proxy.seriesRetrieves(CRANIUM_SERIES), 1);
    const auto frame = c->Get(("/render?dataset=" + seen.back()["dataset"].get<std::string>() +
                               "&size=32x32&mode=reference&renderer=grid")
                                  .c_str());
    ASSERT_TRUE(frame);
    EXPECT_EQ(frame->status, 200) << frame->body;
}

TEST_F(ServerPacs, RefusedCredentialsAnswer401AndNeverTheSecret) {
    LoopbackServer server(options({service("nocreds", orthancStateFile("port"), false)}));
    auto c = server.client();
    const auto res = c->Get("/api/pacs/nocreds/studies");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 401) << res->body;
    const auto body = nlohmann::json::parse(res->body);
    EXPECT_NE(body["error"].get<std::string>().find("credentials"), std::string::npos) << res->body;

    const auto seen = openSeries(*c, "nocreds", RAMP_STUDY, RAMP_SERIES);
    ASSERT_FALSE(seen.empty());
    EXPECT_EQ(seen.back()["state"], "failed");
    EXPECT_EQ(seen.back()["status"], 401) << seen.back().dump();
    EXPECT_EQ(seen.back()["dataset"], nullptr);
    EXPECT_TRUE(keptNothing()) << "a failed open left files behind";
}

TEST_F(ServerPacs, AServiceThatIsDownAnswers502) {
    server::DicomWebService down = service("down", closedPort(), true);
    LoopbackServer server(options({down}));
    auto c = server.client();
    for (const std::string& path :
         {std::string("/api/pacs/down/studies"), "/api/pacs/down/studies/" + RAMP_STUDY + "/series"}) {
        const auto res = c->Get(path.c_str());
        ASSERT_TRUE(res);
        EXPECT_EQ(res->status, 502) << res->body;
        const auto body = nlohmann::json::parse(res->body);
        EXPECT_NE(body["error"].get<std::string>().find("cannot connect"), std::string::npos) << res->body;
        EXPECT_EQ(res->body.find(orthancStateFile("password")), std::string::npos);
    }
    const auto seen = openSeries(*c, "down", RAMP_STUDY, RAMP_SERIES);
    ASSERT_FALSE(seen.empty());
    EXPECT_EQ(seen.back()["status"], 502) << seen.back().dump();
}

TEST_F(ServerPacs, AServiceThatNeverAnswersAnswers504) {
    SilentPort silent;
    server::DicomWebService slow = service("slow", silent.port(), true);
    slow.access.readTimeoutSeconds = 1;
    LoopbackServer server(options({slow}));
    auto c = server.client();
    const auto res = c->Get("/api/pacs/slow/studies?modality=CT");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 504) << res->body;
    const auto body = nlohmann::json::parse(res->body);
    EXPECT_NE(body["error"].get<std::string>().find("timed out"), std::string::npos) << res->body;
    const auto seen = openSeries(*c, "slow", RAMP_STUDY, RAMP_SERIES);
    ASSERT_FALSE(seen.empty());
    EXPECT_EQ(seen.back()["status"], 504) << seen.back().dump();
}

TEST_F(ServerPacs, ASearchGivesUpOnASilentPacsLongBeforeTheRetrievesTimeout) {
    SilentPort silent;
    const server::DicomWebService slow = service("slow", silent.port(), true); // the retrieve's 120 s
    ASSERT_GT(slow.access.readTimeoutSeconds, 60);
    LoopbackServer server(options({slow}));
    auto c = server.client();
    c->set_read_timeout(150, 0);
    const auto start = std::chrono::steady_clock::now();
    const auto res = c->Get("/api/pacs/slow/studies?modality=CT");
    const auto waited = std::chrono::steady_clock::now() - start;
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 504) << res->body;
    EXPECT_NE(res->body.find("timed out (no answer for 15 s)"), std::string::npos) << res->body;
    EXPECT_LT(waited, std::chrono::seconds(60)); // the search's own bound, not the retrieve's
}

TEST_F(ServerPacs, AnOpenCancelledWhileThePacsIsSilentEndsCancelled) {
    SilentPort silent;
    server::DicomWebService slow = service("slow", silent.port(), true);
    slow.access.readTimeoutSeconds = 2;
    LoopbackServer server(options({slow}));
    auto c = server.client();
    const auto posted =
        c->Post(("/api/pacs/slow/studies/" + RAMP_STUDY + "/series/" + RAMP_SERIES + "/open").c_str(), "{}",
                "application/json");
    ASSERT_TRUE(posted);
    ASSERT_EQ(posted->status, 202) << posted->body;
    const std::string id = std::to_string(nlohmann::json::parse(posted->body)["id"].get<std::uint64_t>());
    const auto cancelled = c->Post(("/api/pacs/opens/" + id + "/cancel").c_str(), "{}", "application/json");
    ASSERT_TRUE(cancelled);
    EXPECT_EQ(cancelled->status, 200) << cancelled->body;
    nlohmann::json open;
    for (int i = 0; i < 400; ++i) { // the announcement waits out the read timeout, then the open ends
        open = nlohmann::json::parse(c->Get(("/api/pacs/opens/" + id).c_str())->body);
        if (open["state"] == "cancelled" || open["state"] == "failed" || open["state"] == "done") break;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    EXPECT_EQ(open["state"], "cancelled") << open.dump();
    EXPECT_EQ(open["status"], nullptr);
    EXPECT_EQ(open["dataset"], nullptr);
    EXPECT_TRUE(keptNothing());
}

TEST_F(ServerPacs, ASeriesOverTheMemoryBudgetIsRefusedBeforeItsPixelsAreAskedFor) {
    FaultProxy proxy(mDir.path());
    server::ServerOptions o = options({service("orthanc", proxy.port(), true)});
    o.memoryBudgetBytes = 1; // less than any process holds: every load is refused
    LoopbackServer server(o);
    const auto seen = openSeries(*server.client(), "orthanc", CRANIUM_STUDY, CRANIUM_SERIES);
    ASSERT_FALSE(seen.empty());
    EXPECT_EQ(seen.back()["state"], "failed");
    EXPECT_EQ(seen.back()["status"], 507) << seen.back().dump();
    EXPECT_NE(seen.back()["error"].get<std::string>().find("memory budget"), std::string::npos);
    EXPECT_EQ(proxy.seriesRetrieves(CRANIUM_SERIES), 0);
    EXPECT_TRUE(keptNothing()) << "a refused open left files behind";
}

TEST_F(ServerPacs, BadRequestsAreRefusedBeforeThePacsIsAsked) {
    LoopbackServer server(options({service("orthanc", orthancStateFile("port"), true)}));
    auto c = server.client();
    const auto expectStatus = [&](const std::string& path, int status) {
        const auto res = c->Get(path.c_str());
        ASSERT_TRUE(res) << path;
        EXPECT_EQ(res->status, status) << path << ": " << res->body;
        EXPECT_TRUE(nlohmann::json::parse(res->body, nullptr, false).contains("error")) << path;
    };
    expectStatus("/api/pacs/elsewhere/studies", 404);
    expectStatus("/api/pacs/orthanc/studies?dateFrom=yesterday", 400);
    expectStatus("/api/pacs/orthanc/studies?limit=0", 400);
    expectStatus("/api/pacs/orthanc/studies?patientName=" + std::string(65, 'a'), 400);
    expectStatus("/api/pacs/opens/99", 404);
    const auto unknownSeries = openSeries(*c, "orthanc", RAMP_STUDY, "1.2.3.4");
    ASSERT_FALSE(unknownSeries.empty());
    EXPECT_EQ(unknownSeries.back()["status"], 404) << unknownSeries.back().dump();
}

} // namespace
