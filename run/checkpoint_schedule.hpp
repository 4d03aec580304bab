// When a run writes its checkpoints: every run.checkpoint_interval (0: never), but not at t_end,
// where the run is complete.
#pragma once

#include <functional>
#include <string>

#include "analysis/run_observer.hpp"
#include "core/interval_schedule.hpp"
#include "core/scene.hpp"

namespace granjet {

template <int D>
class CheckpointSchedule final : public analysis::VisitingObserver<D, CheckpointSchedule<D>> {
 public:
  // `write` writes one.
  CheckpointSchedule(const Scene& scene, std::function<void()> write)
      : schedule_(IntervalSchedule::every(scene.run.checkpoint_interval, 0.5 * scene.dt())),
        t_end_(scene.run.t_end),
        write_(std::move(write)) {}

  double next_time(const Simulator<D>&) const override { return schedule_.next; }
  void observe(Simulator<D>& sim) override {
    const double t = sim.time();
    if (!schedule_.due(t) || t >= t_end_ - schedule_.tolerance) return;
    // Before writing: the checkpoint holds the next one's time.
    schedule_.pass(t);
    write_();
  }
  std::string state_group() const override { return "run"; }
  std::string profile_name() const override { return "checkpoints"; }

  template <class Visitor>
  void visit_state(Visitor& v) {
    v("next_checkpoint", schedule_.next);
  }

 private:
  IntervalSchedule schedule_;
  double t_end_;
  std::function<void()> write_;
};

}  // namespace granjet
