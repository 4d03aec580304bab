// Spec §7b: the free-streamline solution of a 2D jet on a flat plate.
#include "analysis/free_streamline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace granjet::analysis::free_streamline {
namespace {

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

// The two routes to the force on the plate, momentum balance and the Bernoulli pressure
// integral over the plate, agree only if the hodograph and the plate map are right.
TEST(FreeStreamline, Sec7b_MomentumForceEqualsBernoulliPressureIntegral) {
  for (const double degrees : {5.0, 20.0, 38.0, 55.0, 66.0, 75.0, 85.0, 89.0}) {
    const double psi0 = radians(degrees);
    EXPECT_NEAR(pressure_force(psi0) / momentum_force(psi0), 1.0, 1e-6) << degrees << " deg";
  }
}

// Independent reference: the same integral by QUADPACK's adaptive Gauss-Kronrod (scipy quad,
// limit 200) gives L/R = 1.2260769426 at psi0 = 60 deg and 0.5461468087 at 40 deg.
TEST(FreeStreamline, Sec7b_PlateHalfWidthMatchesAdaptiveQuadrature) {
  EXPECT_NEAR(plate_half_width(radians(60.0)), 1.2260769426, 1e-8);
  EXPECT_NEAR(plate_half_width(radians(40.0)), 0.5461468087, 1e-8);
}

TEST(FreeStreamline, Sec7b_ExitAngleInvertsThePlateMap) {
  for (const double l_over_r : {0.05, 0.5, 1.0, 1.5, 2.0, 3.0, 6.0}) {
    EXPECT_NEAR(plate_half_width(exit_angle(l_over_r)), l_over_r, 1e-10 * l_over_r);
  }
}

// A narrow plate barely deflects the jet; a wide one turns it into a flat sheet (90 deg).
TEST(FreeStreamline, Sec7b_ExitAngleRisesFromZeroToNinetyDegrees) {
  double previous = 0.0;
  for (const double l_over_r : {0.01, 0.1, 0.5, 1.0, 2.0, 3.0, 5.0, 8.0}) {
    const double psi0 = exit_angle(l_over_r);
    EXPECT_GT(psi0, previous) << l_over_r;
    previous = psi0;
  }
  EXPECT_LT(exit_angle(0.01), radians(10.0));
  EXPECT_GT(exit_angle(8.0), radians(89.9));
  EXPECT_LT(exit_angle(8.0), 0.5 * std::numbers::pi);
}

TEST(FreeStreamline, Sec7b_HodographIsZeroAtStagnationAndOneAtThePlateEdge) {
  const double psi0 = radians(55.0);
  const double edge = 1.0 / std::pow(std::cos(psi0), 2);
  EXPECT_NEAR(hodograph(edge, psi0), 1.0, 1e-12);
  EXPECT_LT(hodograph(1.0 + 1e-12, psi0), 1e-5);
  // So the pressure rho U^2 (1 - chi^2)/2 peaks at the stagnation value rho U^2/2.
  EXPECT_NEAR(0.5 * (1.0 - std::pow(hodograph(1.0 + 1e-14, psi0), 2)), 0.5, 1e-6);
}

TEST(FreeStreamline, Sec7b_RejectsImpossibleGeometry) {
  EXPECT_THROW(exit_angle(0.0), std::invalid_argument);
  EXPECT_THROW(exit_angle(-1.0), std::invalid_argument);
  EXPECT_THROW(plate_half_width(0.5 * std::numbers::pi), std::invalid_argument);
}

}  // namespace
}  // namespace granjet::analysis::free_streamline
