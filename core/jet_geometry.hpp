// The geometry every jet scene shares, whichever backend runs it or analysis measures it: the
// axis the jet flies along and the region its grains are removed from. Scene geometry, not a
// property of the dimension, so it lives here rather than in Dim<D>.
#pragma once

#include "core/dim.hpp"
#include "core/scene.hpp"

namespace granjet {

// The target grains (wall.kind = tethered or fixed) have one diameter d and sit centred on the
// target plane, 0 on the jet axis. The target's surface, their front face, lies d/2 in front of
// it: the plate (wall.kind = plate) puts its face there in their place, so the jet's front row
// keeps the scene's gap to the target, and analysis.height_origin = wall_surface starts there.
inline constexpr double kTargetGrainDiameter = 1.0;
inline constexpr double kTargetSurface = 0.5 * kTargetGrainDiameter;

// The position on the jet axis of the measuring layers' h = 0 (model §6 "Height origin", an
// assumption of the reproduction): the target grains' centre plane, or their top surface.
inline double height_origin_position(HeightOrigin origin) {
  return origin == HeightOrigin::kWallSurface ? kTargetSurface : 0.0;
}

// The axis the jet moves along (towards -infinity) onto the target at 0: 2D x (the target is
// the line x = 0), 3D z (the plane z = 0).
template <int D>
inline constexpr int kJetAxis = D == 3 ? 2 : 0;

// Whether a jet grain at x has left the region and is removed: farther than region.radius from
// the jet axis, or more than region.below behind the target plane.
template <int D>
bool outside_region(const RegionSpec& region, const Vec<D>& x) {
  constexpr int kAxis = kJetAxis<D>;
  const double lateral2 = x.squaredNorm() - x[kAxis] * x[kAxis];
  return lateral2 > region.radius * region.radius || x[kAxis] < -region.below;
}

}  // namespace granjet
