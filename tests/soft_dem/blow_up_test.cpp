// Numerical blow-ups are caught and reported with step, time and grain ids, never carried on
// as silent NaNs.
#include <gtest/gtest.h>

#include <limits>

#include "core/errors.hpp"
#include "soft_dem/dem_simulator.hpp"

namespace granjet {
namespace {

Scene free_space(IntegratorKind integrator) {
  Scene s;
  s.kind = SceneKind::kBinary;  // free space, no target
  s.contact.friction = 0.0;
  s.run.integrator = integrator;
  return s;
}

TEST(BlowUp, OverflowingGrainIsReportedAsNonFiniteWithItsId) {
  for (IntegratorKind integrator :
       {IntegratorKind::kAdamsBashforth2, IntegratorKind::kVelocityVerlet}) {
    Particles<3> p;
    p.add(7, GrainKind::kFree, Vec<3>::Zero(), Vec<3>(1e308, 0, 0), 0.5, 1.0);
    p.add(8, GrainKind::kFree, Vec<3>(5, 0, 0), Vec<3>::Zero(), 0.5, 1.0);
    dem::DemSimulator<3, false> sim(free_space(integrator), p);
    try {
      sim.advance_to(10.0);  // x overflows to inf near t = 1.8
      ADD_FAILURE() << "no blow-up reported";
    } catch (const BlowUpError& e) {
      EXPECT_NE(std::string(e.what()).find("non-finite"), std::string::npos) << e.what();
      ASSERT_EQ(e.grain_ids().size(), 1u);
      EXPECT_EQ(e.grain_ids()[0], 7);
      EXPECT_GT(e.step(), 0);
    }
  }
}

TEST(BlowUp, DeepOverlapNamesThePair) {
  Particles<3> p;
  p.add(3, GrainKind::kFree, Vec<3>::Zero(), Vec<3>::Zero(), 0.5, 1.0);
  p.add(4, GrainKind::kFree, Vec<3>(0.6, 0, 0), Vec<3>::Zero(), 0.5, 1.0);  // overlap 0.4 > 0.25
  try {
    dem::DemSimulator<3, false> sim(free_space(IntegratorKind::kAdamsBashforth2), p);
    sim.advance_to(0.01);
    ADD_FAILURE() << "no blow-up reported";
  } catch (const BlowUpError& e) {
    EXPECT_NE(std::string(e.what()).find("run.max_overlap"), std::string::npos) << e.what();
    EXPECT_EQ(e.grain_ids(), (std::vector<GrainId>{3, 4}));
  }
}

}  // namespace
}  // namespace granjet
