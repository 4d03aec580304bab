// contact.adhesion (soft_dem/adhesion.hpp, model §2 "Adhesion"): the DMT pull F_a. A slow pair
// is caught and settles where the law's repulsion balances F_a: delta = F_a / k_n for the
// linear law (2D and 3D), (3 F_a / (4 E* sqrt(R*)))^(2/3) for Hertz; a fast elastic pair still
// parts with its speed; the key is checked and the event-driven backend notes it ignores it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/errors.hpp"
#include "run/backend_factory.hpp"
#include "run/scene_file.hpp"
#include "soft_dem/contact_coefficients.hpp"
#include "soft_dem/hertz_mindlin.hpp"
#include "two_grains.hpp"

namespace granjet {
namespace {

constexpr double kPull = 5.0;  // F_a, about 1% of k_n of the t_c = 0.1 laws

Scene sticky_pair(int dimension, ContactModel model, double e, double speed) {
  Scene s = testing::binary_scene(dimension, e, 0.0, IntegratorKind::kAdamsBashforth2);
  s.contact.model = model;
  s.contact.adhesion = kPull;
  s.binary.speed = speed;
  return s;
}

template <int D>
double overlap_at_rest(const Scene& s) {
  // The gap closes at binary.gap / v; the pair's oscillation then decays as exp(-eta_n t).
  const testing::TwoGrainRun<D> run =
      testing::run_two_grains<D>(s, s.binary.gap / s.binary.speed + 6.0);
  const Particles<D>& p = run.after;
  EXPECT_LT((p.velocity()[0] - p.velocity()[1]).norm(), 1e-9);  // at rest, together
  return p.radius()[0] + p.radius()[1] - (p.position()[0] - p.position()[1]).norm();
}

TEST(Adhesion, SlowLinearPairSettlesAtFaOverKn2D) {
  const Scene s = sticky_pair(2, ContactModel::kLinear, 0.5, 0.05);
  const double expected = kPull / dem::contact_coefficients(s.contact).kn;
  EXPECT_NEAR(overlap_at_rest<2>(s) / expected, 1.0, 1e-6);
}

TEST(Adhesion, SlowLinearPairSettlesAtFaOverKn3D) {
  const Scene s = sticky_pair(3, ContactModel::kLinear, 0.5, 0.05);
  const double expected = kPull / dem::contact_coefficients(s.contact).kn;
  EXPECT_NEAR(overlap_at_rest<3>(s) / expected, 1.0, 1e-6);
}

TEST(Adhesion, SlowHertzPairSettlesWhereHertzBalancesThePull) {
  const Scene s = sticky_pair(3, ContactModel::kHertz, 0.5, 0.05);
  const double modulus = dem::hertz_coefficients(s.contact).modulus, r_eff = 0.25;
  const double expected = std::pow(3.0 * kPull / (4.0 * modulus * std::sqrt(r_eff)), 2.0 / 3.0);
  EXPECT_NEAR(overlap_at_rest<3>(s) / expected, 1.0, 1e-6);
}

// Without damping the pull is conservative: what it gives on the way in it takes on the way
// out, so a fast pair parts with its speed (to the integrator's error at the pull's onset and
// end, a jump of F_a).
TEST(Adhesion, FastElasticPairPartsWithItsSpeed) {
  const Scene s = sticky_pair(3, ContactModel::kLinear, 1.0, 1.0);
  const testing::TwoGrainRun<3> run = testing::run_two_grains<3>(s, 0.5);
  const auto relative = [](const Particles<3>& p) { return p.velocity()[0] - p.velocity()[1]; };
  const Particles<3>& after = run.after;
  EXPECT_GT((after.position()[0] - after.position()[1]).norm(), 1.0);  // apart
  EXPECT_NEAR(relative(after).norm() / relative(run.before).norm(), 1.0, 0.01);
  EXPECT_LT(relative(after).dot(relative(run.before)), 0.0);  // rebounded
}

TEST(Adhesion, SceneKeyIsCheckedAndTheEventDrivenBackendIgnoresIt) {
  const std::string scenes = GRANJET_SCENES_DIR;
  EXPECT_THROW(load_scene(scenes + "/jet2d.ini", {"contact.adhesion=-1"}), InputError);
  try {
    load_scene(scenes + "/jet2d.ini", {"contact.adhesion=1", "contact.clamp_normal=true"});
    FAIL() << "a pull with a normal force clamped at zero must be refused";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "contact.adhesion");
  }
  const SceneSupport hard =
      check_backend("event_driven", load_scene(scenes + "/jet2d.ini", {"contact.adhesion=1"}));
  bool noted = false;
  for (const std::string& note : hard.notes) noted |= note.find("adhesion") != std::string::npos;
  EXPECT_TRUE(noted);
}

}  // namespace
}  // namespace granjet
