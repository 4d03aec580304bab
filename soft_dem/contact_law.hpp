// The soft-sphere contact law [3.1]-[3.3]: linear spring-dashpot in the normal direction,
// tangential spring-dashpot with Coulomb sliding. A small evaluator for the one pair loop; its
// static traits let the loop drop history and rotation when the scene is frictionless.
#pragma once

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "core/dim.hpp"
#include "soft_dem/contact_coefficients.hpp"
#include "soft_dem/lane_vec.hpp"

namespace granjet::dem {

// Geometry of one contact between grains i and j: n points from j to i, the lever arms reach
// the common contact point on the line of centres (l_i + l_j = |r_i - r_j|), so the tangential
// force conserves angular momentum exactly. V is Vec<D>, or LaneVec<D> in the force pass.
template <class V>
struct ContactGeometryOf {
  V n;
  double overlap;
  double lever_i;
  double lever_j;
};
template <int D>
using ContactGeometry = ContactGeometryOf<Vec<D>>;

template <class V>
inline ContactGeometryOf<V> contact_geometry(const V& r_ij, double dist, double radius_i,
                                             double radius_j) {
  const double overlap = radius_i + radius_j - dist;
  return {r_ij * (1.0 / dist), overlap, radius_i - 0.5 * overlap, radius_j - 0.5 * overlap};
}

inline Vec<2> spin_cross(double w, const Vec<2>& r) { return Dim<2>::spin_cross(w, r); }
inline Vec<3> spin_cross(const Vec<3>& w, const Vec<3>& r) { return Dim<3>::spin_cross(w, r); }

// The velocity of i's surface relative to j's at their contact point (w: spins, kRotation:
// whether the grains turn): du_t/dt of [3.2] with its rotation term, and du_n/dt of [3.1]. V is Vec<D> with Dim<D>::Spin, or LaneVec<D> with its spin type.
template <bool kRotation, class V, class S>
inline V relative_velocity(const V& v_i, const V& v_j, const S& w_i, const S& w_j,
                           const ContactGeometryOf<V>& g) {
  V v_rel = v_i - v_j;
  if constexpr (kRotation) v_rel -= spin_cross(S(g.lever_i * w_i + g.lever_j * w_j), g.n);
  return v_rel;
}

template <int D, bool kFriction>
struct LinearSpringDashpot {
  static constexpr bool kNeedsHistory = kFriction;
  static constexpr bool kNeedsRotation = kFriction;

  LinearSpringDashpot(const ContactCoefficients& coefficients, double time_step)
      : c(coefficients), dt(time_step), inv_kt(1.0 / coefficients.kt) {}

  ContactCoefficients c;
  double dt;
  double inv_kt;  // sliding resets the spring often: multiply, do not divide

  // Force on i from j (j receives its negative). v_rel is the velocity of i's surface relative
  // to j's at the contact point. The tangential history `shear` (u_t) grows by v_t dt and is
  // reset to the Coulomb limit when sliding. V is Vec<D>, or LaneVec<D> (the same roundings).
  template <class V>
  V force(const ContactGeometryOf<V>& g, const std::type_identity_t<V>& v_rel,
          std::type_identity_t<V>& shear) const {
    const double v_n = v_rel.dot(g.n);
    // [3.1] normal: F_n = -k_n u_n - eta_n du_n/dt with u_n = -overlap; never below the floor
    // (contact.clamp_normal).
    const double f_n = std::max(c.normal_floor, c.kn * g.overlap - c.eta_n * v_n);
    V f = f_n * g.n;
    if constexpr (kFriction) {
      const V v_t = v_rel - v_n * g.n;
      shear += dt * v_t;
      shear -= shear.dot(g.n) * g.n;  // keep u_t in the tangent plane as the contact turns
      // [3.2] trial tangential force, [3.3] Coulomb: slide at mu_p |F_n| along the trial.
      // Both outcomes are computed and one is selected: in a jet about half the contacts
      // slide, in no order a branch predictor could learn.
      const V trial = -c.kt * shear - c.eta_t * v_t;
      const double limit = c.mu * std::abs(f_n);
      const double f_t2 = trial.squaredNorm();
      const bool slides = f_t2 > limit * limit;
      const V sliding = trial * (limit / std::sqrt(f_t2));
      const V f_t = slides ? sliding : trial;
      shear = slides ? V(-(sliding + c.eta_t * v_t) * inv_kt) : shear;
      f += f_t;
    }
    return f;
  }

  double elastic_energy(const ContactGeometry<D>& g, const Vec<D>& shear) const {
    double e = 0.5 * c.kn * g.overlap * g.overlap;
    if constexpr (kFriction) e += 0.5 * c.kt * shear.squaredNorm();
    return e;
  }
};

}  // namespace granjet::dem
