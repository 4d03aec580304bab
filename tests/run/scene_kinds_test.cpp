// The scene kinds' table (run/scene_kinds.cpp): one entry per kind, its word parsed by the scene
// file, and what the budget and a quick campaign read from it agree with the scene.
#include "run/scene_kinds.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <sstream>
#include <string>

#include "run/scene_file.hpp"

namespace granjet {
namespace {

const std::string kScenes = GRANJET_SCENES_DIR;

TEST(SceneKinds, EveryKindHasOneEntryWhoseWordTheSceneFileParses) {
  std::set<SceneKind> kinds;
  std::set<std::string> words;
  for (const SceneKindTraits& k : scene_kinds()) {
    kinds.insert(k.kind);
    words.insert(k.word);
    std::istringstream ini("[scene]\nkind = " + k.word + "\n");
    EXPECT_EQ(parse_scene(ini, "test", {}).kind, k.kind) << k.word;
    EXPECT_EQ(&scene_kind(k.kind), &k);
  }
  for (SceneKind k : {SceneKind::kJet, SceneKind::kBinary, SceneKind::kGas, SceneKind::kHcs})
    EXPECT_EQ(kinds.count(k), 1u);
  EXPECT_EQ(words.size(), scene_kinds().size());
}

TEST(SceneKinds, ShippedScenesGiveTheirGrainsSpeedsAndScaledTimes) {
  const Scene jet = load_scene(kScenes + "/jet2d.ini", {});
  EXPECT_EQ(scene_kind(jet.kind).grains(jet), 8000.0 + 67.0);  // the column and its row
  EXPECT_EQ(scene_kind(jet.kind).contact_speed(jet).value, jet.jet.speed);
  const auto times = scene_kind(jet.kind).scaled_times(jet);
  ASSERT_EQ(times.size(), 2u);
  EXPECT_EQ(times[0].second, jet.analysis.window_start);
  EXPECT_EQ(times[1].second, jet.analysis.window_end);

  const Scene gas = load_scene(kScenes + "/gas3d.ini", {});
  EXPECT_EQ(scene_kind(gas.kind).grains(gas), static_cast<double>(gas.gas.grains));
  // The rms relative speed of a Maxwellian gas at T: sqrt(2 D T).
  EXPECT_DOUBLE_EQ(scene_kind(gas.kind).contact_speed(gas).value,
                   std::sqrt(6.0 * gas.gas.temperature));
  EXPECT_EQ(scene_kind(gas.kind).scaled_times(gas).at(0).first, "gas.equilibration");

  const Scene binary = load_scene(kScenes + "/binary.ini", {});
  EXPECT_EQ(scene_kind(binary.kind).grains(binary), 2.0);
  EXPECT_TRUE(scene_kind(binary.kind).sampled_every_step);
  EXPECT_TRUE(scene_kind(binary.kind).samples(binary).key.empty());
}

}  // namespace
}  // namespace granjet
