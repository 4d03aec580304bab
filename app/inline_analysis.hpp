// The study's measurements (spec §6) taken while a jet runs, so a 20,000-grain run need not
// store its trajectory: samples particles and momentum transfers every
// analysis.sample_interval, through the Simulator interface only (either backend).
#pragma once

#include <chrono>
#include <vector>

#include "analysis/run_analysis.hpp"
#include "core/scene.hpp"
#include "core/simulator.hpp"

namespace granjet {

template <int D>
class InlineAnalysis {
 public:
  InlineAnalysis(const Scene& scene, Simulator<D>& sim);

  // The next time at which the analysis wants to look at the run.
  double next_time() const { return analysis_.next_sample_time(); }
  // Looks at the run at sim.time() (call after every advance_to).
  void observe(Simulator<D>& sim);
  analysis::RunResult finish() const { return analysis_.finish(); }
  // Whether any sample fell inside the analysis window (false: the run ended before it).
  bool window_sampled() const { return analysis_.field_accumulator().samples() > 0; }
  // Wall time spent in observe(), to report what the analysis costs the run.
  double seconds() const { return seconds_; }

  template <class Visitor>
  void visit_state(Visitor& v) {
    analysis_.visit_state(v);
  }

 private:
  analysis::RunAnalysis<D> analysis_;
  std::vector<PairImpulse<D>> transfers_;
  double seconds_ = 0.0;
};

extern template class InlineAnalysis<2>;
extern template class InlineAnalysis<3>;

}  // namespace granjet
