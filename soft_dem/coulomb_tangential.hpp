// The tangential part both soft contact laws share: a spring k_t on the tangential displacement
// u_t accumulated since first touch and a dashpot eta_t on the slip velocity [3.2], the trial
// force kept while it lies inside the Coulomb limit mu_p |F_n| and scaled onto it otherwise
// [3.3] (model §2). A law supplies k_t, eta_t and the limit (constant for the linear law; the
// Hertz-Mindlin law's grow with the contact radius).
#pragma once

#include <cmath>
#include <type_traits>

#include "soft_dem/contact_geometry.hpp"

namespace granjet::dem {

// Returns the tangential force on i and advances u_t (`shear`) in place: by v_t dt, kept in the
// tangent plane as the contact turns, and reset to the spring length of the Coulomb limit when
// the contact slides. v_rel is i's surface velocity relative to j's, v_n its normal part.
// inv_k_t = 1/k_t, which the caller may have computed once. V is Vec<D> or LaneVec<D> (the
// same roundings); both outcomes are computed and one selected, since in a jet about half the
// contacts slide, in no order a branch predictor could learn, and the force pass's loop must
// vectorise.
template <int D, class V>
V coulomb_tangential(const V& n, const std::type_identity_t<V>& v_rel, double v_n,
                     std::type_identity_t<V>& shear, double dt, double k_t, double eta_t,
                     double inv_k_t, double limit) {
  const V v_t = v_rel - v_n * n;
  shear += dt * v_t;
  shear -= shear.dot(n) * n;
  const V trial = -k_t * shear - eta_t * v_t;  // [3.2]
  const double f_t2 = trial.squaredNorm();
  const bool slides = f_t2 > limit * limit;  // [3.3]
  const V sliding = trial * (limit / std::sqrt(f_t2));
  shear = select_components<D>(slides, V(-(sliding + eta_t * v_t) * inv_k_t), shear);
  return select_components<D>(slides, sliding, trial);
}

}  // namespace granjet::dem
