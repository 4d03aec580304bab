// Stability (d): inelastic collapse of the event-driven backend [model §8], constant restitution
// against the velocity-dependent law e(v_n) = 1 - (1 - e0)(v_n/v0)^(3/4) below v0 = 0.1.
//
// tests/event_driven/ed_simulator_test.cpp checks the report for one case (2D, phi = 0.6,
// e = 0.5, 1000 disks, t <= 200). Here: how far each law gets over e0 = 0.3 ... 0.9 in dense
// cooling gases in 2D (phi = 0.6, 1000 disks) and 3D (phi = 0.45, 500 spheres), each run
// until 3000 collisions per grain, a collapse, or the gas has cooled below 1e-30 of its initial
// temperature (a cooling gas's clock runs away: chunks of time double whenever they hold fewer
// than 20 collisions per grain). The scenes are the shipped hcs2d/hcs3d files with overrides.
//
// Expected:
// - the velocity-dependent law, same scene and e0, never collapses: it runs through the whole
//   budget (its slow collisions become nearly elastic), finite, its kinetic energy never rising;
// - the constant law stops, if it stops, with a BlowUpError naming at least two grains and the
//   remedy; it never leaves a non-finite state;
// - strong dissipation collapses: e0 = 0.3 in 2D and 3D, and the dense 2D gas at e0 = 0.5; weaker
//   dissipation may cool without collapsing within the budget
//   (recorded, not asserted).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/errors.hpp"
#include "event_driven/ed_simulator.hpp"
#include "stability_common.hpp"

namespace granjet::stability {
namespace {

constexpr double kCollisionsPerGrain = 3000.0;

struct CollapseCase {
  int dimension;
  double phi;
  std::int64_t grains;
  double e0;
};

struct LawOutcome {
  bool collapsed = false;
  bool frozen = false;  // cooled below 1e-30 T_0 without collapsing
  std::string message;
  std::vector<GrainId> ids;
  double collisions_per_grain = 0.0;
  double time = 0.0;
  double temperature_ratio = 0.0;  // T_end / T_0
  double worst_energy_rise = 0.0;  // largest rise of the kinetic energy between chunks / E_0
  bool finite = true;
  double seconds = 0.0;
};

Scene collapse_scene(const CollapseCase& c, const std::string& law) {
  return shipped_scene(
      c.dimension == 2 ? "hcs2d" : "hcs3d",
      {"contact.restitution=" + std::to_string(c.e0), "gas.phi=" + std::to_string(c.phi),
       "gas.grains=" + std::to_string(c.grains), "ed.restitution_law=" + law, "gas.equilibration=0",
       "run.t_end=1e9"});
}

// Advances in time chunks that double while the gas cools (Haff: collision times grow), until
// the collision budget is spent or the run throws.
template <int D>
LawOutcome run_law(const Scene& scene) {
  Stopwatch clock;
  auto sim = ed::make_ed_simulator<D>(scene);
  const double n = static_cast<double>(sim->particles().size());
  const double e0 = sim->energy().total();
  LawOutcome o;
  double chunk = 0.1;
  double kinetic = e0;
  try {
    while (2.0 * sim->stats().collisions / n < kCollisionsPerGrain && kinetic > 1e-30 * e0) {
      const std::int64_t before = sim->stats().collisions;
      sim->advance_to(sim->time() + chunk);
      // Collisions with e <= 1 only ever take energy out.
      const double now = sim->energy().kinetic;
      o.worst_energy_rise = std::max(o.worst_energy_rise, (now - kinetic) / e0);
      kinetic = now;
      // Fewer than a collision per grain in this chunk: the next may be longer.
      if (2.0 * (sim->stats().collisions - before) / n < 20.0) chunk *= 2.0;
    }
  } catch (const BlowUpError& e) {
    o.collapsed = true;
    o.message = e.what();
    o.ids = e.grain_ids();
    o.time = e.time();
  }
  o.frozen = !o.collapsed && kinetic <= 1e-30 * e0;
  o.collisions_per_grain = 2.0 * sim->stats().collisions / n;
  if (!o.collapsed) o.time = sim->time();
  o.finite = all_finite(sim->particles());
  o.temperature_ratio = sim->energy().kinetic / e0;
  o.seconds = clock.seconds();
  return o;
}

std::string describe(const LawOutcome& o) {
  return cat(o.collapsed ? "collapsed"
             : o.frozen  ? "cooled below 1e-30 T0"
                         : "ran through",
             " after ", o.collisions_per_grain, " collisions/grain, t = ", o.time,
             ", T/T0 = ", o.temperature_ratio, ", ", o.seconds, " s",
             o.collapsed ? "; " + o.message : "");
}

class EdCollapse : public ::testing::TestWithParam<CollapseCase> {};

template <int D>
void check(const CollapseCase& c) {
  const std::string key = cat("ed_collapse.", D, "d.phi", c.phi, ".e", c.e0);
  Watchdog dog(300.0, key);
  const LawOutcome constant = run_law<D>(collapse_scene(c, "constant"));
  report(key + ".constant", describe(constant));
  const LawOutcome dependent = run_law<D>(collapse_scene(c, "velocity_dependent"));
  report(key + ".velocity_dependent", describe(dependent));

  const bool must_collapse = c.e0 <= 0.3 || (D == 2 && c.e0 <= 0.5);
  if (must_collapse) {
    EXPECT_TRUE(constant.collapsed) << "constant e0 = " << c.e0 << ": " << describe(constant);
  }
  EXPECT_TRUE(constant.finite);
  if (constant.collapsed) {
    EXPECT_NE(constant.message.find("inelastic collapse"), std::string::npos);
    EXPECT_NE(constant.message.find("velocity_dependent"), std::string::npos);
    EXPECT_GE(constant.ids.size(), 2u);
  }
  EXPECT_FALSE(dependent.collapsed) << dependent.message;
  EXPECT_GE(dependent.collisions_per_grain, kCollisionsPerGrain);
  EXPECT_TRUE(dependent.finite);
  // The kinetic energy never rises (round-off aside): e(v_n) <= 1 for every collision.
  EXPECT_LT(dependent.worst_energy_rise, 1e-12);
}

TEST_P(EdCollapse, Sec8_ConstantLawCollapsesAndIsReportedVelocityDependentRunsOn) {
  if (GetParam().dimension == 2)
    check<2>(GetParam());
  else
    check<3>(GetParam());
}

INSTANTIATE_TEST_SUITE_P(
    DenseCoolingGases, EdCollapse,
    ::testing::Values(CollapseCase{2, 0.6, 1000, 0.3}, CollapseCase{2, 0.6, 1000, 0.5},
                      CollapseCase{2, 0.6, 1000, 0.7}, CollapseCase{2, 0.6, 1000, 0.9},
                      CollapseCase{3, 0.45, 500, 0.3}, CollapseCase{3, 0.45, 500, 0.5},
                      CollapseCase{3, 0.45, 500, 0.7}, CollapseCase{3, 0.45, 500, 0.9}),
    [](const auto& info) {
      return cat(info.param.dimension, "D_e", static_cast<int>(std::lround(10 * info.param.e0)));
    });

}  // namespace
}  // namespace granjet::stability
