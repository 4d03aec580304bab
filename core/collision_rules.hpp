// Hard-sphere binary collision rules [2.1]-[2.4], general masses. Pure functions: the
// event-driven backend and the tests use exactly these. An inverse mass of 0 is an immovable
// (infinite-mass) grain, e.g. a fixed wall grain.
#pragma once

#include "core/dim.hpp"

namespace granjet {

// Reduced mass m1 m2 / (m1 + m2) from inverse masses; infinite mass on one side gives the
// other's mass.
inline double reduced_mass(double inv_m1, double inv_m2) { return 1.0 / (inv_m1 + inv_m2); }

// Direct collision [2.1]-[2.2]: k = (r2 - r1)/|r2 - r1|, v12 = v1 - v2. The normal relative
// velocity k.v12 is reversed and scaled by e; the tangential part is untouched. Returns the
// impulse received by grain 1 (grain 2 receives its negative). For equal masses this is
// v1' = v1 - (1+e)/2 (k.v12) k, v2' = v2 + (1+e)/2 (k.v12) k.
template <class VecT>
VecT collide(const VecT& k, VecT& v1, VecT& v2, double inv_m1, double inv_m2, double e) {
  const double j = (1.0 + e) * reduced_mass(inv_m1, inv_m2) * k.dot(v1 - v2);
  v1 -= (j * inv_m1) * k;
  v2 += (j * inv_m2) * k;
  return -j * k;
}

// Inverse collision [2.3]-[2.4]: the pre-collision velocities that collide() maps onto
// (v1, v2); for equal masses v1'' = v1 - (1+e)/(2e) (k.v12) k.
template <class VecT>
void collide_inverse(const VecT& k, VecT& v1, VecT& v2, double inv_m1, double inv_m2, double e) {
  const double j = (1.0 + e) / e * reduced_mass(inv_m1, inv_m2) * k.dot(v1 - v2);
  v1 -= (j * inv_m1) * k;
  v2 += (j * inv_m2) * k;
}

// Kinetic energy lost in a direct collision: (1 - e^2)/2 mu (k.v12)^2, which is
// (1 - e^2)/4 m (k.v12)^2 for equal masses [model §1].
template <class VecT>
double collision_energy_loss(const VecT& k, const VecT& v1, const VecT& v2, double inv_m1,
                             double inv_m2, double e) {
  const double vn = k.dot(v1 - v2);
  return 0.5 * (1.0 - e * e) * reduced_mass(inv_m1, inv_m2) * vn * vn;
}

}  // namespace granjet
