// Each contact law's peak_overlap, which the run budget refuses scenes by (run/run_budget.cpp),
// against the deepest overlap of a head-on binary collision on the DEM backend: equal when
// elastic ([3.1] with [3.4]: v t_c / pi; Hertz: (5 m_eff v^2 / 4 K)^(2/5)), an upper bound
// when damped.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/errors.hpp"
#include "core/number_text.hpp"
#include "run/run_budget.hpp"
#include "soft_dem/dem_simulator.hpp"
#include "two_grains.hpp"

namespace granjet {
namespace {

Scene head_on(ContactModel model, double e, double speed) {
  Scene s = testing::binary_scene(3, e, 0.0, IntegratorKind::kVelocityVerlet);
  s.contact.model = model;
  s.binary.speed = speed;
  // A fine step resolves the turning point, so the sampled maximum is the peak to ~1e-5.
  s.run.dt = 1e-3 * s.contact.contact_time;
  return s;
}

double deepest_overlap(const Scene& s) {
  auto sim = dem::make_dem_simulator<3>(s);
  const double t_end = s.binary.gap / s.binary.speed + 3.0 * s.contact.contact_time;
  double deepest = 0.0;
  while (sim->time() < t_end) {
    sim->advance_to(sim->time() + s.dt());
    const auto& x = sim->particles().position();
    deepest = std::max(deepest, 1.0 - (x[0] - x[1]).norm());
  }
  return deepest;
}

TEST(PeakOverlap, Eq3_1_LinearElasticContactReachesVtcOverPi) {
  for (const double v : {0.5, 1.0, 2.0}) {
    SCOPED_TRACE("v = " + std::to_string(v));
    const Scene s = head_on(ContactModel::kLinear, 1.0, v);
    EXPECT_NEAR(dem::peak_overlap(s, v), v * 0.1 / std::numbers::pi, 1e-15);
    EXPECT_NEAR(deepest_overlap(s) / dem::peak_overlap(s, v), 1.0, 1e-4);
  }
}

TEST(PeakOverlap, HertzElasticContactStoresAllItsKineticEnergy) {
  for (const double v : {0.5, 1.0, 2.0}) {
    SCOPED_TRACE("v = " + std::to_string(v));
    const Scene s = head_on(ContactModel::kHertz, 1.0, v);
    EXPECT_NEAR(deepest_overlap(s) / dem::peak_overlap(s, v), 1.0, 1e-4);
  }
  // As v^(4/5): at u0 deeper than the linear law's of the same t_c.
  const Scene s = head_on(ContactModel::kHertz, 1.0, 1.0);
  EXPECT_GT(dem::peak_overlap(s, 1.0), 1.05 * 0.1 / std::numbers::pi);
}

TEST(PeakOverlap, DampedContactsStayBelowTheBound) {
  for (const ContactModel model : {ContactModel::kLinear, ContactModel::kHertz}) {
    const Scene s = head_on(model, 0.5, 1.0);
    const double deepest = deepest_overlap(s);
    EXPECT_LT(deepest, dem::peak_overlap(s, 1.0));
    EXPECT_GT(deepest, 0.5 * dem::peak_overlap(s, 1.0));
  }
}

// The budget refuses by the scene's law: at u0 a Hertz contact overlaps 6.7% deeper than a
// linear one of the same t_c, so between the two bounds the Hertz scene is refused, naming its
// own overlap, and the linear one passes.
TEST(PeakOverlap, RunBudgetUsesTheScenesContactLaw) {
  Scene s = head_on(ContactModel::kHertz, 0.9, 1.0);
  s.contact.contact_time = 1.0;
  s.run.dt = 0.0;
  const double hertz = dem::peak_overlap(s, 1.0);
  const double linear = 1.0 / std::numbers::pi;
  s.run.max_overlap = (hertz + linear) / 2.0 / 0.5;  // of the radius 0.5
  try {
    check_run_budget(s, "soft_dem", 16e9);
    ADD_FAILURE() << "a Hertz contact overlapping by " << hertz << " passed";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "binary.speed");
    EXPECT_NE(std::string(e.what()).find("overlaps by " + number_text(hertz)), std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(check_run_budget(s, "event_driven", 16e9));  // hard grains never overlap
  s.contact.model = ContactModel::kLinear;
  EXPECT_NO_THROW(check_run_budget(s, "soft_dem", 16e9));
}

}  // namespace
}  // namespace granjet
