#include "run/frame_output.hpp"

namespace granjet {
namespace {

template <int D>
analysis::Observables observables(const Simulator<D>& sim, std::size_t grains) {
  const EnergyBalance e = sim.energy();
  return {e.kinetic, e.rotational, e.elastic, e.dissipated, static_cast<std::int64_t>(grains)};
}

// The H5MD step of a frame: DEM counts time steps, the event-driven backend events.
std::int64_t frame_step(const SimStats& s) { return s.steps > 0 ? s.steps : s.events; }

}  // namespace

template <int D>
FrameOutput<D>::FrameOutput(analysis::H5mdWriter<D>& writer, const Scene& scene)
    : writer_(writer),
      schedule_(IntervalSchedule::every(scene.output.interval, 0.5 * scene.dt())),
      t_end_(scene.run.t_end) {}

template <int D>
void FrameOutput<D>::observe(Simulator<D>& sim) {
  const double t = sim.time();
  if (!schedule_.due(t) && t < t_end_ - schedule_.tolerance) return;
  write(sim, frame_step(sim.stats()));
  last_output_ = t;
  schedule_.pass(t);
}

template <int D>
void FrameOutput<D>::finish(Simulator<D>& sim) {
  if (last_output_ < sim.time()) write(sim, frame_step(sim.stats()));
}

template <int D>
void FrameOutput<D>::write(Simulator<D>& sim, std::int64_t step) {
  const std::size_t grains = writer_.write_frame(step, sim.time(), sim);
  writer_.write_observables(step, sim.time(), observables(sim, grains));
}

template class FrameOutput<2>;
template class FrameOutput<3>;

}  // namespace granjet
