// Rolling resistance, an optional part of a soft contact law (contact.rolling_friction = mu_r >
// 0; not in the study): the constant directional torque of model A in Ai, Chen, Rotter & Ooi,
// Powder Technol. 206, 269 (2011), after Zhou et al., Physica A 269, 536 (1999), the
// rolling_friction cdt of LIGGGHTS. On i, with j's opposite,
//   M_r = -mu_r R* |F_n| w_r / |w_r|,   R* = R_i R_j / (R_i + R_j)
// (R* = R_i against the immovable plate), w_r the relative spin w_i - w_j less its twist about
// the normal (in 2D the whole scalar spin difference), F_n the law's normal force. It resists
// the grains rolling on each other and vanishes when they turn together (then their surfaces
// slide, which is the Coulomb part's). Model §2, "Rolling resistance".
//
// Rolling<Law> is the law with the part added: the force pass asks `rolls<Law>` and then feeds
// rolling_torque the contact's relative spin. The torque does not change sign within a step, so
// where w_r passes through 0 under a steady load it flips from step to step with amplitude
// mu_r R* |F_n| dt / I (the known price of model A; it does no net work).
#pragma once

#include <cmath>
#include <type_traits>

#include "core/scene.hpp"
#include "soft_dem/contact_geometry.hpp"

namespace granjet::dem {

template <class Law, bool kWall = false>
struct Rolling : Law {
  static constexpr bool kRolling = true;
  static_assert(Law::kNeedsRotation, "rolling resistance needs the grains to turn");
  using Wall = Rolling<typename Law::Wall, true>;

  Rolling(const ContactSpec& spec, double time_step)
      : Law(spec, time_step), mu_r(spec.rolling_friction) {}
  Rolling(const Law& law, double rolling_friction) : Law(law), mu_r(rolling_friction) {}

  Wall against_wall() const { return {Law::against_wall(), mu_r}; }

  // The torque on i (j receives its negative). V is Vec<D> or LaneVec<D>, S the matching spin
  // (a scalar in 2D); f is the law's force on i at this contact.
  template <class V, class S>
  S rolling_torque(const ContactGeometryOf<V>& g, const S& w_rel, const V& f) const {
    S w_r = w_rel;
    if constexpr (!std::is_arithmetic_v<S>)
      w_r -= w_rel.dot(g.n) * g.n;  // the twist is not rolling
    double norm;
    if constexpr (std::is_arithmetic_v<S>)
      norm = std::abs(w_r);
    else
      norm = std::sqrt(w_r.squaredNorm());
    const double load = mu_r * reduced_radius(g) * std::abs(f.dot(g.n));
    // Grains that do not roll on each other feel none (and no 0/0).
    const double scale = norm > 0.0 ? load / norm : 0.0;
    return S(-scale * w_r);
  }

  double mu_r;

 private:
  // R*, the radii read back from the lever arms: R - delta/2 for a pair, R - delta against the
  // plate.
  template <class V>
  static double reduced_radius(const ContactGeometryOf<V>& g) {
    if constexpr (kWall) {
      return g.lever_i + g.overlap;
    } else {
      const double r_i = g.lever_i + 0.5 * g.overlap, r_j = g.lever_j + 0.5 * g.overlap;
      return r_i * r_j / (r_i + r_j);
    }
  }
};

// Whether a law has the rolling part.
template <class Law>
inline constexpr bool rolls = requires {
  requires Law::kRolling;
};

}  // namespace granjet::dem
