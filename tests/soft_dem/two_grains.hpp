// Runs the binary scene on the DEM backend, observing every step.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "analysis/binary_collision.hpp"
#include "soft_dem/dem_simulator.hpp"

namespace granjet::testing {

template <int D>
struct TwoGrainRun {
  analysis::BinaryCollisionTracker<D> tracker;
  Particles<D> before;  // state at t = 0
  Particles<D> after;   // state at the end, well after separation
};

inline Scene binary_scene(int dimension, double e, double friction, IntegratorKind integrator) {
  Scene s;
  s.kind = SceneKind::kBinary;
  s.dimension = dimension;
  s.contact.restitution = e;
  s.contact.contact_time = 0.1;
  s.contact.friction = friction;
  s.run.integrator = integrator;
  return s;
}

template <int D>
TwoGrainRun<D> run_two_grains(const Scene& scene, double t_end = 0.5) {
  auto sim = dem::make_dem_simulator<D>(scene);
  TwoGrainRun<D> run;
  run.before = sim->particles();
  run.tracker.observe(sim->particles(), sim->time());
  while (sim->time() < t_end) {
    sim->advance_to(sim->time() + scene.dt());
    run.tracker.observe(sim->particles(), sim->time());
  }
  run.after = sim->particles();
  return run;
}

// |F_t| / |F_n| of every contact force of a 3D binary collision sampled step by step (F_n along
// the line of centres), until t = 0.5.
inline std::vector<double> friction_ratios(const Scene& scene) {
  auto sim = dem::make_dem_simulator<3>(scene);
  std::vector<double> ratios;
  std::vector<PairImpulse<3>> transfers;
  while (sim->time() < 0.5) {
    sim->advance_to(sim->time() + scene.dt());
    transfers.clear();
    sim->collect_transfers(transfers);
    for (const PairImpulse<3>& t : transfers) {
      const Vec<3> n = (t.position_i - t.position_j).normalized();
      const double f_n = t.impulse.dot(n);
      ratios.push_back((t.impulse - f_n * n).norm() / std::abs(f_n));
    }
  }
  return ratios;
}

// [3.2]: a nearly head-on collision with strong friction mu_p: the tangential spring holds at
// first, so most samples stick (|F_t| < 0.9 mu_p |F_n|) and none leaves the cone.
inline void expect_sticking_inside_the_coulomb_cone(const Scene& s, double mu) {
  const std::vector<double> ratios = friction_ratios(s);
  ASSERT_GT(ratios.size(), 30u);
  int sticking = 0;
  for (double r : ratios) {
    EXPECT_LE(r, mu + 1e-9);
    sticking += r < 0.9 * mu;
  }
  EXPECT_GT(sticking, static_cast<int>(ratios.size()) / 2);
}

}  // namespace granjet::testing
