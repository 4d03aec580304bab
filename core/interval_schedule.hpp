// The times an observer looks at a run: `next`, then every `interval` after it. A time-stepped
// run reaches a requested time only to within half a step, so a look is due within `tolerance`
// of its time (half a step; 0 for an observer that asks for times beyond the step itself).
// interval 0 means never (next is infinite).
#pragma once

#include <limits>

namespace granjet {

struct IntervalSchedule {
  double next;
  double interval;
  double tolerance;

  // The first look one interval after the start.
  static IntervalSchedule every(double interval, double tolerance) {
    return {interval > 0.0 ? interval : std::numeric_limits<double>::infinity(), interval,
            tolerance};
  }

  bool due(double t) const { return t >= next - tolerance; }
  // After a look at t: the first time of the schedule beyond it.
  void pass(double t) {
    while (next <= t + tolerance) next += interval;
  }
};

}  // namespace granjet
