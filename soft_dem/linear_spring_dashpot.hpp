// The study's contact law (model §2): a linear spring-dashpot along the normal [3.1], a
// tangential spring-dashpot [3.2] with Coulomb sliding [3.3], coefficients from the scene's
// (e, t_c) by [3.4] and [3.5] (soft_dem/contact_coefficients.hpp). contact.model = linear.
//
// It is also the prototype of a contact law (ARCHITECTURE.md, "A contact law"): a class
// template Law<D, kFriction>, kFriction meaning "with its tangential part" (the factory,
// make_dem_simulator, passes true when the scene needs contact history or rotation), with
//   kNeedsHistory, kNeedsRotation  what the simulator keeps and integrates: the tangential
//                                  history u_t of each touching pair (and against the plate),
//                                  the spins and torques; false compiles them out;
//   kUnsupported                   why the law cannot run in D dimensions (empty: it can; the
//                                  factory then refuses contact.model with this reason);
//   Law(const ContactSpec&, dt)    its coefficients from the scene's contact keys;
//   force(g, v_rel, shear)         the force on i from j (ContactGeometryOf<V>, the velocity of
//                                  i's surface relative to j's, u_t advanced in place), a
//                                  template over V = Vec<D> and LaneVec<D> that selects rather
//                                  than branches (the force pass's loop must vectorise);
//   elastic_energy(g, shear)       for the energy books;
//   peak_overlap(spec, v)          the deepest overlap of two unit grains meeting head-on at
//                                  relative normal speed v, undamped (an upper bound), for the
//                                  run budget's refusal of scenes that would blow up;
//   Wall, against_wall()           the law of a grain against the immovable plate, where the
//                                  geometry's lever_j is 0 and the partner has infinite mass.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string_view>
#include <type_traits>

#include "core/dim.hpp"
#include "core/scene.hpp"
#include "soft_dem/adhesion.hpp"
#include "soft_dem/contact_coefficients.hpp"
#include "soft_dem/contact_geometry.hpp"
#include "soft_dem/coulomb_tangential.hpp"

namespace granjet::dem {

template <int D, bool kFriction>
struct LinearSpringDashpot {
  static constexpr bool kNeedsHistory = kFriction;
  static constexpr bool kNeedsRotation = kFriction;
  static constexpr std::string_view kUnsupported = "";
  using Wall = LinearSpringDashpot;

  LinearSpringDashpot(const ContactSpec& spec, double time_step)
      : LinearSpringDashpot(contact_coefficients(spec), time_step) {}
  LinearSpringDashpot(const ContactCoefficients& coefficients, double time_step)
      : c(coefficients), dt(time_step), inv_kt(1.0 / coefficients.kt) {}

  ContactCoefficients c;
  double dt;
  double inv_kt;  // sliding resets the spring often: multiply, do not divide

  // [3.1] with k_n from [3.4]: the undamped amplitude v / omega_0 = v t_c / sqrt(pi^2 + ln^2 e),
  // at most v t_c / pi.
  static double peak_overlap(const ContactSpec& spec, double speed) {
    return speed * spec.contact_time / std::numbers::pi;
  }

  // A grain against the immovable plate moves with its own mass, a pair with half of it: twice
  // the pair's springs and dashpots give the pair's e and t_c, [3.4] and [3.5] (equal masses
  // m = 1).
  Wall against_wall() const {
    ContactCoefficients w = c;
    w.kn *= 2.0;
    w.eta_n *= 2.0;
    w.kt *= 2.0;
    w.eta_t *= 2.0;
    return {w, dt};
  }

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
    V f = with_adhesion(f_n, c.adhesion) * g.n;
    if constexpr (kFriction)
      f += coulomb_tangential<D, V>(g.n, v_rel, v_n, shear, dt, c.kt, c.eta_t, inv_kt,
                                    c.mu * std::abs(f_n));
    return f;
  }

  double elastic_energy(const ContactGeometry<D>& g, const Vec<D>& shear) const {
    double e = 0.5 * c.kn * g.overlap * g.overlap + adhesion_energy(g.overlap, c.adhesion);
    if constexpr (kFriction) e += 0.5 * c.kt * shear.squaredNorm();
    return e;
  }
};

}  // namespace granjet::dem
