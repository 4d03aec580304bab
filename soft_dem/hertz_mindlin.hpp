// Hertz-Mindlin contact law with Tsuji damping (contact.model = hertz; 3D only), from the same
// scene keys as the linear law: (e, t_c), mu_p, k_t/k_n, eta_t/eta_n, the clamp. For two grains
// of effective radius R_eff = R_i R_j/(R_i + R_j), overlap delta and contact radius
// a = sqrt(R_eff delta):
// - normal, Hertz (Johnson, "Contact Mechanics", 1985, ch. 4; Landau & Lifshitz, "Theory of
//   Elasticity", §9): F_n = (4/3) E* sqrt(R_eff) delta^(3/2) + c_n d(delta)/dt, never below
//   contact.clamp_normal's floor. Its stiffness is S_n = dF/d(delta) = 2 E* a.
// - damping, Tsuji, Tanaka & Ishida, Powder Technol. 71, 239 (1992):
//   c_n = alpha sqrt(m_eff K) delta^(1/4) with K = (4/3) E* sqrt(R_eff), the one power of
//   delta for which e does not depend on the impact speed (the collision's equation has no
//   other scale). Antypov & Elliott, EPL 94, 50004 (2011) give e(alpha) exactly,
//   alpha = sqrt(5) (-ln e)/sqrt(pi^2 + ln^2 e) (the damped Hertz oscillator's phase curve
//   maps onto a linear spring-dashpot's).
// - tangential, Mindlin (J. Appl. Mech. 16, 259, 1949): a spring of no-slip stiffness
//   k_t = 8 G* a = (4 G*/E*) S_n on the history u_t, here k_t = contact.spring_ratio S_n (the
//   ratio of the two stiffnesses, as for the linear law; an elastic material of Poisson ratio
//   nu has 2(1 - nu)/(2 - nu), 0.82 at nu = 0.3), with the dashpot
//   c_t = contact.damping_ratio c_n, and the Coulomb limit mu_p |F_n| as [3.3]. u_t is kept
//   from first touch to separation as for the linear law (no Mindlin-Deresiewicz memory of
//   the loading path), so the tangential spring energy 1/2 k_t |u_t|^2 is not a potential.
// The mapping from (e, t_c) is made on the study's reference pair, two unit grains
// (m_eff = m/2, R_eff = d/4): other sizes enter through R_eff, while the dashpot takes
// m_eff = m/2 whatever the masses (the linear law's convention, docs/model.md
// §2). e gives alpha by Antypov & Elliott's relation (with contact.clamp_normal the
// clamped collision is solved for alpha by bisection instead), and E* is chosen so that a
// head-on collision of the reference pair at relative normal speed u0 = 1 lasts t_c with that
// damping. The collision
// of x = delta/L at time tau = t v/L, L = (m_eff v^2/K)^(2/5), is
//   x'' = -x^(3/2) - alpha x^(1/4) x',  x(0) = 0, x'(0) = 1,
// whose duration tau(alpha) gives t_c = tau (m_eff/K)^(2/5) v^(-1/5); elastically (alpha = 0)
// tau = 2 (5/4)^(2/5) sqrt(pi) Gamma(7/5)/Gamma(9/10) = 3.218, which is Hertz's
// t_c = 2.868 (m_eff^2/(R_eff E*^2 v))^(1/5) (Johnson ch. 11; Landau & Lifshitz §9).
// Why not 2D: delta^(3/2) is the contact of spheres; two disks (parallel cylinders) follow
// another law, their approach linear in the load up to a logarithm (Johnson ch. 4).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string_view>
#include <type_traits>

#include "core/dim.hpp"
#include "core/errors.hpp"
#include "core/scene.hpp"
#include "soft_dem/adhesion.hpp"
#include "soft_dem/contact_geometry.hpp"
#include "soft_dem/coulomb_tangential.hpp"

