// Wall time per phase of a run, for `granjet run --profile`: where a step's time goes and how
// much of it ran on one thread while the others waited (the part no thread count shortens,
// Amdahl's serial share). A phase is registered once with its kind; a Timer adds the wall time
// of its scope. Disabled (the default) a Timer costs one branch: no clock is read. A phase whose
// loops are shared out by core/balanced_split.hpp also gets its threads' times at work on their
// shares: the rest of its wall time is spent waiting (for the slowest share, at barriers, in
// forks and joins, in the parts one thread runs alone).
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace granjet {

class PhaseProfile {
 public:
  enum class Kind : std::uint8_t { kParallel, kSerial };

  struct Phase {
    std::string name;
    Kind kind;
    double seconds = 0.0;
    std::int64_t calls = 0;
    // Summed over its shared loops and calls: the threads' mean time at work on their shares,
    // and the slowest thread's (zero where no loop of the phase reports shares).
    double work_seconds = 0.0;
    double slowest_seconds = 0.0;
  };

  // Adds the wall time of its scope to one phase (nothing while the profile is disabled).
  class Timer {
   public:
    Timer(PhaseProfile* profile, int phase)
        : profile_(profile != nullptr && profile->enabled_ ? profile : nullptr), phase_(phase) {
      if (profile_ != nullptr) start_ = Clock::now();
    }
    ~Timer() {
      if (profile_ == nullptr) return;
      Phase& p = profile_->phases_[phase_];
      p.seconds += std::chrono::duration<double>(Clock::now() - start_).count();
      ++p.calls;
    }
    Timer(const Timer&) = delete;
    Timer& operator=(const Timer&) = delete;

   private:
    PhaseProfile* profile_;
    int phase_;
    std::chrono::steady_clock::time_point start_;
  };

  void enable() { enabled_ = true; }
  bool enabled() const { return enabled_; }

  // The phase of that name, registered on first use; its index for Timer.
  int phase(const std::string& name, Kind kind) {
    for (std::size_t k = 0; k < phases_.size(); ++k)
      if (phases_[k].name == name) return static_cast<int>(k);
    phases_.push_back({name, kind});
    return static_cast<int>(phases_.size()) - 1;
  }
  const std::vector<Phase>& phases() const { return phases_; }
  // Each phase's seconds, in the order of phases().
  std::vector<double> phase_seconds() const {
    std::vector<double> seconds;
    for (const Phase& p : phases_) seconds.push_back(p.seconds);
    return seconds;
  }

  // One pass of a shared loop of `phase`: each thread's seconds on its share.
  void add_shares(int phase, std::span<const double> seconds) {
    if (!enabled_ || seconds.empty()) return;
    double total = 0.0, slowest = 0.0;
    for (double s : seconds) {
      total += s;
      slowest = std::max(slowest, s);
    }
    Phase& p = phases_[phase];
    p.work_seconds += total / static_cast<double>(seconds.size());
    p.slowest_seconds += slowest;
  }

  // Seconds in phases of one kind.
  double seconds(Kind kind) const {
    double total = 0.0;
    for (const Phase& p : phases_)
      if (p.kind == kind) total += p.seconds;
    return total;
  }

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_ = false;
  std::vector<Phase> phases_;
};

}  // namespace granjet
