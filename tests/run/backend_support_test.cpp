// What each backend declares it makes of a scene (core/scene_support.hpp): the features it
// refuses, naming the key; the keys it adapts, with both values; what it ignores. And that the
// campaign still recognises a run stored before the declarations, whose file holds the scene as
// requested rather than as run.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/h5md_writer.hpp"
#include "campaign/campaign_plan.hpp"
#include "campaign/campaign_runner.hpp"
#include "core/errors.hpp"
#include "run/backend_factory.hpp"
#include "run/scene_file.hpp"

namespace granjet {
namespace {

namespace fs = std::filesystem;

Scene shipped(const std::string& file, const std::vector<std::string>& overrides = {}) {
  return load_scene(std::string(GRANJET_SCENES_DIR) + "/" + file, overrides);
}

// The key and message of the InputError that check_backend throws ("" when it throws none).
std::pair<std::string, std::string> refusal(const std::string& backend, const Scene& scene) {
  try {
    check_backend(backend, scene);
  } catch (const InputError& e) {
    return {e.key(), e.what()};
  }
  return {"", ""};
}

TEST(BackendSupport, EventDrivenAdaptsTetheredTargetsAndTouchingLatticesAndSaysWhatItIgnores) {
  const Scene requested = shipped("jet3d.ini");  // tethered target, jet.spacing = 1, mu_p = 0.2
  const SceneSupport s = check_backend("event_driven", requested);
  ASSERT_EQ(s.adaptations.size(), 2u);
  EXPECT_EQ(s.adaptations[0].key, "wall.kind");
  EXPECT_EQ(s.adaptations[0].requested, "tethered");
  EXPECT_EQ(s.adaptations[0].resolved, "fixed");
  EXPECT_EQ(s.adaptations[1].key, "jet.spacing");
  EXPECT_EQ(s.adaptations[1].requested, "1");
  EXPECT_EQ(s.adaptations[1].resolved, "1.001");
  EXPECT_EQ(s.resolved.wall.kind, WallKind::kFixed);
  EXPECT_EQ(s.resolved.jet.spacing, 1.001);
  EXPECT_EQ(requested.wall.kind, WallKind::kTethered);  // the request is left as it was
  EXPECT_EQ(describe("event_driven", s.adaptations[1]),
            "event_driven: jet.spacing = 1 becomes 1.001 (hard grains in contact have no "
            "collision order)");
  ASSERT_FALSE(s.notes.empty());
  EXPECT_NE(s.notes.front().find("contact.friction = 0.2 is ignored"), std::string::npos);
  // The resolved scene is what it runs: resolving it again changes nothing.
  EXPECT_TRUE(check_backend("event_driven", s.resolved).adaptations.empty());
  EXPECT_EQ(scene_to_ini(check_backend("event_driven", s.resolved).resolved),
            scene_to_ini(s.resolved));
}

TEST(BackendSupport, EventDrivenKeepsPlatesSpacedLatticesAndGasesAsTheyAre) {
  EXPECT_TRUE(check_backend("event_driven", shipped("jet2d.ini", {"wall.kind=plate"}))
                  .adaptations.empty());  // jet2d's lattice is spaced at 1.1 d
  EXPECT_TRUE(check_backend("event_driven", shipped("gas3d.ini")).adaptations.empty());
  EXPECT_TRUE(check_backend("event_driven", shipped("binary.ini")).adaptations.empty());
}

TEST(BackendSupport, SoftDemRunsEverySceneAsItIsAndAdvisesAgainstCoarseSteps) {
  for (const char* file : {"jet3d.ini", "jet2d.ini", "gas3d.ini", "hcs2d.ini", "binary.ini"}) {
    const Scene requested = shipped(file);
    const SceneSupport s = check_backend("soft_dem", requested);
    EXPECT_TRUE(s.adaptations.empty()) << file;
    EXPECT_TRUE(s.notes.empty()) << file;
    EXPECT_EQ(scene_to_ini(s.resolved), scene_to_ini(requested)) << file;
  }
  const SceneSupport coarse = check_backend("soft_dem", shipped("jet2d.ini", {"run.dt=0.03"}));
  ASSERT_EQ(coarse.notes.size(), 1u);
  EXPECT_NE(coarse.notes.front().find("coarser than 0.05 t_c"), std::string::npos);
}

TEST(BackendSupport, RefusalsNameTheKeyAndSayWhy) {
  const auto [forces, forces_why] = refusal(
      "event_driven", shipped("jet3d.ini", {"output.fields=position,velocity,radius,id,force"}));
  EXPECT_EQ(forces, "output.fields");
  EXPECT_NE(forces_why.find("impulses only"), std::string::npos) << forces_why;
  const auto [both, both_why] =
      refusal("event_driven",
              shipped("jet3d.ini", {"output.fields=position,velocity,radius,id,contacts,omega"}));
  EXPECT_EQ(both, "output.fields");
  EXPECT_NE(both_why.find("impulses only"), std::string::npos) << both_why;  // every reason
  EXPECT_NE(both_why.find("smooth hard spheres"), std::string::npos) << both_why;
  const auto [spin, spin_why] =
      refusal("soft_dem", shipped("jet3d.ini", {"output.fields=position,velocity,radius,id,omega",
                                                "contact.friction=0"}));
  EXPECT_EQ(spin, "output.fields");
  EXPECT_NE(spin_why.find("contact.friction = 0"), std::string::npos) << spin_why;
  EXPECT_EQ(refusal("soft_dem", shipped("jet3d.ini", {"output.fields=position,velocity,radius,"
                                                      "id,omega,force,contacts"}))
                .first,
            "");
  EXPECT_EQ(refusal("gpu", shipped("jet3d.ini")).first, "--backend");
  // Overlapping target grains (wall.spacing < 1): soft grains only; a plate has no grains.
  const auto [smooth, smooth_why] =
      refusal("event_driven", shipped("jet3d.ini", {"wall.spacing=0.75"}));
  EXPECT_EQ(smooth, "wall.spacing");
  EXPECT_NE(smooth_why.find("hard grains cannot"), std::string::npos) << smooth_why;
  EXPECT_EQ(refusal("soft_dem", shipped("jet3d.ini", {"wall.spacing=0.75"})).first, "");
  EXPECT_EQ(
      refusal("event_driven", shipped("jet3d.ini", {"wall.spacing=0.75", "wall.kind=plate"})).first,
      "");
}

TEST(BackendSupport, BackendsDeclareWhatTheyCount) {
  EXPECT_FALSE(backend_named("soft_dem").counts_events);
  EXPECT_TRUE(backend_named("event_driven").counts_events);
  EXPECT_THROW(backend_named("gpu"), InputError);
}

// A campaign run finished before the backends declared their adaptations stored the scene as
// requested (a tethered target); the campaign now plans the resolved one (fixed) and still
// finds that run complete.
TEST(BackendSupport, CampaignFindsRunsThatStoredTheRequestedScene) {
  const fs::path dir =
      fs::temp_directory_path() / ("granjet_support_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  std::istringstream text(
      "[campaign]\nseeds = 1\n[hard]\nresults = HC\nscene = jet2d.ini\n"
      "backend = event_driven\njet.grains = 50\n");
  PlanOptions options;
  options.out_dir = dir;
  const CampaignPlan plan =
      plan_campaign(parse_campaign(text, "test.ini", GRANJET_SCENES_DIR), options);
  ASSERT_EQ(plan.runs.size(), 1u);
  const PlannedRun& run = plan.runs.front();
  EXPECT_EQ(run.scene.wall.kind, WallKind::kFixed);
  ASSERT_EQ(run.adaptations.size(), 1u);
  EXPECT_NE(run.adaptations.front().find("wall.kind = tethered becomes fixed"), std::string::npos);

  fs::create_directories(run.base.parent_path());
  analysis::RunMetadata old;
  old.backend = "event_driven";
  old.dimension = 2;
  old.scene_ini = scene_to_ini(shipped("jet2d.ini", run.overrides));  // as requested
  analysis::H5mdWriter<2>(run.file(".h5"), old, 1).finish();
  std::ofstream(run.file(".json")) << R"({"status": "complete"})";
  EXPECT_EQ(stored_state(run), RunState::kComplete);
  // Another request is another run.
  old.scene_ini = scene_to_ini(shipped("jet2d.ini", {"jet.grains=51"}));
  fs::remove(run.file(".h5"));
  analysis::H5mdWriter<2>(run.file(".h5"), old, 1).finish();
  EXPECT_EQ(stored_state(run), RunState::kMissing);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace granjet
