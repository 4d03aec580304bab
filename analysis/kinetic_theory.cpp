#include "analysis/kinetic_theory.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace granjet::analysis::kinetic {
namespace {

double cube(double x) { return x * x * x; }

// [5.4]-[5.11]: c* = 32(1-e)(1-2e^2)/(81 - 17e + 30e^2(1-e)), which is 2 a2 of [2.37].
double c_star(double e) { return 2.0 * sonine_a2(e); }

}  // namespace

double chi(double phi) {
  if (phi < kPhiFreezing) return (1.0 - phi / 2.0) / cube(1.0 - phi);  // [5.3], dilute branch
  if (phi >= kPhiClosePacking) return std::numeric_limits<double>::infinity();
  // [5.3], dense branch: continuous at phi_f, diverging at phi_c.
  return (1.0 - kPhiFreezing / 2.0) * (kPhiClosePacking - kPhiFreezing) /
         (cube(1.0 - kPhiFreezing) * (kPhiClosePacking - phi));
}

double pressure_ratio(double phi, double e) { return 1.0 + 2.0 * phi * (1.0 + e) * chi(phi); }

double directional_pressure(double n, double t_alpha, double phi, double e) {
  return n * t_alpha * pressure_ratio(phi, e);
}

double effective_restitution(double e, double mu_p) {
  return e - std::numbers::pi / 2.0 * mu_p + 4.5 * mu_p * mu_p;  // [2.55]
}

double sonine_a2(double e) {
  return 16.0 * (1.0 - e) * (1.0 - 2.0 * e * e) / (81.0 - 17.0 * e + 30.0 * e * e * (1.0 - e));
}

double sonine_a2(double e, int dimension) {
  const double d = dimension;
  return 16.0 * (1.0 - e) * (1.0 - 2.0 * e * e) /
         (9.0 + 24.0 * d - e * (41.0 - 8.0 * d) + 30.0 * (1.0 - e) * e * e);
}

double cooling_per_collision(double e, int dimension) {
  const double a2 = sonine_a2(e, dimension);
  return -(1.0 - e * e) / dimension * (1.0 + 3.0 * a2 / 16.0) / (1.0 - a2 / 16.0);
}

double carnahan_starling(double phi) {
  return (1.0 + phi + phi * phi - cube(phi)) / cube(1.0 - phi);
}

double henderson(double phi) { return (1.0 + phi * phi / 8.0) / ((1.0 - phi) * (1.0 - phi)); }

double enskog_collision_frequency(double phi, double temperature, int dimension) {
  const double z = dimension == 3 ? carnahan_starling(phi) : henderson(phi);
  const double phi_chi = (z - 1.0) / (dimension == 3 ? 4.0 : 2.0);
  return (dimension == 3 ? 24.0 : 8.0) * phi_chi * std::sqrt(temperature / std::numbers::pi);
}

double viscosity_star(double phi, double e) {
  const double g = chi(phi);
  const double c = c_star(e);
  // [5.4]-[5.11] in the model's order: the collision frequency nu_eta*, the cooling rate zeta*,
  // the kinetic part eta_k*, the bulk-viscosity term gamma*, and eta* itself ([5.6]).
  const double nu_eta = g * (1.0 - (1.0 - e) * (1.0 - e) / 4.0) * (1.0 - c / 64.0);
  const double zeta = 5.0 / 12.0 * g * (1.0 - e * e) * (1.0 + 3.0 * c / 32.0);
  const double eta_k =
      (1.0 - 2.0 * (1.0 + e) * (1.0 - 3.0 * e) * phi * g / 5.0) / (nu_eta - zeta / 2.0);
  const double gamma =
      128.0 / (5.0 * std::numbers::pi) * phi * phi * g * (1.0 + e) * (1.0 - c / 32.0);
  return eta_k * (1.0 + 4.0 * phi * g * (1.0 + e) / 5.0) + 3.0 * gamma / 5.0;
}

double dilute_viscosity(double temperature, double mass, double diameter, int dimension) {
  const double root = std::sqrt(mass * temperature / std::numbers::pi);
  if (dimension == 3) return 5.0 / (16.0 * diameter * diameter) * root;  // [5.4] prefactor
  return root / (2.0 * diameter);
}

double kinetic_viscosity(double phi, double e, double temperature, double mass, double diameter) {
  return dilute_viscosity(temperature, mass, diameter, 3) * viscosity_star(phi, e);  // [5.4]
}

}  // namespace granjet::analysis::kinetic
