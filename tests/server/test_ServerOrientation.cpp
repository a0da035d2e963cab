// /api/datasets gives each dataset's orientation in patient space (docs/API.md), null when unknown.
#include "OrientationPhantom.h"
#include "ServerFixture.h"

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

namespace vots::test {
namespace {

TEST(ServerOrientation, DatasetsCarryTheirPatientAxes) {
    const ServerWorld world;
    writePhantomNifti(phantomGrid(RAS_ORDER), (world.data() / "phantom_ras.nii").string());
    writePhantomNrrd(phantomGrid(PERMUTED_ORDER), (world.data() / "phantom_permuted.nrrd").string(), false);
    const LoopbackServer server(world.options());
    const nlohmann::json listed = bodyJson(server.client()->Get("/api/datasets"));
    std::map<std::string, nlohmann::json> byName;
    for (const auto& d : listed["datasets"])
        byName[d["name"].get<std::string>()] = d;
    ASSERT_EQ(byName.size(), 4u) << listed.dump();
    EXPECT_TRUE(byName[BLOBS]["orientation"].is_null()) << "spacings only: nothing known";
    // The real MRI's qform: its grid runs to the patient's left, anterior and superior.
    EXPECT_EQ(byName[MRI_BRAIN]["orientation"]["directions"], nlohmann::json::array({"L", "A", "S"}));
    const nlohmann::json& ras = byName["phantom_ras"]["orientation"];
    EXPECT_EQ(ras["axes"], nlohmann::json(RAS_ORDER));
    EXPECT_EQ(ras["directions"], nlohmann::json::array({"R", "A", "S"}));
    EXPECT_EQ(byName["phantom_permuted"]["orientation"]["directions"],
              nlohmann::json::array({"S", "R", "A"}));
}

// The Cranium, the default dataset, is listed in patient space, so its views and labels are anatomical.
TEST(ServerOrientation, TheCraniumRunsToTheLeftAnteriorAndSuperior) {
    const ServerWorld world;
    std::ifstream in(VOTS_CRANIUM_HEADER);
    std::string header, line;
    while (std::getline(in, line)) {
        if (line.rfind("data file: ", 0) == 0) // the samples stay where scripts/fetch-ct put them
            line = "data file: " + (std::filesystem::path(VOTS_CRANIUM_HEADER).parent_path() /
                                    line.substr(std::string("data file: ").size()))
                                       .string();
        header += line + "\n";
    }
    world.dir().write("data/cranium.nhdr", header);
    const LoopbackServer server(world.options());
    const nlohmann::json listed = bodyJson(server.client()->Get("/api/datasets"));
    for (const auto& d : listed["datasets"]) {
        if (d["name"] != "cranium") continue;
        EXPECT_EQ(d["orientation"]["directions"], nlohmann::json::array({"L", "A", "S"})) << d.dump();
        return;
    }
    ADD_FAILURE() << "no cranium in " << listed.dump();
}

} // namespace
} // namespace vots::test
