// Anything that watches a run as `granjet run` drives it: the measurements of analysis/ and the
// app's frames, progress rows and checkpoints. The run loop advances the simulator to the
// earliest time any observer asks for, then lets every observer look, in their order. Observers
// see the run through the Simulator interface only, so each serves either backend.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/simulator.hpp"
#include "core/state_archive.hpp"

namespace granjet::analysis {

template <int D>
class RunObserver {
 public:
  virtual ~RunObserver() = default;

  // When it next wants to look: a time after sim.time() (infinity: only when another looks).
  virtual double next_time(const Simulator<D>& sim) const = 0;
  // Looks at the run at sim.time(); called after every advance_to, whoever asked for it.
  virtual void observe(Simulator<D>& sim) = 0;

  // Its part of a checkpoint, in the group of that name, so that the observer of a resumed run
  // goes on where this one stopped.
  virtual std::string state_group() const = 0;
  // Its name in a run's profile (`granjet run --profile`).
  virtual std::string profile_name() const { return state_group(); }
  virtual void save_state(StateWriter& out) = 0;
  virtual void restore_state(StateReader& in) = 0;

  // Adds its part to the run's summary, whatever the run's outcome.
  virtual void summarize(Simulator<D>& sim, nlohmann::json& summary) {
    (void)sim;
    (void)summary;
  }
  // After a complete run: stores what else it produced into the run's file `file` (which will
  // be renamed `published_as`) and the summary. Returns a line to tell the user, or "".
  virtual std::string store(const std::filesystem::path& file,
                            const std::filesystem::path& published_as, nlohmann::json& summary) {
    (void)file;
    (void)published_as;
    (void)summary;
    return {};
  }
};

// The checkpoint half of RunObserver from the observer's one list of members, `visit_state`
// (core/state_archive.hpp), which serves both directions.
template <int D, class Self>
class VisitingObserver : public RunObserver<D> {
 public:
  void save_state(StateWriter& out) final { static_cast<Self&>(*this).visit_state(out); }
  void restore_state(StateReader& in) final { static_cast<Self&>(*this).visit_state(in); }
};

}  // namespace granjet::analysis
