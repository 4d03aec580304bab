#include "app/inline_analysis.hpp"

namespace granjet {

template <int D>
InlineAnalysis<D>::InlineAnalysis(const Scene& scene, Simulator<D>& sim)
    : analysis_(analysis::AnalysisConfig::for_scene(scene)) {
  sim.record_transfers(true);  // the event-driven backend keeps impulses only when asked
}

template <int D>
void InlineAnalysis<D>::observe(Simulator<D>& sim) {
  if (!analysis_.due(sim.time())) return;
  const auto start = std::chrono::steady_clock::now();
  // Every sample collects, inside the window or not, so the transfers always cover exactly the
  // time since the previous sample.
  transfers_.clear();
  sim.collect_transfers(transfers_);
  analysis_.sample(sim.time(), sim.particles(), transfers_);
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

template class InlineAnalysis<2>;
template class InlineAnalysis<3>;

}  // namespace granjet
