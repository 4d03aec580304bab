// The flat target plate (wall.kind = plate): an immovable rigid wall of infinite mass, a disk of
// diameter wall.diameter (3D) or a segment of that length (2D) normal to the jet axis, facing the
// jet. A grain that reaches the face collides with it by [2.1]-[2.2] with an infinite-mass
// partner: the normal velocity is reversed and scaled by e, the tangential one kept.
//
// The plate is a face only: a grain collides when its centre is over the face (within the
// plate's radius of the jet axis) and its surface reaches the face plane. Its edge has no rim,
// so a grain whose centre passes beside the edge flies on however close it comes, and its back
// is not modelled: a grain behind the face plane (it got there past the edge) never collides.
// A grain whose centre comes over the face while its surface is already through the plane
// (sliding in over the edge) collides at once, so no grain passes through the face.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/particles.hpp"
#include "core/plate_face.hpp"
#include "event_driven/flight.hpp"

namespace granjet::ed {

template <int D>
class Plate : public PlateFace<D> {
 public:
  using PlateFace<D>::kAxis;
  using PlateFace<D>::height;

  explicit Plate(double diameter) : PlateFace<D>(diameter) {}

  // Time until the grain (centre x at its own time, velocity v, radius r) touches the face, or
  // kNever.
  double contact_delay(const Vec<D>& x, const Vec<D>& v, double r) const {
    const double height = this->height(x), closing = -v[kAxis];
    if (!(closing > 0.0) || height < 0.0) return kNever;  // receding, or behind the face
    const double reach = std::max(0.0, (height - r) / closing);
    const double through = height / closing;  // the centre would cross the plane
    // Over the face while |lateral(t)| <= radius: a t^2 + 2 b t + c <= 0.
    Vec<D> lateral = x, drift = v;
    lateral[kAxis] = 0.0;
    drift[kAxis] = 0.0;
    const double a = drift.squaredNorm(), b = lateral.dot(drift);
    const double c = lateral.squaredNorm() - this->radius_ * this->radius_;
    const double disc = b * b - a * c;
    double enter = 0.0, leave = kNever;
    if (c > 0.0) {  // beside the edge now: over the face only if it moves in
      if (!(b < 0.0) || !(disc > 0.0)) return kNever;
      enter = c / (-b + std::sqrt(disc));  // the smaller root, cancellation-free
    }
    if (a > 0.0) leave = (-b + std::sqrt(std::max(disc, 0.0))) / a;
    const double when = std::max(reach, enter);
    return when <= leave && when < through ? when : kNever;
  }

  // The unit normal from a grain in front of the face towards it (the k of [2.1]).
  static Vec<D> inward() {
    Vec<D> k = Vec<D>::Zero();
    k[kAxis] = -1.0;
    return k;
  }
};

}  // namespace granjet::ed
