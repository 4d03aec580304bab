#include "soft_dem/contact_coefficients.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace granjet::dem {

ContactCoefficients contact_coefficients(const ContactSpec& spec) {
  const double tc = spec.contact_time;
  const double eta_n = -std::log(spec.restitution) / tc;    // [3.5]
  const double omega = std::numbers::pi / tc;               // [3.4]
  const double kn = 0.5 * (omega * omega + eta_n * eta_n);  // m = 1
  const double floor = spec.clamp_normal ? 0.0 : -std::numeric_limits<double>::infinity();
  return {kn,    eta_n,        spec.spring_ratio * kn, spec.damping_ratio * eta_n, spec.friction,
          floor, spec.adhesion};
}

BinaryCollision binary_collision(double kn, double eta_n) {
  const double omega_squared = 2.0 * kn - eta_n * eta_n;  // m = 1
  if (!(omega_squared > 0.0)) return {std::nan(""), std::nan("")};
  const double tc = std::numbers::pi / std::sqrt(omega_squared);  // [3.4]
  return {std::exp(-tc * eta_n), tc};                             // [3.5]
}

}  // namespace granjet::dem
