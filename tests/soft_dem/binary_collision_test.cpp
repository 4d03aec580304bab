// Binary head-on collision on the DEM backend: the restitution and contact time measured from
// the trajectory match the requested (e, t_c) within 0.5% at dt = 0.02 t_c, for both
// integrators, 2D and 3D, and several start gaps (the contact starts at different phases of a
// step).
#include <gtest/gtest.h>

#include "two_grains.hpp"

namespace granjet {
namespace {

struct Case {
  int dimension;
  IntegratorKind integrator;
  double e;
};

class BinaryHeadOn : public ::testing::TestWithParam<Case> {};

template <int D>
void check(const Case& c) {
  for (double gap : {0.0537, 0.0311, 0.0779}) {
    Scene s = testing::binary_scene(D, c.e, 0.2, c.integrator);
    s.binary.gap = gap;
    SCOPED_TRACE("gap " + std::to_string(gap));
    const auto run = testing::run_two_grains<D>(s);
    ASSERT_TRUE(run.tracker.complete());
    EXPECT_NEAR(run.tracker.restitution() / c.e, 1.0, 0.005);
    EXPECT_NEAR(run.tracker.contact_time() / 0.1, 1.0, 0.005);
  }
}

TEST_P(BinaryHeadOn, Eq3_4_Eq3_5_MeasuredRestitutionAndContactTime) {
  if (GetParam().dimension == 2)
    check<2>(GetParam());
  else
    check<3>(GetParam());
}

std::vector<Case> cases() {
  std::vector<Case> out;
  for (int d : {2, 3})
    for (IntegratorKind i : {IntegratorKind::kAdamsBashforth2, IntegratorKind::kVelocityVerlet})
      for (double e : {0.75, 0.9, 0.99}) out.push_back({d, i, e});
  return out;
}

INSTANTIATE_TEST_SUITE_P(AllCases, BinaryHeadOn, ::testing::ValuesIn(cases()),
                         [](const auto& info) {
                           const Case& c = info.param;
                           return std::to_string(c.dimension) + "D_" +
                                  (c.integrator == IntegratorKind::kAdamsBashforth2 ? "ab2"
                                                                                    : "verlet") +
                                  "_e" + std::to_string(static_cast<int>(c.e * 100));
                         });

}  // namespace
}  // namespace granjet