namespace granjet::dem {

// One head-on collision of the dimensionless equation above: e = -x' when x returns to 0, and
// tau, the time that took. With `clamp` the bracket -(x^(3/2) + alpha x^(1/4) x') never pulls.
struct HertzCollision {
  double restitution;
  double duration;
};

// Classical Runge-Kutta at a step of 1e-4 (of a duration of about 3); the crossing of x = 0
// interpolated linearly. Checked against the elastic duration to 1e-9 and Antypov & Elliott's
// e to 1e-5 (tests/soft_dem/hertz_test.cpp).
inline HertzCollision hertz_collision(double alpha, bool clamp) {
  constexpr double h = 1e-4;
  const auto acceleration = [&](double x, double v) {
    x = std::max(x, 0.0);
    const double push = x * std::sqrt(x) + alpha * std::sqrt(std::sqrt(x)) * v;
    return clamp ? -std::max(push, 0.0) : -push;
  };
  double x = 0.0, v = 1.0;
  for (long step = 0; step < 100'000'000; ++step) {
    const double a1 = acceleration(x, v);
    const double a2 = acceleration(x + 0.5 * h * v, v + 0.5 * h * a1);
    const double a3 = acceleration(x + 0.5 * h * (v + 0.5 * h * a1), v + 0.5 * h * a2);
    const double a4 = acceleration(x + h * (v + 0.5 * h * a2), v + h * a3);
    const double x_next = x + h / 6.0 * (6.0 * v + h * (a1 + a2 + a3));
    const double v_next = v + h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
    if (x_next <= 0.0) {
      const double s = x / (x - x_next);
      return {-(v + s * (v_next - v)), (static_cast<double>(step) + s) * h};
    }
    x = x_next;
    v = v_next;
  }
  throw InputError("contact.restitution",
                   "too small for contact.model = hertz: the collision does not end");
}

// Tsuji's alpha for restitution e: Antypov & Elliott's exact relation, or with the clamp the
// root of hertz_collision(alpha, true).restitution = e (e falls as alpha grows).
inline double tsuji_alpha(double e, bool clamp) {
  const double log_e = std::log(e);
  if (!clamp)
    return std::sqrt(5.0) * -log_e / std::sqrt(std::numbers::pi * std::numbers::pi + log_e * log_e);
  if (e >= 1.0) return 0.0;
  double low = 0.0, high = 1.0;
  while (hertz_collision(high, true).restitution > e) high *= 2.0;
  for (int i = 0; i < 50; ++i) {
    const double mid = 0.5 * (low + high);
    if (hertz_collision(mid, true).restitution > e)
      low = mid;
    else
      high = mid;
  }
  return 0.5 * (low + high);
}

struct HertzCoefficients {
  double modulus = 0.0;        // E*
  double mass = 0.0;           // m_eff of the dashpot: m/2 for a pair, m against the plate
  double alpha = 0.0;          // Tsuji's damping factor
  double spring_ratio = 0.0;   // k_t / S_n
  double damping_ratio = 0.0;  // c_t / c_n
  double mu = 0.0;             // Coulomb friction mu_p
  double normal_floor = 0.0;   // -infinity, or 0 with contact.clamp_normal
  double adhesion = 0.0;       // F_a (adhesion.hpp)
};

// The mapping above from the scene's (e, t_c) for the reference pair of unit grains.
inline HertzCoefficients hertz_coefficients(const ContactSpec& spec) {
  constexpr double kMass = 0.5, kRadius = 0.25;  // m_eff, R_eff of two unit grains
  const double alpha = tsuji_alpha(spec.restitution, spec.clamp_normal);
  const double tau = hertz_collision(alpha, spec.clamp_normal).duration;
  // t_c = tau (m_eff/K)^(2/5) at v = 1, so K = m_eff (tau/t_c)^(5/2).
  const double k = kMass * std::pow(tau / spec.contact_time, 2.5);
  HertzCoefficients c;
  c.modulus = k / (4.0 / 3.0 * std::sqrt(kRadius));
  c.mass = kMass;
  c.alpha = alpha;
  c.spring_ratio = spec.spring_ratio;
  c.damping_ratio = spec.damping_ratio;
  c.mu = spec.friction;
  c.normal_floor = spec.clamp_normal ? 0.0 : -std::numeric_limits<double>::infinity();
  c.adhesion = spec.adhesion;
  return c;
}

// kWall: the plate's variant, whose geometry has lever_i = R - delta and lever_j = 0.
template <int D, bool kFriction, bool kWall = false>
struct HertzMindlinOf {
  static constexpr bool kNeedsHistory = kFriction;
  static constexpr bool kNeedsRotation = kFriction;
  static constexpr std::string_view kUnsupported =
      D == 3 ? ""
             : "hertz is the contact law of spheres (scene.dimension = 3): disks touch along a "
               "line and follow another law; use contact.model = linear in 2D";
  // A grain against the plate feels, in its motion relative to the face, what a grain feels
  // relative to an equal partner: the Hertz force of R_eff = R/2 at twice the modulus and
  // with m_eff = m (not m/2) in the dashpot, twice the pair's force at the same overlap and
  // rate. So the pair's e and t_c, as the linear law's wall variant.
  using Wall = HertzMindlinOf<D, kFriction, true>;

