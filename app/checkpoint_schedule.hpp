// When a run writes its checkpoints: every run.checkpoint_interval (0: never), but not at t_end,
// where the run is complete.
#pragma once

#include <functional>
#include <limits>
#include <string>

#include "analysis/run_observer.hpp"
#include "core/scene.hpp"

namespace granjet {

template <int D>
class CheckpointSchedule final : public analysis::VisitingObserver<D, CheckpointSchedule<D>> {
 public:
  // `write` writes one.
  CheckpointSchedule(const Scene& scene, std::function<void()> write)
      : interval_(scene.run.checkpoint_interval),
        t_end_(scene.run.t_end),
        half_step_(0.5 * scene.dt()),
        next_checkpoint_(interval_ > 0.0 ? interval_ : std::numeric_limits<double>::infinity()),
        write_(std::move(write)) {}

  double next_time(const Simulator<D>&) const override { return next_checkpoint_; }
  void observe(Simulator<D>& sim) override {
    const double t = sim.time();
    if (t < next_checkpoint_ - half_step_ || t >= t_end_ - half_step_) return;
    // Before writing: the checkpoint holds the next one's time.
    while (next_checkpoint_ <= t + half_step_) next_checkpoint_ += interval_;
    write_();
  }
  std::string state_group() const override { return "run"; }
  std::string profile_name() const override { return "checkpoints"; }

  template <class Visitor>
  void visit_state(Visitor& v) {
    v("next_checkpoint", next_checkpoint_);
  }

 private:
  double interval_;
  double t_end_;
  double half_step_;
  double next_checkpoint_;
  std::function<void()> write_;
};

}  // namespace granjet
