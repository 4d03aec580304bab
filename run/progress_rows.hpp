// The progress rows of a run (progress_table.hpp), one every run.progress_interval, and the
// run's wall clock and CPU time over all its invocations (a resumed run goes on from its
// checkpoint's).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>

#include "analysis/run_observer.hpp"
#include "core/interval_schedule.hpp"
#include "core/scene.hpp"
#include "run/progress_table.hpp"

namespace granjet {

template <int D>
class ProgressRows final : public analysis::RunObserver<D> {
 public:
  ProgressRows(std::ostream& out, const Scene& scene, bool event_driven)
      : table_(out, scene.run.t_end, /*quiet=*/false, event_driven),
        schedule_(IntervalSchedule::every(scene.run.progress_interval, 0.5 * scene.dt())) {}

  void header() { table_.header(); }
  // Of every invocation of the run so far.
  double wall_seconds() const { return earlier_seconds_ + table_.elapsed_seconds(); }
  double cpu_seconds() const { return earlier_cpu_seconds_ + table_.cpu_seconds(); }

  double next_time(const Simulator<D>&) const override { return schedule_.next; }
  void observe(Simulator<D>& sim) override {
    const double t = sim.time();
    if (!schedule_.due(t)) return;
    table_.row(t, static_cast<std::int64_t>(sim.grain_count()), sim.stats(), sim.energy());
    schedule_.pass(t);
  }
  std::string state_group() const override { return "run"; }
  std::string profile_name() const override { return "progress rows"; }
  void save_state(StateWriter& out) override {
    out("next_progress", schedule_.next);
    out("wall_seconds", wall_seconds());
    out("cpu_seconds", cpu_seconds());
  }
  void restore_state(StateReader& in) override {
    in("next_progress", schedule_.next);
    in("wall_seconds", earlier_seconds_);
    if (in.contains("cpu_seconds")) in("cpu_seconds", earlier_cpu_seconds_);
  }

 private:
  ProgressTable table_;
  IntervalSchedule schedule_;
  double earlier_seconds_ = 0.0;      // of the invocations before this one
  double earlier_cpu_seconds_ = 0.0;  // checkpoints before it was kept start it at 0
};

}  // namespace granjet
