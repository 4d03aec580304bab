// jet_cuts: with run.lengthwise_cuts = auto a jet's column is cut lengthwise while its pieces
// stay kPieceReaches reaches across (soft_dem/jet_cuts.hpp), along the jet axis of its
// dimension; scenes without a jet are not, nor any scene by default.
#include "soft_dem/jet_cuts.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/errors.hpp"
#include "run/scene_file.hpp"

namespace granjet::dem {
namespace {

// The scene with run.lengthwise_cuts = auto and `overrides`.
Scene scene(const std::string& file, std::vector<std::string> overrides = {}) {
  overrides.insert(overrides.begin(), "run.lengthwise_cuts=auto");
  return load_scene(std::string(GRANJET_SCENES_DIR) + "/" + file, overrides);
}

TEST(JetCuts, AWideColumnIsCutLengthwiseWhileItsPiecesStayWide) {
  // jet3d_large: a 30-d column, reach 1.4 d: two halvings leave pieces 15 d across (10.7
  // reaches), a third would leave 7.5 d.
  const LengthwiseCuts large = jet_cuts<3>(scene("jet3d_large.ini"), 1.4);
  EXPECT_EQ(large.axis, kJetAxis<3>);
  EXPECT_EQ(large.levels, 2);
  EXPECT_EQ(jet_cuts<3>(scene("jet3d_large.ini"), 1.5).levels, 2);  // 15 d is 10 reaches
  EXPECT_EQ(jet_cuts<3>(scene("jet3d_large.ini"), 1.6).levels, 0);
  EXPECT_EQ(jet_cuts<3>(scene("jet3d_large.ini", {"jet.diameter=60"}), 1.4).levels, 4);
  // jet3d's 10-d column is not cut lengthwise.
  EXPECT_EQ(jet_cuts<3>(scene("jet3d.ini"), 1.3).levels, 0);
}

TEST(JetCuts, ARectangularColumnHalvesItsLongSideFirst) {
  // 40 d x 10 d: the long side halves twice (to 10 d), the short one not at all.
  const Scene rectangle =
      scene("jet3d.ini", {"jet.shape=rectangle", "jet.area=400", "jet.aspect_ratio=4"});
  EXPECT_EQ(jet_cuts<3>(rectangle, 1.0).levels, 2);
}

TEST(JetCuts, A2dStripIsCutAlongX) {
  // jet2d: a strip 30 d wide along x, reach 1.3 d: one halving (15 d), not two (7.5 d).
  const LengthwiseCuts strip = jet_cuts<2>(scene("jet2d.ini"), 1.3);
  EXPECT_EQ(strip.axis, kJetAxis<2>);
  EXPECT_EQ(strip.axis, 0);
  EXPECT_EQ(strip.levels, 1);
}

TEST(JetCuts, OffTheDefaultCutsEveryPartAcrossItsLongestSide) {
  EXPECT_EQ(jet_cuts<3>(scene("jet3d_large.ini", {"run.lengthwise_cuts=off"}), 1.4).levels, 0);
  const Scene as_shipped = load_scene(std::string(GRANJET_SCENES_DIR) + "/jet3d_large.ini", {});
  EXPECT_FALSE(as_shipped.run.lengthwise_cuts);
  EXPECT_EQ(jet_cuts<3>(as_shipped, 1.4).levels, 0);
  EXPECT_THROW(scene("jet3d_large.ini", {"run.lengthwise_cuts=2"}), InputError);
}

TEST(JetCuts, ScenesWithoutAJetAreNotCutLengthwise) {
  EXPECT_EQ(jet_cuts<3>(scene("binary.ini"), 1.3).levels, 0);
  EXPECT_EQ(jet_cuts<3>(scene("gas3d.ini"), 1.3).levels, 0);
}

}  // namespace
}  // namespace granjet::dem
