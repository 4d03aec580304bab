// The forces a frame stores (output.fields = force, contacts): sampled at the current state
// without advancing it, they follow the contact law [3.1]-[3.3] and Newton's third law.
#include <gtest/gtest.h>

#include <cmath>

#include "soft_dem/contact_coefficients.hpp"
#include "two_grains.hpp"

namespace granjet {
namespace {

// Mid-collision, the one contact's normal force is [3.1] F_n = k_n u_n + m eta_n du_n/dt on
// grain i along n = (x_i - x_j)/|x_i - x_j|, frictionless: no tangential part.
TEST(SampledForces, Eq3_1_NormalForceOfAHeadOnCollision) {
  const Scene scene = testing::binary_scene(3, 0.75, 0.0, IntegratorKind::kAdamsBashforth2);
  const dem::ContactCoefficients c = dem::contact_coefficients(scene.contact);
  auto sim = dem::make_dem_simulator<3>(scene);
  ForceSample<3> f;
  for (int step = 0; step < 200 && f.contacts.empty(); ++step) {
    sim->advance_to(sim->time() + scene.dt());
    sim->sample_forces(f);
  }
  for (int step = 0; step < 2; ++step) sim->advance_to(sim->time() + scene.dt());  // well inside
  const Particles<3> before = sim->particles();
  sim->sample_forces(f);
  ASSERT_EQ(f.contacts.size(), 1u);
  const auto& contact = f.contacts[0];
  const auto& p = sim->particles();
  const std::size_t i = p.id()[0] == contact.i ? 0 : 1, j = 1 - i;
  const Vec<3> r = p.position()[i] - p.position()[j];
  const Vec<3> n = r.normalized();
  const double overlap = p.radius()[i] + p.radius()[j] - r.norm();
  const double closing = -(p.velocity()[i] - p.velocity()[j]).dot(n);
  const Vec<3> expected = (c.kn * overlap + c.eta_n * closing) * n;
  EXPECT_GT(overlap, 0.0);
  EXPECT_NEAR(contact.overlap, overlap, 1e-15);
  EXPECT_LT((contact.normal_force - expected).norm(), 1e-12 * expected.norm());
  EXPECT_EQ(contact.tangential_force, Vec<3>::Zero());
  EXPECT_EQ(f.total[i], contact.normal_force);
  EXPECT_EQ(f.total[j], -contact.normal_force);
  // Sampling reads the state, it does not step it: a second sample is the same.
  ForceSample<3> again;
  sim->sample_forces(again);
  EXPECT_EQ(again.contacts[0].normal_force, contact.normal_force);
  EXPECT_EQ(sim->particles().velocity()[i], before.velocity()[i]);
}

// A frictional oblique collision: [3.2]-[3.3] |F_t| <= mu |F_n| at every sample, and each grain's
// total is the sum of its contacts' forces (on j: minus those on i).
TEST(SampledForces, Eq3_3_TangentialForceStaysInTheCoulombConeAndTotalsAddUp) {
  Scene scene = testing::binary_scene(3, 0.75, 0.5, IntegratorKind::kAdamsBashforth2);
  scene.binary.impact_parameter = 0.6;
  auto sim = dem::make_dem_simulator<3>(scene);
  ForceSample<3> f;
  int sampled = 0;
  while (sim->time() < 0.5) {
    sim->advance_to(sim->time() + scene.dt());
    sim->sample_forces(f);
    ASSERT_LE(f.contacts.size(), 1u);
    for (const auto& c : f.contacts) {
      ++sampled;
      EXPECT_LE(c.tangential_force.norm(), 0.5 * c.normal_force.norm() * (1 + 1e-12));
      EXPECT_NEAR(c.normal_force.dot(c.tangential_force), 0.0,
                  1e-12 * c.normal_force.squaredNorm());
      const std::size_t i = sim->particles().id()[0] == c.i ? 0 : 1;
      const double tolerance = 1e-14 * c.normal_force.norm();
      EXPECT_LT((f.total[i] - (c.normal_force + c.tangential_force)).norm(), tolerance);
      EXPECT_LT((f.total[1 - i] + c.normal_force + c.tangential_force).norm(), tolerance);
    }
    if (f.contacts.empty()) {
      EXPECT_EQ(f.total[0] + f.total[1], Vec<3>::Zero());
    }
  }
  EXPECT_GT(sampled, 10);
}

}  // namespace
}  // namespace granjet
