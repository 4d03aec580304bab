// The study's measurements (model §6) taken while a jet runs, so a 20,000-grain run need not
// store its trajectory: samples particles and momentum transfers every
// analysis.sample_interval, through the Simulator interface only (either backend). A complete
// run stores them in its file (/fields, /analysis, the fields' sidecar) and summary.
#pragma once

#include <chrono>
#include <limits>
#include <type_traits>
#include <vector>

#include "analysis/run_analysis.hpp"
#include "analysis/run_observer.hpp"
#include "core/scene.hpp"
#include "core/simulator.hpp"

namespace granjet::analysis {

template <int D>
class InlineAnalysis final : public VisitingObserver<D, InlineAnalysis<D>> {
 public:
  InlineAnalysis(const Scene& scene, Simulator<D>& sim);

  double next_time(const Simulator<D>& sim) const override;
  void observe(Simulator<D>& sim) override;
  static constexpr const char* kStateGroup = "analysis";
  std::string state_group() const override { return kStateGroup; }
  // Where its bins' state lies in a checkpoint whose observers' groups lie under `observers`:
  // there each follower rank keeps its own part of it (OwnSampler::save_own).
  static std::string bins_state(const std::string& observers) {
    return observers + "/" + kStateGroup + "/" + RunAnalysis<D>::kFieldsState;
  }
  // A window that never opened (t_end before its start) measured nothing: no all-NaN fields,
  // and a line that says so.
  std::string store(const std::filesystem::path& file, const std::filesystem::path& published_as,
                    nlohmann::json& summary) override;

  RunResult finish() const { return analysis_.finish(); }
  // Whether any sample fell inside the analysis window (false: the run ended before it).
  bool window_sampled() const { return analysis_.field_accumulator().samples() > 0; }
  // Wall time spent in observe(), to report what the analysis costs the run.
  double seconds() const { return seconds_; }

  // Checkpoints: what the samples so far have summed, the ranks' sums joined first.
  template <class Visitor>
  void visit_state(Visitor& v) {
    if constexpr (std::is_same_v<Visitor, StateWriter>) sim_->join_samples(analysis_.bins());
    analysis_.visit_state(v);
  }

 private:
  RunAnalysis<D> analysis_;
  double half_step_;   // the least the run advances between two looks
  Simulator<D>* sim_;  // whose ranks' sums join (Simulator::join_samples)
  // Simulator::travel at the last sample (NaN: none since the start or the resume).
  double travel_at_sample_ = std::numeric_limits<double>::quiet_NaN();
  double seconds_ = 0.0;
};

extern template class InlineAnalysis<2>;
extern template class InlineAnalysis<3>;

}  // namespace granjet::analysis
