// The frames of a run in its H5MD file, with their observables: the start, one every
// output.interval, and the end of the run.
#pragma once

#include <string>

#include "analysis/h5md_writer.hpp"
#include "analysis/run_observer.hpp"
#include "core/interval_schedule.hpp"
#include "core/scene.hpp"

namespace granjet {

template <int D>
class FrameOutput final : public analysis::VisitingObserver<D, FrameOutput<D>> {
 public:
  FrameOutput(analysis::H5mdWriter<D>& writer, const Scene& scene);

  double next_time(const Simulator<D>&) const override { return schedule_.next; }
  // A frame when one is due, and at t_end.
  void observe(Simulator<D>& sim) override;
  std::string state_group() const override { return "run"; }
  std::string profile_name() const override { return "frames"; }

  // The first frame, of a run that starts.
  void start(Simulator<D>& sim) { write(sim, 0); }
  // The last frame, unless the run stopped where one was written.
  void finish(Simulator<D>& sim);

  template <class Visitor>
  void visit_state(Visitor& v) {
    v("next_output", schedule_.next);
    v("last_output", last_output_);
  }

 private:
  void write(Simulator<D>& sim, std::int64_t step);

  analysis::H5mdWriter<D>& writer_;
  IntervalSchedule schedule_;
  double t_end_;
  double last_output_ = 0.0;
};

extern template class FrameOutput<2>;
extern template class FrameOutput<3>;

}  // namespace granjet
