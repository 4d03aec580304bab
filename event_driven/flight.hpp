// Free flight between collisions [model §8] and the prediction of a pair's next contact. No force
// acts between events, so a grain's state is its position at its own time t and a constant
// velocity; it is streamed to the present only when an event touches it (DynamO's delayed
// states).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/dim.hpp"

namespace granjet::ed {

inline constexpr double kNever = std::numeric_limits<double>::infinity();

// Everything a pair prediction reads of a partner, in one 64-byte cache line.
template <int D>
struct alignas(64) Flight {
  Vec<D> x = Vec<D>::Zero();  // position at time t
  double t = 0.0;
  Vec<D> v = Vec<D>::Zero();
  double radius = 0.0;

  Vec<D> position_at(double time) const { return x + v * (time - t); }
  void stream_to(double time) {
    x += v * (time - t);
    t = time;
  }
};

// A pair with separation dr = x_j - x_i and relative velocity dv = v_j - v_i touches at centre
// distance sigma when |dr + dv t|^2 = sigma^2, i.e. a t^2 + 2 b t + c = 0 with b = dr.dv,
// c = dr^2 - sigma^2, a = dv^2.
struct PairQuadratic {
  double b, c, a;
};

template <class VecT>
PairQuadratic pair_quadratic(const VecT& dr, const VecT& dv, double sigma) {
  return {dr.dot(dv), dr.squaredNorm() - sigma * sigma, dv.squaredNorm()};
}

// Time until the pair of the quadratic (b, c, a) touches, or kNever. Receding (b >= 0) and
// grazing (no real root) pairs never touch; an overlapping or touching pair that approaches
// collides at once (delay 0), so round-off can neither hide a collision nor let grains pass
// through each other. The smaller root is taken in the cancellation-free form
// c / (-b + sqrt(b^2 - a c)): the textbook (-b - sqrt(.)) / a loses every digit near contact,
// where a c << b^2.
//
// Written with selects, no branches, so that a loop over many pairs vectorises; c <= 0 gives a
// root <= 0, hence 0 (and then b^2 - a c >= b^2 > 0).
inline double contact_delay(double b, double c, double a) {
  const double disc = b * b - a * c;
  const double root = std::max(c / (-b + std::sqrt(std::max(disc, 0.0))), 0.0);
  return b < 0.0 && disc > 0.0 ? root : kNever;
}

}  // namespace granjet::ed
