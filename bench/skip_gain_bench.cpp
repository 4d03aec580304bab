// What the compile-time skips buy: the same physics, jet2d monodisperse and
// frictionless after impact (fixed target), stepped by the instantiation the factory picks and
// by ones that skip less — contact history and rotation kept (mu_p = 0, so the tangential force
// stays zero), per-grain radius lookups kept, and the 2D jet run by the 3D code in the plane
// z = 0 (its jet axis x turned onto z, so the removal region matches). particle-steps/s.
#include <benchmark/benchmark.h>

#include "core/initial_state.hpp"
#include "run/scene_file.hpp"
#include "soft_dem/dem_simulator.hpp"
#include "soft_dem/linear_spring_dashpot.hpp"

namespace {

using granjet::Particles;
using granjet::Vec;

granjet::Scene jet2d_mono_frictionless() {
  return granjet::load_scene(std::string(GRANJET_SCENES_DIR) + "/jet2d.ini",
                             {"wall.kind=fixed", "contact.friction=0", "jet.dispersity=mono"});
}

// The 2D grains in the 3D code: (x, y) -> (y, 0, x), so the 2D jet axis x becomes the 3D one z.
Particles<3> in_plane(const Particles<2>& flat) {
  Particles<3> p;
  for (std::size_t i = 0; i < flat.size(); ++i) {
    const Vec<2>& x = flat.position()[i];
    const Vec<2>& v = flat.velocity()[i];
    p.add(flat.id()[i], flat.kind()[i], Vec<3>(x.y(), 0.0, x.x()), Vec<3>(v.y(), 0.0, v.x()),
          flat.radius()[i], flat.mass()[i]);
  }
  return p;
}

template <class Sim, class Grains>
void step_after_impact(benchmark::State& state, const granjet::Scene& scene, Grains grains) {
  Sim sim(scene, std::move(grains));
  sim.advance_to(20.0);
  const double dt = scene.dt();
  const std::int64_t before = sim.stats().particle_steps;
  for (auto _ : state) sim.advance_to(sim.time() + 100 * dt);
  state.counters["particle_steps/s"] = benchmark::Counter(
      static_cast<double>(sim.stats().particle_steps - before), benchmark::Counter::kIsRate);
}

// kFriction, kMono: what the 2D code computes.
template <bool kFriction, bool kMono>
void BM_SkipGain2d(benchmark::State& state) {
  const granjet::Scene scene = jet2d_mono_frictionless();
  using Law = granjet::dem::LinearSpringDashpot<2, kFriction>;
  step_after_impact<granjet::dem::DemSimulator<2, Law, kMono>>(
      state, scene, granjet::build_initial_state<2>(scene));
}

void BM_SkipGain2dAs3d(benchmark::State& state) {
  const granjet::Scene scene = jet2d_mono_frictionless();
  using Law = granjet::dem::LinearSpringDashpot<3, false>;
  step_after_impact<granjet::dem::DemSimulator<3, Law, true>>(
      state, scene, in_plane(granjet::build_initial_state<2>(scene)));
}

}  // namespace

BENCHMARK(BM_SkipGain2d<false, true>)->Name("BM_SkipGain/all_skips")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SkipGain2d<true, true>)
    ->Name("BM_SkipGain/with_history_and_rotation")
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SkipGain2d<false, false>)
    ->Name("BM_SkipGain/with_radius_lookups")
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SkipGain2dAs3d)->Name("BM_SkipGain/as_3d")->Unit(benchmark::kMillisecond);
