// Campaign files expanded into runs: products of swept keys, seed lists, stable names, --quick,
// --only, the scene hash, and malformed files refused naming the group and key.
#include "campaign/campaign_plan.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "core/errors.hpp"
#include "run/scene_file.hpp"

namespace granjet {
namespace {

CampaignFile parse(const std::string& text) {
  std::istringstream in(text);
  return parse_campaign(in, "test.ini", GRANJET_SCENES_DIR);
}

CampaignPlan plan(const std::string& text, PlanOptions options = {}) {
  if (options.out_dir.empty()) options.out_dir = "DIR";
  return plan_campaign(parse(text), options);
}

// The key of the InputError that planning `text` throws ("" when it throws none).
std::string refused_key(const std::string& text, PlanOptions options = {}) {
  try {
    plan(text, options);
  } catch (const InputError& e) {
    return e.key();
  }
  return "";
}

const char* const kSweep = R"(
[campaign]
seeds = 1..3
[rheology]
results = F5.3, F5.5
scene = jet3d.ini
contact.friction = 0, 0.2
jet.phi_tilde = 0.3, 0.5, 0.9
wall.kind = fixed
[binary]
results = T4.1
scene = binary.ini
seeds = 4
)";

TEST(CampaignPlan, SweptKeysMakeTheirProductTimesTheSeedsWithStableNames) {
  const CampaignPlan p = plan(kSweep);
  ASSERT_EQ(p.runs.size(), 2u * 3u * 3u + 1u);
  ASSERT_EQ(p.ensembles.size(), 6u + 1u);
  // The first swept key varies slowest, seeds fastest.
  EXPECT_EQ(p.runs[0].name, "rheology/friction-0_phi_tilde-0.3.seed1");
  EXPECT_EQ(p.runs[2].name, "rheology/friction-0_phi_tilde-0.3.seed3");
  EXPECT_EQ(p.runs[3].name, "rheology/friction-0_phi_tilde-0.5.seed1");
  EXPECT_EQ(p.runs[9].name, "rheology/friction-0.2_phi_tilde-0.3.seed1");
  EXPECT_EQ(p.runs.back().name, "binary/binary.seed4");  // the group's own seeds
  EXPECT_EQ(p.runs[0].base, std::filesystem::path("DIR/rheology/friction-0_phi_tilde-0.3.seed1"));
  EXPECT_EQ(p.ensembles[0].base, std::filesystem::path("DIR/rheology/friction-0_phi_tilde-0.3"));
  EXPECT_EQ(p.ensembles[0].runs, (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_TRUE(p.ensembles[0].analysed);
  EXPECT_FALSE(p.ensembles.back().analysed);  // the binary scene has no field analysis
  // Each run's scene carries the fixed override, its swept values and its seed.
  const Scene& s = p.runs[10].scene;
  EXPECT_EQ(s.contact.friction, 0.2);
  EXPECT_EQ(s.jet.phi_tilde, 0.3);
  EXPECT_EQ(s.wall.kind, WallKind::kFixed);
  EXPECT_EQ(s.run.seed, 2u);
  // Costs: jet3d runs 50,000 steps (t_end 100 at dt 0.002); its 200 d column is not used up
  // by t = 100, so between half and all of its grains are there on average. The binary
  // scene's two grains stay.
  const RunCost& jet = p.runs[0].cost;
  EXPECT_EQ(jet.steps, 50000);
  EXPECT_GT(jet.grains, 20000);
  EXPECT_GT(jet.particle_steps, 0.5 * jet.grains * 50000.0);
  EXPECT_LT(jet.particle_steps, 1.0 * jet.grains * 50000.0);
  EXPECT_DOUBLE_EQ(p.runs.back().cost.particle_steps, 2.0 * p.runs.back().cost.steps);
}

TEST(CampaignPlan, ExpansionIsTheSameEveryTime) {
  const CampaignPlan a = plan(kSweep), b = plan(kSweep);
  ASSERT_EQ(a.runs.size(), b.runs.size());
  for (std::size_t r = 0; r < a.runs.size(); ++r) {
    EXPECT_EQ(a.runs[r].name, b.runs[r].name);
    EXPECT_EQ(a.runs[r].hash, b.runs[r].hash);
  }
}

TEST(CampaignPlan, HashFollowsTheResolvedSceneAndBackendOnly) {
  const CampaignPlan p = plan(kSweep);
  EXPECT_EQ(p.runs[0].hash, scene_hash("soft_dem", p.runs[0].scene_ini));
  EXPECT_NE(p.runs[0].hash, p.runs[1].hash);  // another seed
  EXPECT_NE(scene_hash("soft_dem", p.runs[0].scene_ini),
            scene_hash("event_driven", p.runs[0].scene_ini));
  // The resolved scene reparsed (as the run's .ini file is) gives the same scene text.
  std::istringstream ini(p.runs[0].scene_ini);
  EXPECT_EQ(scene_to_ini(parse_scene(ini, "resolved", {})), p.runs[0].scene_ini);
}

TEST(CampaignPlan, QuickKeepsOneSeedAndShortensTimeAndWindowAlike) {
  PlanOptions o;
  o.quick = true;
  const CampaignPlan p = plan(std::string(kSweep) + "quick_fraction = 1\n", o);
  ASSERT_EQ(p.runs.size(), 6u + 1u);
  const Scene& s = p.runs[0].scene;
  EXPECT_DOUBLE_EQ(s.run.t_end, 10.0);  // the default quick_fraction, 0.1
  EXPECT_DOUBLE_EQ(s.analysis.window_start, 5.0);
  EXPECT_DOUBLE_EQ(s.analysis.window_end, 10.0);
  EXPECT_EQ(s.run.seed, 1u);
  EXPECT_DOUBLE_EQ(p.runs.back().scene.run.t_end, 0.5);  // binary's quick_fraction = 1
}

TEST(CampaignPlan, OnlyKeepsTheGroupsServingTheIds) {
  PlanOptions o;
  o.only = {"T4.1"};
  EXPECT_EQ(plan(kSweep, o).runs.size(), 1u);
  o.only = {"F5.5", "T4.1"};
  EXPECT_EQ(plan(kSweep, o).runs.size(), 19u);
  o.only = {"F9.9"};
  EXPECT_EQ(refused_key(kSweep, o), "--only");
}

TEST(CampaignPlan, MalformedFilesNameTheGroupAndKey) {
  const std::string head = "[g]\nresults = X\nscene = jet3d.ini\n";
  EXPECT_EQ(refused_key(head + "jet.phi_tildee = 0.3\n"), "[g] jet.phi_tildee");
  EXPECT_EQ(refused_key(head + "jet.phi_tilde = 0.3, 1.5\n"), "[g] jet.phi_tilde");
  EXPECT_EQ(refused_key(head + "jet.phi_tilde = 0.3,,0.5\n"), "[g] jet.phi_tilde");
  EXPECT_EQ(refused_key(head + "jet.phi_tilde = 0.3, 0.3\n"), "[g] jet.phi_tilde");
  EXPECT_EQ(refused_key(head + "seeds = 3..1\n"), "[g] seeds");
  EXPECT_EQ(refused_key(head + "quick_fraction = 2\n"), "[g] quick_fraction");
  EXPECT_EQ(refused_key(head + "colour = red\n"), "[g] colour");
  EXPECT_EQ(refused_key(head + "backend = lammps\n"), "[g] backend");
  EXPECT_EQ(refused_key(head + "run.dt = 0.5\n"), "[g] run.dt");  // dt >= t_c
  EXPECT_EQ(refused_key(head + "run.t_end = 1\nrun.t_end = 2\n"), "[g] run.t_end");
  EXPECT_EQ(refused_key("[g]\nresults = X\n"), "[g] scene");
  EXPECT_EQ(refused_key("[g]\nscene = jet3d.ini\n"), "[g] results");
  EXPECT_EQ(refused_key("[g]\nresults = X\nscene = nowhere.ini\n"), "[g] scene");
  EXPECT_EQ(refused_key("[F5.3]\nresults = X\nscene = jet3d.ini\n"), "test.ini:1");
  EXPECT_EQ(refused_key("jet.grains = 3\n" + head), "jet.grains");
  EXPECT_EQ(refused_key("[campaign]\nseed = 1\n" + head), "[campaign] seed");
  EXPECT_EQ(refused_key("[campaign]\n"), "test.ini");  // no group
  EXPECT_EQ(refused_key(head), "");
}

}  // namespace
}  // namespace granjet