  HertzMindlinOf(const ContactSpec& spec, double time_step)
      : HertzMindlinOf(hertz_coefficients(spec), time_step) {}
  HertzMindlinOf(const HertzCoefficients& coefficients, double time_step)
      : c(coefficients),
        dt(time_step),
        damping(coefficients.alpha * std::sqrt(2.0 / 3.0 * coefficients.mass)) {}

  HertzCoefficients c;
  double dt;
  // c_n = damping sqrt(S_n), since alpha sqrt(m_eff K) delta^(1/4) = alpha sqrt(2/3 m_eff S_n).
  double damping;

  // Undamped, the kinetic energy m_eff v^2/2 is all stored at the turning point, (2/5) K
  // delta^(5/2): delta = (5 m_eff v^2 / (4 K))^(2/5) (Johnson ch. 11), for two unit grains.
  static double peak_overlap(const ContactSpec& spec, double speed) {
    const HertzCoefficients h = hertz_coefficients(spec);
    const double k = 4.0 / 3.0 * h.modulus * std::sqrt(0.25);
    return std::pow(1.25 * h.mass * speed * speed / k, 0.4);
  }

  Wall against_wall() const {
    HertzCoefficients w = c;
    w.modulus *= 2.0;
    w.mass *= 2.0;
    return {w, dt};
  }

  // Force on i from j, as LinearSpringDashpot::force (the same roundings on Vec<D> and
  // LaneVec<D>; outcomes selected, not branched on).
  template <class V>
  V force(const ContactGeometryOf<V>& g, const std::type_identity_t<V>& v_rel,
          std::type_identity_t<V>& shear) const {
    static_assert(D == 3, "see kUnsupported");
    const double s_n = 2.0 * c.modulus * contact_radius(g);
    const double c_n = damping * std::sqrt(s_n);
    const double v_n = v_rel.dot(g.n);
    // (2/3) S_n delta = (4/3) E* sqrt(R_eff) delta^(3/2); d(delta)/dt = -v_n.
    const double f_n = std::max(c.normal_floor, 2.0 / 3.0 * s_n * g.overlap - c_n * v_n);
    V f = with_adhesion(f_n, c.adhesion) * g.n;
    if constexpr (kFriction) {
      // Mindlin's k_t and c_t grow with the contact radius. A contact that slides has k_t > 0:
      // at a = 0 the trial force is 0 and does not exceed the limit, so 1/k_t's infinity is
      // never selected.
      const double k_t = c.spring_ratio * s_n, c_t = c.damping_ratio * c_n;
      f += coulomb_tangential<D, V>(g.n, v_rel, v_n, shear, dt, k_t, c_t, 1.0 / k_t,
                                    c.mu * std::abs(f_n));
    }
    return f;
  }

  double elastic_energy(const ContactGeometry<D>& g, const Vec<D>& shear) const {
    const double s_n = 2.0 * c.modulus * contact_radius(g);
    double e = 4.0 / 15.0 * s_n * g.overlap * g.overlap +  // (2/5) K delta^(5/2)
               adhesion_energy(g.overlap, c.adhesion);
    if constexpr (kFriction) e += 0.5 * c.spring_ratio * s_n * shear.squaredNorm();
    return e;
  }

 private:
  // a = sqrt(R_eff delta), the radii read back from the lever arms: R - delta/2 for a pair,
  // R - delta against the plate (where R_eff = R/2, see Wall).
  template <class V>
  static double contact_radius(const ContactGeometryOf<V>& g) {
    const double overlap = std::max(g.overlap, 0.0);
    double r_eff;
    if constexpr (kWall) {
      r_eff = 0.5 * (g.lever_i + overlap);
    } else {
      const double r_i = g.lever_i + 0.5 * overlap, r_j = g.lever_j + 0.5 * overlap;
      r_eff = r_i * r_j / (r_i + r_j);
    }
    return std::sqrt(r_eff * overlap);
  }
};

template <int D, bool kFriction>
using HertzMindlin = HertzMindlinOf<D, kFriction>;

}  // namespace granjet::dem
