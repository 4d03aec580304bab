// Runs the binary scene on the DEM backend, observing every step.
#pragma once

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

}  // namespace granjet::testing
