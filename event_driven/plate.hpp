// The flat target plate (wall.kind = plate): an immovable rigid wall of infinite mass, a disk of
// diameter wall.diameter (3D) or a segment of that length (2D) normal to the jet axis, facing the
// jet. A grain that reaches the face collides with it by [2.1]-[2.2] with an infinite-mass
// partner: the normal velocity is reversed and scaled by e, the tangential one kept.
//
// A grain collides with the face when its centre is over it (within the plate's radius of the
// jet axis) and its surface reaches the face plane. In 2D the segment's two end points are its
// rim, as for the soft plate (core/plate_face.hpp): a grain passing beside the edge collides
// with the end point it comes within its radius of, along the line from the point to its
// centre. The 3D rim (a circle, whose collision time solves a quartic) is not modelled yet: a
// grain whose centre passes beside a disk's edge flies on however close it comes. The back is
// not modelled: a grain behind the face plane (it got there past the edge) never collides with
// the face. A grain whose centre comes over the face while its surface is already through the
// plane (sliding in over a 3D edge) collides at once, so no grain passes through the face.
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
    if constexpr (D == 2) return std::min(face_delay(x, v, r), rim_delay(x, v, r));
    return face_delay(x, v, r);
  }

  // Time until the grain's surface reaches the face plane with its centre over the face.
  double face_delay(const Vec<D>& x, const Vec<D>& v, double r) const {
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

  // 2D: time until the grain touches an end point of the segment while its centre is beside the
  // segment (over it, the face comes first), or kNever.
  double rim_delay(const Vec<D>& x, const Vec<D>& v, double r) const requires(D == 2) {
    double first = kNever;
    for (const double side : {-1.0, 1.0}) {
      Vec<D> end = Vec<D>::Zero();
      end[kAxis] = kTargetSurface;
      end[1 - kAxis] = side * this->radius_;
      const PairQuadratic q = pair_quadratic(Vec<D>(x - end), v, r);
      const double t = ed::contact_delay(q.b, q.c, q.a);
      if (t < first && std::abs((x + t * v)[1 - kAxis]) >= this->radius_) first = t;
    }
    return first;
  }

  // The unit normal from a grain at x, touching, towards the plate (the k of [2.1]): towards
  // its nearest point, the face's normal over the face and the line to an end point beside it.
  Vec<D> inward(const Vec<D>& x) const {
    const Vec<D> to_plate = this->nearest_point(x) - x;
    const double distance = to_plate.norm();
    if (distance > 0.0) return to_plate / distance;
    Vec<D> k = Vec<D>::Zero();  // a centre on the face itself: push it back to the front
    k[kAxis] = -1.0;
    return k;
  }
};

}  // namespace granjet::ed
