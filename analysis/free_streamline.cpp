#include "analysis/free_streamline.hpp"

#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <string>

namespace granjet::analysis::free_streamline {
namespace {

void check_angle(double psi0) {
  if (!(psi0 > 0.0 && psi0 < 0.5 * std::numbers::pi))
    throw std::invalid_argument("free-streamline exit angle must lie in (0, pi/2), got " +
                                std::to_string(psi0));
}

// chi at t = 1 + s, a distance `edge` = (a - 1) - s before the plate edge t = a = 1/cos^2 psi0.
// xi = 1/(-p + sqrt(p^2 - 1)) with p = (1 - c t)/(1 - t), c = -cos 2 beta = cos 2 psi0. In closed
// form p^2 - 1 = 4 sin^2(psi0) cos^2(psi0) t edge/s^2, so
//   xi = s / ((1 - c t) + 2 sin(psi0) cos(psi0) sqrt(t edge)),
// a sum of positive terms that stays accurate at both ends, where s or edge vanish.
double chi_at(double s, double edge, double psi0) {
  const double t = 1.0 + s;
  const double c = std::cos(2.0 * psi0);
  const double xi = s / ((1.0 - c * t) + std::sin(2.0 * psi0) * std::sqrt(t * edge));
  return std::sqrt(xi);
}

// integral_1^a f(t, chi(t)) dt, integrated over s = t - 1 so that the abscissae next to the
// stagnation point keep their precision. Both integrands are ~ 1/sqrt(t - 1) there; tanh-sinh
// quadrature converges exponentially for such endpoint singularities, and its complement
// argument gives the distance to the plate edge without cancellation.
template <class F>
double over_plate(double psi0, F integrand) {
  check_angle(psi0);
  const double length = std::tan(psi0) * std::tan(psi0);  // a - 1
  boost::math::quadrature::tanh_sinh<double> quadrature;
  return quadrature.integrate(
      [&](double s, double complement) {
        // complement: -s in the left half, the distance to the right end in the right half
        const double edge = complement > 0.0 ? complement : length - s;
        return integrand(1.0 + s, chi_at(s, edge, psi0));
      },
      0.0, length);
}

}  // namespace

double hodograph(double t, double psi0) {
  check_angle(psi0);
  const double a = 1.0 / (std::cos(psi0) * std::cos(psi0));
  return chi_at(t - 1.0, a - t, psi0);
}

double plate_half_width(double psi0) {
  return over_plate(psi0, [](double t, double chi) { return 1.0 / (t * chi); }) / std::numbers::pi;
}

double momentum_force(double psi0) { return 2.0 * (1.0 - std::cos(psi0)); }

double pressure_force(double psi0) {
  return over_plate(psi0, [](double t, double chi) { return (1.0 - chi * chi) / (t * chi); }) /
         std::numbers::pi;
}

double exit_angle(double plate_over_jet) {
  if (!(plate_over_jet > 0.0) || !std::isfinite(plate_over_jet))
    throw std::invalid_argument("free-streamline plate half-width L/R must be positive, got " +
                                std::to_string(plate_over_jet));
  // plate_half_width rises monotonically from 0 to infinity over (0, pi/2); bracket the root
  // inside the open interval and solve with TOMS 748 to full double precision.
  const auto residual = [&](double psi0) { return plate_half_width(psi0) - plate_over_jet; };
  double lo = 1e-6, hi = 0.5 * std::numbers::pi - 1e-9;
  if (residual(lo) >= 0.0 || residual(hi) <= 0.0)
    throw std::invalid_argument(
        "free-streamline plate half-width L/R = " + std::to_string(plate_over_jet) +
        " is outside what double precision resolves");
  std::uintmax_t iterations = 200;
  const auto [a, b] = boost::math::tools::toms748_solve(
      residual, lo, hi, boost::math::tools::eps_tolerance<double>(52), iterations);
  return 0.5 * (a + b);
}

}  // namespace granjet::analysis::free_streamline
