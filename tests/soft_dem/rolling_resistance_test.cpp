// Rolling resistance (soft_dem/rolling_resistance.hpp, model §2 "Rolling resistance"): the
// torque's size and direction, the twist left alone, the plate's R*, and a pair rolling on each
// other, whose spins lose exactly mu_r R* J / I for a normal impulse J.
#include "soft_dem/rolling_resistance.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.hpp"
#include "run/backend_factory.hpp"
#include "run/scene_file.hpp"
#include "soft_dem/dem_simulator.hpp"
#include "soft_dem/linear_spring_dashpot.hpp"

namespace granjet::dem {
namespace {

ContactSpec rolling_spec(double mu_r) {
  ContactSpec c;
  c.friction = 0.5;
  c.rolling_friction = mu_r;
  return c;
}

TEST(RollingResistance, TorqueOpposesTheRollingSpinAndIgnoresTheTwist) {
  const Rolling<LinearSpringDashpot<3, true>> law(rolling_spec(0.1), 0.002);
  // Unit grains: R* = 1/4 whatever the overlap (the levers are R - delta/2).
  const ContactGeometry<3> g{Vec<3>(1, 0, 0), 0.02, 0.49, 0.49};
  const Vec<3> f(3.0, 0.4, 0.0);  // F_n = 3
  // Rolling about y, and a twist about the normal x that rolling resistance does not see.
  const Vec<3> m = law.rolling_torque(g, Vec<3>(5.0, -2.0, 0.0), f);
  EXPECT_NEAR(m.x(), 0.0, 1e-15);
  EXPECT_NEAR(m.y(), 0.1 * 0.25 * 3.0, 1e-15);  // against w_y = -2
  EXPECT_NEAR(m.z(), 0.0, 1e-15);
  // Turning together (no relative spin): no torque, and no 0/0.
  const Vec<3> zero = Vec<3>::Zero();
  EXPECT_EQ(law.rolling_torque(g, zero, f), zero);
  // A pure twist: none either.
  EXPECT_EQ(law.rolling_torque(g, Vec<3>(4.0, 0.0, 0.0), f), zero);
}

TEST(RollingResistance, AgainstThePlateTheReducedRadiusIsTheGrains) {
  const auto wall = Rolling<LinearSpringDashpot<2, true>>(rolling_spec(0.2), 0.002).against_wall();
  // Lever R - delta against the face, partner none: R* = R = 1/2.
  const ContactGeometry<2> g{Vec<2>(0, 1), 0.01, 0.49, 0.0};
  EXPECT_NEAR(wall.rolling_torque(g, 3.0, Vec<2>(0.0, -2.0)), -0.2 * 0.5 * 2.0, 1e-15);
  EXPECT_NEAR(wall.rolling_torque(g, -3.0, Vec<2>(0.0, 2.0)), 0.2 * 0.5 * 2.0, 1e-15);
}

// Two unit grains meet head-on spinning in opposite senses about z: their surfaces roll on each
// other without slipping, so no tangential force acts and the rolling torque alone turns them.
// It is mu_r R* |F_n| throughout (F_n >= 0 with the clamp), so each spin changes by
// mu_r R* J / I, J the normal impulse read off the velocities, and the total spin stays 0.
template <int D>
void check_rolling_pair() {
  Scene s;
  s.kind = SceneKind::kBinary;
  s.dimension = D;
  s.contact = rolling_spec(0.1);
  s.contact.clamp_normal = true;
  constexpr double w0 = 2.0;
  Particles<D> p;
  Vec<D> x0 = Vec<D>::Zero(), v0 = Vec<D>::Zero();
  x0[0] = -1.05;
  v0[0] = 1.0;
  p.add(0, GrainKind::kFree, x0, v0, 0.5, 1.0);
  p.add(1, GrainKind::kFree, Vec<D>::Zero(), Vec<D>::Zero(), 0.5, 1.0);
  if constexpr (D == 2) {
    p.spin()[0] = w0;
    p.spin()[1] = -w0;
  } else {
    p.spin()[0] = Vec<3>(0, 0, w0);
    p.spin()[1] = Vec<3>(0, 0, -w0);
  }
  DemSimulator<D, Rolling<LinearSpringDashpot<D, true>>, true> sim(s, std::move(p));
  sim.advance_to(0.4);
  const Particles<D>& after = sim.particles();
  ASSERT_EQ(sim.stats().contacts, 0);  // apart again
  const double impulse = 1.0 - after.velocity()[0][0];
  EXPECT_NEAR(impulse, 0.88, 0.01);  // (1 + e) m_eff u0, e = 0.76 for the clamped collision
  const double inertia = Dim<D>::kInertiaFactor * 0.25;
  double w_0, w_1;
  if constexpr (D == 2) {
    w_0 = after.spin()[0];
    w_1 = after.spin()[1];
  } else {
    w_0 = after.spin()[0].z();
    w_1 = after.spin()[1].z();
    EXPECT_EQ(after.spin()[0].x(), 0.0);
    EXPECT_EQ(after.spin()[0].y(), 0.0);
  }
  EXPECT_NEAR(w_0, w0 - 0.1 * 0.25 * impulse / inertia, 1e-9);
  EXPECT_EQ(w_0 + w_1, 0.0);
  EXPECT_NEAR(after.velocity()[0][1], 0.0, 1e-15);  // no slip, so no tangential force
}

TEST(RollingResistance, PairRollingOnEachOtherLosesMuRStarJOverIOfSpin2D) {
  check_rolling_pair<2>();
}
TEST(RollingResistance, PairRollingOnEachOtherLosesMuRStarJOverIOfSpin3D) {
  check_rolling_pair<3>();
}

TEST(RollingResistance, SceneKeysAreCheckedAndTheEventDrivenBackendIgnoresThem) {
  const std::string scenes = GRANJET_SCENES_DIR;
  try {
    load_scene(scenes + "/jet2d.ini", {"contact.rolling_friction=0.1", "contact.friction=0"});
    FAIL() << "a rolling resistance without friction must be refused";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "contact.rolling_friction");
  }
  EXPECT_THROW(load_scene(scenes + "/jet2d.ini", {"contact.rolling_friction=-1"}), InputError);
  const Scene gas =
      load_scene(scenes + "/hcs3d.ini", {"contact.friction=0.2", "contact.rolling_friction=0.1"});
  EXPECT_THROW(check_backend("soft_dem", gas), InputError);
  const Scene jet =
      load_scene(scenes + "/jet2d.ini", {"contact.friction=0.2", "contact.rolling_friction=0.1"});
  const SceneSupport hard = check_backend("event_driven", jet);
  bool noted = false;
  for (const std::string& note : hard.notes)
    noted |= note.find("rolling_friction") != std::string::npos;
  EXPECT_TRUE(noted);
}

}  // namespace
}  // namespace granjet::dem
