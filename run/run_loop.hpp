// The loop of `granjet run` over the run's observers (analysis/run_observer.hpp), and the
// checkpoint that holds the simulator's state with theirs (the app's group "app" of the archive,
// each observer in its own group there).
#pragma once

#include <algorithm>
#include <vector>

#include "analysis/h5md_writer.hpp"
#include "analysis/run_observer.hpp"
#include "run/interrupts.hpp"

namespace granjet {

template <int D>
using RunObservers = std::vector<analysis::RunObserver<D>*>;

// Advances the run to t_end (within half a step), each time to the earliest time an observer
// asks for, and lets every observer look there, in their order. Returns early, none looking,
// once a signal has arrived. The observers' looks are phases of the simulator's profile.
template <int D>
void observe_until(Simulator<D>& sim, double t_end, double half_step,
                   const RunObservers<D>& observers, const Interrupts& interrupts) {
  std::vector<int> phase;
  for (const analysis::RunObserver<D>* o : observers)
    phase.push_back(
        sim.profile().phase("observer: " + o->profile_name(), PhaseProfile::Kind::kSerial));
  while (sim.time() < t_end - half_step) {
    double target = t_end;
    for (const analysis::RunObserver<D>* o : observers)
      target = std::min(target, o->next_time(sim));
    sim.advance_to(target);
    if (interrupts.signal() != 0) return;  // between the observers' times: none looks
    for (std::size_t k = 0; k < observers.size(); ++k) {
      const PhaseProfile::Timer timing(&sim.profile(), phase[k]);
      observers[k]->observe(sim);
    }
  }
}

// The group of the checkpoint that holds the observers' groups.
inline constexpr const char* kObserverStates = "app";

template <int D>
void write_checkpoint(Simulator<D>& sim, const RunObservers<D>& observers,
                      analysis::H5mdWriter<D>& writer) {
  StateArchive archive;
  sim.checkpoint(archive);
  archive.put("app/time", sim.time());
  const StateWriter app(archive, kObserverStates);
  for (analysis::RunObserver<D>* o : observers) {
    StateWriter group = app.nested(o->state_group());
    o->save_state(group);
  }
  writer.write_checkpoint(archive, [&sim](int rank) { return sim.checkpoint_share(rank); });
}

template <int D>
void restore_checkpoint(Simulator<D>& sim, const RunObservers<D>& observers,
                        const StateArchive& archive) {
  sim.restore(archive);
  const StateReader app(archive, kObserverStates);
  for (analysis::RunObserver<D>* o : observers) {
    StateReader group = app.nested(o->state_group());
    o->restore_state(group);
  }
}

}  // namespace granjet
