// /api/datasets gives each dataset's orientation in patient space (docs/API.md), null when unknown.
#include "OrientationPhantom.h"
#include "ServerFixture.h"

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
    EXPECT_TRUE(byName[NEGHIP]["orientation"].is_null()) << "spacings only: nothing known";
    const nlohmann::json& ras = byName["phantom_ras"]["orientation"];
    EXPECT_EQ(ras["axes"], nlohmann::json(RAS_ORDER));
    EXPECT_EQ(ras["directions"], nlohmann::json::array({"R", "A", "S"}));
    EXPECT_EQ(byName["phantom_permuted"]["orientation"]["directions"],
              nlohmann::json::array({"S", "R", "A"}));
}

} // namespace
} // namespace vots::test
