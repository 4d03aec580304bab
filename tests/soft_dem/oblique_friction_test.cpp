// Oblique binary collisions with friction [3.2]-[3.3]: Coulomb's bound in the sliding and
// sticking regimes, angular momentum, and frictionless spins.
#include <gtest/gtest.h>

#include <cmath>

#include "two_grains.hpp"

namespace granjet {
namespace {

using testing::friction_ratios;

TEST(ObliqueFriction, Eq3_3_SlidingContactSitsOnTheCoulombLimit) {
  // Grazing impact: the tangential slip (0.9 u0) outlasts what friction can remove.
  Scene s = testing::binary_scene(3, 0.9, 0.2, IntegratorKind::kAdamsBashforth2);
  s.binary.impact_parameter = 0.9;
  const std::vector<double> ratios = friction_ratios(s);
  ASSERT_GT(ratios.size(), 30u);  // about t_c / dt = 50 contact steps
  for (double r : ratios) EXPECT_NEAR(r, 0.2, 1e-9);
}

TEST(ObliqueFriction, Eq3_2_StickingContactStaysInsideTheCoulombCone) {
  // Nearly head-on with strong friction: the tangential spring holds (sticks) at first.
  Scene s = testing::binary_scene(3, 0.75, 1.0, IntegratorKind::kAdamsBashforth2);
  s.binary.impact_parameter = 0.1;
  testing::expect_sticking_inside_the_coulomb_cone(s, 1.0);
}

template <int D>
double spin_z(const Particles<D>& p, std::size_t i) {
  if constexpr (D == 2)
    return p.spin()[i];
  else
    return p.spin()[i].z();
}

// Orbital and spin parts of the angular momentum about `about`, z component.
template <int D>
std::pair<double, double> angular_momentum_z(const Particles<D>& p, const Vec<D>& about) {
  double orbital = 0.0, spin = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec<D> r = p.position()[i] - about;
    const Vec<D> v = p.velocity()[i];
    orbital += p.mass()[i] * (r.x() * v.y() - r.y() * v.x());
    spin += Dim<D>::kInertiaFactor * p.mass()[i] * std::pow(p.radius()[i], 2) * spin_z(p, i);
  }
  return {orbital, spin};
}

template <int D>
void check_angular_momentum(IntegratorKind integrator) {
  Scene s = testing::binary_scene(D, 0.75, 0.4, integrator);
  s.binary.impact_parameter = 0.5;
  s.binary.spin = 3.0;
  const auto run = testing::run_two_grains<D>(s);
  ASSERT_TRUE(run.tracker.complete());
  // About the point where the grains first touch (any fixed point works for a free pair).
  const Vec<D> contact = 0.5 * (run.before.position()[0] + run.before.position()[1]);
  const auto [orbital_before, spin_before] = angular_momentum_z(run.before, contact);
  const auto [orbital_after, spin_after] = angular_momentum_z(run.after, contact);
  const double total = orbital_before + spin_before;
  EXPECT_NEAR(orbital_after + spin_after, total, 1e-6 * std::abs(total));
  // ... while friction did move angular momentum between orbit and spins.
  EXPECT_GT(std::abs(spin_after - spin_before), 1e-2 * std::abs(total));
}

TEST(ObliqueFriction, AngularMomentumAboutTheContactPointIsConserved2D) {
  check_angular_momentum<2>(IntegratorKind::kAdamsBashforth2);
  check_angular_momentum<2>(IntegratorKind::kVelocityVerlet);
}

TEST(ObliqueFriction, AngularMomentumAboutTheContactPointIsConserved3D) {
  check_angular_momentum<3>(IntegratorKind::kAdamsBashforth2);
  check_angular_momentum<3>(IntegratorKind::kVelocityVerlet);
}

TEST(ObliqueFriction, FrictionlessCollisionLeavesSpinsAndTangentialVelocityUntouched) {
  Scene s = testing::binary_scene(3, 0.75, 0.0, IntegratorKind::kAdamsBashforth2);
  s.binary.impact_parameter = 0.5;
  s.binary.spin = 3.0;
  const auto run = testing::run_two_grains<3>(s);
  ASSERT_TRUE(run.tracker.complete());
  for (std::size_t i = 0; i < 2; ++i) {
    const std::size_t j = run.after.id()[0] == run.before.id()[i] ? 0 : 1;  // same grain
    EXPECT_EQ(run.after.spin()[j], run.before.spin()[i]);
  }
  // The impulse is along the line of centres: the total velocity stays in the x-y plane and
  // momentum is conserved.
  const Vec<3> p_before = run.before.velocity()[0] + run.before.velocity()[1];
  const Vec<3> p_after = run.after.velocity()[0] + run.after.velocity()[1];
  EXPECT_NEAR((p_after - p_before).norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace granjet
