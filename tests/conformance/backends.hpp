// The backends the conformance tests run on (model §1 scenes written once, run on both), and
// what each is held to: the event-driven collision rule is exact up to rounding, the soft
// contact reproduces e within 0.5% at dt = 0.02 t_c ([3.4], [3.5]).
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "event_driven/ed_simulator.hpp"
#include "soft_dem/dem_simulator.hpp"
#include "soft_dem/linear_spring_dashpot.hpp"

namespace granjet::testing {

struct SoftDemBackend {
  static constexpr const char* kName = "soft_dem";
  static constexpr double kRestitutionTolerance = 0.005;  // relative
  template <int D>
  static std::unique_ptr<Simulator<D>> make(const Scene& scene, Particles<D> grains) {
    return std::make_unique<dem::DemSimulator<D, dem::LinearSpringDashpot<D, false>>>(
        scene, std::move(grains));
  }
};

struct EventDrivenBackend {
  static constexpr const char* kName = "event_driven";
  static constexpr double kRestitutionTolerance = 4e-16;  // a few roundings
  template <int D>
  static std::unique_ptr<Simulator<D>> make(const Scene& scene, Particles<D> grains) {
    return std::make_unique<ed::EdSimulator<D>>(scene, std::move(grains), ed::Verification::kOn);
  }
};

// Backend x dimension, for TYPED_TEST.
template <class B, int kD>
struct On {
  using Backend = B;
  static constexpr int D = kD;
};

// Every conformance test runs on all of these.
using AllBackends = ::testing::Types<On<SoftDemBackend, 2>, On<SoftDemBackend, 3>,
                                     On<EventDrivenBackend, 2>, On<EventDrivenBackend, 3>>;

}  // namespace granjet::testing
