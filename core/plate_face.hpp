// The flat target plate (wall.kind = plate) as geometry both backends share: an immovable face
// normal to the jet axis, a disk of diameter wall.diameter (3D) or a segment of that length
// (2D). A face only: a grain meets it while its centre is over the face and in front of it.
#pragma once

#include "core/dim.hpp"
#include "core/jet_geometry.hpp"
#include "core/particles.hpp"
#include "core/scene.hpp"

namespace granjet {

// The partner id of plate contacts in the momentum transfers handed to the analysis
// (PairImpulse::j); the partner position is the grain's mirror image through the face.
inline constexpr GrainId kPlateId = -1;

template <int D>
class PlateFace {
 public:
  static constexpr int kAxis = kJetAxis<D>;

  explicit PlateFace(double diameter) : radius_(0.5 * diameter) {}

  // The centre's height above the face plane, and whether the centre is over the face.
  double height(const Vec<D>& x) const { return x[kAxis] - kTargetSurface; }
  bool over_face(Vec<D> x) const {
    x[kAxis] = 0.0;
    return x.squaredNorm() <= radius_ * radius_;
  }
  // The point of the face, rim included, nearest to x: below x while x is over the face, else
  // on the rim. A thin plate's edge is where grains passing beside a narrow plate touch it.
  Vec<D> nearest_point(Vec<D> x) const {
    x[kAxis] = 0.0;
    const double lateral = x.norm();
    if (lateral > radius_) x *= radius_ / lateral;
    x[kAxis] = kTargetSurface;
    return x;
  }
  // Grain x's mirror image through its nearest face point: r_i - r_j then spans grain and image
  // as for two grains in contact (over the face, the mirror image through the face plane). The
  // half behind the face lies outside every bin when the layers start at the face
  // (analysis.height_origin = wall_surface); from the target grains' centre plane (wall_centres)
  // it counts, as the segment to a target grain would.
  Vec<D> mirror(const Vec<D>& x) const { return 2.0 * nearest_point(x) - x; }
  // The unit normal from the face towards the grains in front of it.
  static Vec<D> outward() {
    Vec<D> n = Vec<D>::Zero();
    n[kAxis] = 1.0;
    return n;
  }
  double radius() const { return radius_; }

 protected:
  double radius_;
};

}  // namespace granjet
