// Grain volume (area) inside a bin, for phi: exact disk-rectangle areas, and the sphere-ring
// quadrature against closed forms and a fine midpoint rule.
#include "analysis/grain_overlap.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace granjet::analysis {
namespace {

constexpr double kPi = std::numbers::pi;

// Circular segment beyond a chord at distance a from the centre: r^2 acos(a/r) - a sqrt(r^2-a^2).
double segment_area(double r, double a) {
  return r * r * std::acos(a / r) - a * std::sqrt(r * r - a * a);
}

TEST(GrainOverlap, DiskRectangleClosedForms) {
  EXPECT_NEAR(disk_rectangle_area(0.3, -0.2, 0.5, -1, 1, -1, 1), kPi * 0.25, 1e-15);  // inside
  EXPECT_NEAR(disk_rectangle_area(0, 0, 1, 0, 2, -2, 2), kPi / 2, 1e-15);             // half
  EXPECT_NEAR(disk_rectangle_area(0, 0, 1, 0, 2, 0, 2), kPi / 4, 1e-15);              // quarter
  EXPECT_NEAR(disk_rectangle_area(0, 0, 1, 0.4, 2, -2, 2), segment_area(1, 0.4), 1e-15);
  EXPECT_NEAR(disk_rectangle_area(0, 0, 1, -2, 2, -0.3, 2), kPi - segment_area(1, 0.3), 1e-14);
  // A strip through the middle: the disk minus the two segments beyond |y| = 0.2.
  EXPECT_NEAR(disk_rectangle_area(5, 7, 1, -9, 9, 6.8, 7.2), kPi - 2 * segment_area(1, 0.2), 1e-14);
  EXPECT_EQ(disk_rectangle_area(0, 0, 1, 1.0, 2, -2, 2), 0.0);  // touching from outside
}

TEST(GrainOverlap, DiskAreasOverATilingSumToTheDisk) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (int trial = 0; trial < 50; ++trial) {
    const double cx = u(rng), cy = u(rng), r = 0.4 + 0.5 * (u(rng) + 0.5);
    double sum = 0.0;
    for (int i = -6; i < 6; ++i)
      for (int j = -5; j < 5; ++j)
        sum += disk_rectangle_area(cx, cy, r, 0.27 * i, 0.27 * (i + 1), 0.31 * j, 0.31 * (j + 1));
    EXPECT_NEAR(sum, kPi * r * r, 1e-13);
  }
}

TEST(GrainOverlap, LensOfTwoUnitCirclesOneApart) {
  EXPECT_NEAR(lens_area(1, 1, 1), 2 * kPi / 3 - std::sqrt(3.0) / 2, 1e-14);
  EXPECT_NEAR(lens_area(0.5, 2.0, 0.3), kPi * 0.25, 1e-15);  // small disk inside
  EXPECT_EQ(lens_area(0.5, 2.0, 2.5), 0.0);                  // tangent from outside
}

TEST(GrainOverlap, SphereInCoaxialCylinderAndSlabClosedForms) {
  const double r = 0.5;
  // Coaxial cylinder of radius c: 4/3 pi (r^3 - (r^2 - c^2)^(3/2)).
  for (double c : {0.1, 0.3, 0.49})
    EXPECT_NEAR(sphere_cylinder_slab_volume(0, 2, r, c, 0, 5),
                4 * kPi / 3 * (r * r * r - std::pow(r * r - c * c, 1.5)), 1e-14);
  // The cap of height h above the plane z0 = zc + r - h: pi h^2 (3r - h)/3.
  const double h = 0.3;
  EXPECT_NEAR(sphere_cylinder_slab_volume(1.0, 0.0, r, 5.0, r - h, 5.0),
              kPi * h * h * (3 * r - h) / 3, 1e-15);
}

// Off-axis spheres straddling a cylinder: the quadrature against a 50,000-point midpoint rule
// in z over the exact cross-section lens (accurate to ~1e-10), within 1e-6 of the sphere's
// volume -- the accuracy the header promises.
TEST(GrainOverlap, SphereCylinderSlabQuadratureWithin1e6OfTheGrain) {
  const double r = 0.5, grain = 4 * kPi / 3 * r * r * r;
  double worst = 0.0;
  for (double rho : {0.0, 0.2, 0.5, 2.0, 2.3, 2.6, 3.1})
    for (double cylinder : {0.3, 2.2, 2.5})
      for (double zc : {0.2, 2.0, 4.8}) {
        const double z0 = std::max(0.0, zc - r), z1 = std::min(5.0, zc + r);
        constexpr int kSteps = 50000;
        double reference = 0.0;
        for (int k = 0; k < kSteps; ++k) {
          const double z = z0 + (k + 0.5) * (z1 - z0) / kSteps;
          const double a = std::sqrt(std::max(0.0, r * r - (z - zc) * (z - zc)));
          reference += lens_area(a, cylinder, rho) * (z1 - z0) / kSteps;
        }
        worst = std::max(
            worst,
            std::abs(sphere_cylinder_slab_volume(rho, zc, r, cylinder, 0, 5) - reference) / grain);
      }
  EXPECT_LT(worst, 1e-6);
}

}  // namespace
}  // namespace granjet::analysis
