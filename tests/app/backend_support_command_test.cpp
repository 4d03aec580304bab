// What `granjet run` does with a backend's declarations: a note per adaptation on stderr and in
// the log, the adaptations in the summary, the scene as run in /parameters/granjet/scene (and
// `granjet info --scene`) with the request beside it in /parameters/granjet/requested_scene,
// and the stored scene redoing the run bit for bit.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <sstream>

#include "analysis/h5md_reader.hpp"
#include "command_fixture.hpp"
#include "run/scene_file.hpp"

namespace granjet {
namespace {

namespace fs = std::filesystem;

using BackendSupportCommand = testing::CommandTest;

const std::string kSmallJet =
    " --quiet --set jet.grains=300 --set run.t_end=6 --set output.interval=3"
    " --set analysis.window_start=2 --set analysis.window_end=6";

Scene stored_scene(const std::string& ini) {
  std::istringstream in(ini);
  return parse_scene(in, "stored", {});
}

TEST_F(BackendSupportCommand, EventDrivenRunStoresTheSceneItRanBesideTheRequestedOne) {
  ASSERT_EQ(
      granjet("run " + scene("jet3d.ini") + " --backend event_driven" + kSmallJet + " --out " +
              (dir_ / "ed.h5").string() + " --summary " + (dir_ / "ed.json").string()),
      0)
      << err_;
  // One note per adaptation, on stderr and in the log.
  EXPECT_NE(err_.find("granjet: event_driven: wall.kind = tethered becomes fixed ("),
            std::string::npos)
      << err_;
  EXPECT_NE(err_.find("granjet: event_driven: jet.spacing = 1 becomes 1.001 ("), std::string::npos)
      << err_;
  std::ifstream log_in(dir_ / "ed.log");
  const std::string log{std::istreambuf_iterator<char>(log_in), {}};
  EXPECT_NE(log.find("wall.kind = tethered becomes fixed"), std::string::npos);

  const nlohmann::json adaptations = summary("ed.json")["adaptations"];
  ASSERT_EQ(adaptations.size(), 2u) << adaptations.dump();
  EXPECT_EQ(adaptations[0]["key"], "wall.kind");
  EXPECT_EQ(adaptations[0]["requested"], "tethered");
  EXPECT_EQ(adaptations[0]["resolved"], "fixed");
  EXPECT_EQ(adaptations[1]["key"], "jet.spacing");
  EXPECT_FALSE(adaptations[1]["reason"].get<std::string>().empty());

  const analysis::FileSummary stored = analysis::read_summary(dir_ / "ed.h5");
  const Scene ran = stored_scene(stored.scene_ini);
  EXPECT_EQ(ran.wall.kind, WallKind::kFixed);
  EXPECT_EQ(ran.jet.spacing, 1.001);
  ASSERT_FALSE(stored.requested_scene_ini.empty());
  const Scene requested = stored_scene(stored.requested_scene_ini);
  EXPECT_EQ(requested.wall.kind, WallKind::kTethered);
  EXPECT_EQ(requested.jet.spacing, 1.0);

  // `info --scene` prints the scene as run, which redoes the run: nothing left to adapt, the
  // same frames bit for bit.
  ASSERT_EQ(granjet("info " + (dir_ / "ed.h5").string() + " --scene"), 0) << err_;
  fs::copy_file(dir_ / "stdout.txt", dir_ / "ran.ini");
  ASSERT_EQ(
      granjet("run " + (dir_ / "ran.ini").string() + " --backend event_driven --quiet --out " +
              (dir_ / "again.h5").string() + " --summary " + (dir_ / "again.json").string()),
      0)
      << err_;
  EXPECT_EQ(err_.find("becomes"), std::string::npos) << err_;
  EXPECT_FALSE(summary("again.json").contains("adaptations"));
  EXPECT_TRUE(analysis::read_summary(dir_ / "again.h5").requested_scene_ini.empty());
  for (const char* group : {"/particles", "/observables", "/fields", "/analysis"})
    EXPECT_TRUE(same_hdf5(dir_ / "ed.h5", dir_ / "again.h5", group)) << group;
}

TEST_F(BackendSupportCommand, RunsTheBackendTakesAsTheyAreStoreOneScene) {
  for (const char* backend : {"soft_dem", "event_driven"}) {
    SCOPED_TRACE(backend);
    ASSERT_EQ(granjet("run " + scene("jet2d.ini") + " --backend " + backend +
                      " --set wall.kind=plate" + kSmallJet + " --out " +
                      (dir_ / "run.h5").string() + " --summary " + (dir_ / "run.json").string()),
              0)
        << err_;
    EXPECT_EQ(err_.find("becomes"), std::string::npos) << err_;
    EXPECT_FALSE(summary("run.json").contains("adaptations"));
    EXPECT_TRUE(analysis::read_summary(dir_ / "run.h5").requested_scene_ini.empty());
  }
}

TEST_F(BackendSupportCommand, RefusedFeaturesExitTwoNamingTheKeyBeforeAnyFileIsWritten) {
  EXPECT_EQ(granjet("run " + scene("jet3d.ini") + " --backend event_driven" + kSmallJet +
                    " --set output.fields=position,velocity,radius,id,force --out " +
                    (dir_ / "no.h5").string()),
            2);
  EXPECT_NE(err_.find("output.fields: force and contacts need contact forces"), std::string::npos)
      << err_;
  EXPECT_FALSE(fs::exists(dir_ / "no.h5.partial"));
  EXPECT_FALSE(fs::exists(dir_ / "no.log"));
}

}  // namespace
}  // namespace granjet
