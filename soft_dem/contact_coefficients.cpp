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
  return {kn, eta_n, spec.spring_ratio * kn, spec.damping_ratio * eta_n, spec.friction, floor};
}

}  // namespace granjet::dem
