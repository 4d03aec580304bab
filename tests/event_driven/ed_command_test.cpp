// The event-driven backend through the granjet command, end to end [model §8]: the jets on the
// same scene files, the periodic gas scenes and their measured quantities, bit-identical reruns,
// inelastic collapse as exit code 3, bad keys as exit code 2, and `granjet compare`.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "../app/command_fixture.hpp"
#include "analysis/h5md_reader.hpp"
#include "analysis/kinetic_theory.hpp"

namespace granjet {
namespace {

namespace fs = std::filesystem;

using EventDrivenCommand = testing::CommandTest;

TEST_F(EventDrivenCommand, JetsRunOnTheSameSceneFilesAndReportEventCounts) {
  for (const std::string jet : {"jet2d.ini", "jet3d.ini"}) {
    SCOPED_TRACE(jet);
    ASSERT_EQ(granjet("run " + scene(jet) +
                      " --backend event_driven --quiet --set jet.grains=500 --set run.t_end=15"
                      " --set output.interval=5 --out " +
                      (dir_ / "jet.h5").string() + " --summary " + (dir_ / "jet.json").string()),
              0)
        << err_;
    // One note says what the backend made of the scene.
    EXPECT_NE(err_.find("tethered target becomes fixed wall grains"), std::string::npos) << err_;
    const nlohmann::json j = summary("jet.json");
    EXPECT_EQ(j["backend"], "event_driven");
    EXPECT_EQ(j["status"], "complete");
    EXPECT_GT(j["collisions"].get<std::int64_t>(), 1000);
    EXPECT_GT(j["cell_crossings"].get<std::int64_t>(), 0);
    EXPECT_GE(j["events"].get<std::int64_t>(),
              j["collisions"].get<std::int64_t>() + j["cell_crossings"].get<std::int64_t>());
    EXPECT_GT(j["collisions_per_second"].get<double>(), 0.0);
    EXPECT_EQ(analysis::read_summary(dir_ / "jet.h5").frames, 4u);
  }
  // The touching fcc lattice of jet3d is spaced, and said so.
  EXPECT_NE(err_.find("jet.spacing = 1 becomes 1.001"), std::string::npos) << err_;
}

// wall.kind = plate: the flat target replaces the target grains, so the frames hold the jet only.
TEST_F(EventDrivenCommand, JetsRunOnThePlateTargetWithoutTargetGrains) {
  for (const std::string jet : {"jet2d.ini", "jet3d.ini"}) {
    SCOPED_TRACE(jet);
    ASSERT_EQ(granjet("run " + scene(jet) +
                      " --backend event_driven --quiet --set wall.kind=plate"
                      " --set jet.grains=500 --set run.t_end=15 --set output.interval=5 --out " +
                      (dir_ / "jet.h5").string() + " --summary " + (dir_ / "jet.json").string()),
              0)
        << err_;
    EXPECT_EQ(err_.find("tethered"), std::string::npos) << err_;
    const nlohmann::json j = summary("jet.json");
    EXPECT_EQ(j["status"], "complete");
    EXPECT_GT(j["collisions"].get<std::int64_t>(), 1000);
    const auto last = jet == "jet2d.ini" ? analysis::read_frame<2>(dir_ / "jet.h5", 3).id
                                         : analysis::read_frame<3>(dir_ / "jet.h5", 3).id;
    ASSERT_FALSE(last.empty());
    for (const auto id : last) EXPECT_LT(id, 500);  // jet grains only
  }
}

TEST_F(EventDrivenCommand, SameSceneAndSeedGiveBitIdenticalFrames) {
  const std::string args = "run " + scene("jet2d.ini") +
                           " --backend event_driven --quiet --set jet.grains=600"
                           " --set run.t_end=20 --set output.interval=10";
  ASSERT_EQ(granjet(args + " --out " + (dir_ / "a.h5").string()), 0) << err_;
  ASSERT_EQ(granjet(args + " --out " + (dir_ / "b.h5").string()), 0) << err_;
  ASSERT_EQ(granjet(args + " --set run.seed=2 --out " + (dir_ / "c.h5").string()), 0) << err_;
  const auto a = analysis::read_frame<2>(dir_ / "a.h5", 2);
  const auto b = analysis::read_frame<2>(dir_ / "b.h5", 2);
  const auto c = analysis::read_frame<2>(dir_ / "c.h5", 2);
  ASSERT_FALSE(a.position.empty());
  EXPECT_EQ(a.id, b.id);
  EXPECT_TRUE(a.position == b.position);  // bit for bit
  EXPECT_TRUE(a.velocity == b.velocity);
  EXPECT_FALSE(a.position == c.position);
}

TEST_F(EventDrivenCommand, GasScenesReportCompressibilityAndCoolingBesideTheory) {
  ASSERT_EQ(granjet("run " + scene("gas3d.ini") +
                    " --backend event_driven --quiet --set gas.grains=2048 --set run.t_end=15"
                    " --out " +
                    (dir_ / "gas.h5").string() + " --summary " + (dir_ / "gas.json").string()),
            0)
      << err_;
  nlohmann::json j = summary("gas.json");
  EXPECT_DOUBLE_EQ(j["theory"]["compressibility"].get<double>(),
                   analysis::kinetic::carnahan_starling(0.3));
  EXPECT_NEAR(
      j["measured"]["compressibility"].get<double>() / j["theory"]["compressibility"].get<double>(),
      1.0, 0.015);
  EXPECT_NEAR(j["measured"]["temperature"].get<double>(), 1.0, 1e-12);  // elastic: kept

  ASSERT_EQ(granjet("run " + scene("hcs2d.ini") + " --backend event_driven --quiet --out " +
                    (dir_ / "hcs.h5").string() + " --summary " + (dir_ / "hcs.json").string()),
            0)
      << err_;
  j = summary("hcs.json");
  EXPECT_DOUBLE_EQ(j["theory"]["cooling_per_collision"].get<double>(),
                   analysis::kinetic::cooling_per_collision(0.9, 2));
  EXPECT_NEAR(j["measured"]["cooling_per_collision"].get<double>() /
                  j["theory"]["cooling_per_collision"].get<double>(),
              1.0, 0.02);
}

TEST_F(EventDrivenCommand, SoftDemRunsThePeriodicGasToo) {
  const fs::path out = dir_ / "gas.h5";
  ASSERT_EQ(granjet("run " + scene("gas2d.ini") + " --set gas.grains=400 --set run.t_end=1 " +
                    "--set gas.equilibration=0.2 --quiet --out " + out.string() + " --summary " +
                    (dir_ / "gas.json").string()),
            0)
      << err_;
  std::ifstream in(dir_ / "gas.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["backend"], "soft_dem");
  EXPECT_GT(j["measured"]["compressibility"].get<double>(), 1.0);  // a dense gas pushes
}

TEST_F(EventDrivenCommand, BadEventDrivenKeysExitTwoNamingTheKeyAndWhatIsAllowed) {
  const fs::path out = dir_ / "bad.h5";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"ed.restitution_law=soft", "constant | velocity_dependent | tc_model"},
      {"ed.v0=0", "> 0"},
      {"ed.tc=-1", ">= 0"},
      {"gas.phi=0.8", "too dense"},
      {"gas.grains=10", "narrower than 3 diameters"},
      {"gas.equilibration=100", "smaller than run.t_end"}};
  for (const auto& [set, allowed] : cases) {
    EXPECT_EQ(granjet("run " + scene("gas3d.ini") + " --backend event_driven --set " + set +
                      " --out " + out.string()),
              2);
    EXPECT_NE(err_.find(set.substr(0, set.find('='))), std::string::npos) << err_;
    EXPECT_NE(err_.find(allowed), std::string::npos) << err_;
    EXPECT_FALSE(fs::exists(out));
  }
}

TEST_F(EventDrivenCommand, InelasticCollapseExitsThreeNamingGrainsAndTheRemedy) {
  const fs::path out = dir_ / "collapse.h5";
  EXPECT_EQ(granjet("run " + scene("hcs2d.ini") +
                    " --backend event_driven --quiet --set contact.restitution=0.5"
                    " --set gas.phi=0.6 --set gas.grains=1000 --set run.t_end=200"
                    " --set output.interval=50 --out " +
                    out.string()),
            3);
  EXPECT_NE(err_.find("inelastic collapse"), std::string::npos) << err_;
  EXPECT_NE(err_.find("velocity_dependent"), std::string::npos) << err_;
  EXPECT_NE(err_.find("grains"), std::string::npos) << err_;
  EXPECT_TRUE(fs::exists(out.string() + ".partial"));
}

TEST_F(EventDrivenCommand, CompareRunsBothBackendsAndWritesThemSideBySide) {
  const fs::path out = dir_ / "cmp";
  ASSERT_EQ(granjet("compare " + scene("binary.ini") + " --quiet --out " + out.string()), 0)
      << err_;
  for (const std::string file :
       {"soft_dem.h5", "soft_dem.json", "event_driven.h5", "event_driven.json", "compare.json"})
    EXPECT_TRUE(fs::exists(out / file)) << file;
  std::ifstream in(out / "compare.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  const nlohmann::json& e = j["side_by_side"]["measured/restitution"];
  EXPECT_NEAR(e["event_driven"].get<double>(), 0.75, 1e-15);  // hard: exact
  EXPECT_NEAR(e["soft_dem"].get<double>() / 0.75, 1.0, 0.005);
  EXPECT_GT(j["side_by_side"]["wall_seconds"]["soft_dem"].get<double>(), 0.0);
  EXPECT_GT(j["side_by_side"]["collisions_per_second"]["event_driven"].get<double>(), 0.0);
  // A scene that cannot run is refused before anything is written.
  EXPECT_EQ(granjet("compare " + scene("gas2d.ini") + " --set gas.phi=0.95 --out " +
                    (dir_ / "no").string()),
            2);
  EXPECT_FALSE(fs::exists(dir_ / "no"));
}

}  // namespace
}  // namespace granjet
