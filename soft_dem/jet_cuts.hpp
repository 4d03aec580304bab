// How a jet run over MPI ranks may cut its column (run.lengthwise_cuts = auto): lengthwise
// (planes that contain the jet axis) in the bisection's first levels, while the pieces stay
// wide. When the jet hits the target a compression front climbs its column of touching grains
// at about 20 d per unit time, and the contacts behind it are the costliest part of a step's
// pass. A cut across the column has the
// front cross from the part below into the part above between two looks at the work; a cut
// along it leaves each part its share of the front wherever the front is. The price is the
// halo: a piece w across holds ghosts within one reach of each lengthwise face, about
// 2 reach / w of its grains. Pieces of at least kPieceReaches reaches keep that to a fifth.
// Counted on the 2e5-grain jet over 16 ranks (a 30-d column, reach 1.4 d: two lengthwise
// levels, pieces 15 d across), they cut the busiest rank's pass by a sixth while the front
// climbs and by 7% over the run, but the ghost exchange they add, as estimated from the
// measured cost of an exchange, takes most of that back; so they are off unless asked for
// (docs/performance.md, "Lengthwise cuts for the column").
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/jet_geometry.hpp"
#include "core/recursive_bisection.hpp"
#include "core/scene.hpp"

namespace granjet::dem {

inline constexpr double kPieceReaches = 10.0;

// The lengthwise levels for `scene` with ghosts within `reach` of a part: each halves the
// column's widest side across the jet axis while the halves stay kPieceReaches reaches across;
// none for scenes without a jet or with run.lengthwise_cuts = off.
template <int D>
LengthwiseCuts jet_cuts(const Scene& scene, double reach) {
  if (scene.kind != SceneKind::kJet || !scene.run.lengthwise_cuts) return {};
  std::vector<double> sides;  // the column's widths across the jet axis
  if constexpr (D == 2) {
    sides = {scene.jet.diameter};
  } else if (scene.jet.shape == JetShape::kRectangle) {
    sides = {std::sqrt(scene.jet.area * scene.jet.aspect_ratio),
             std::sqrt(scene.jet.area / scene.jet.aspect_ratio)};
  } else {
    sides = {scene.jet.diameter, scene.jet.diameter};
  }
  LengthwiseCuts cuts{kJetAxis<D>, 0};
  for (;;) {
    double& widest = *std::max_element(sides.begin(), sides.end());
    if (widest / 2 < kPieceReaches * reach) return cuts;
    widest /= 2;
    ++cuts.levels;
  }
}

}  // namespace granjet::dem
