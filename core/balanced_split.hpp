// Shares the items of a loop that runs every step (pairs, contacts, grains) among a team of
// threads so that each share takes about as long as the others, from how long each share took
// at the last pass. The cost of an item varies along a jet's lists (contacts of the impact
// region against those of the arriving column, grains pushed against grains coasting), so
// shares of equal count leave threads waiting at the next barrier. Every loop it serves gives
// the same results for any share-out (each one joins its threads' parts in order), so only the
// speed depends on the timings.
//
// The split is kept as cut points, fractions of the items: thread t takes [cut_t, cut_t+1).
// After a pass each share's time spreads evenly over its items; the new cuts give every thread
// an equal part of the total, and the cuts move halfway there (timings are noisy).
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/phase_profile.hpp"

namespace granjet {

class BalancedSplit {
 public:
  explicit BalancedSplit(int threads = 1) : cut_(threads + 1), seconds_(threads, 0.0) {
    for (int t = 0; t <= threads; ++t) cut_[t] = static_cast<double>(t) / threads;
  }

  // Thread t's items [begin, end) of n, cut at multiples of `grain`. A team of another size than
  // the split's shares the items evenly.
  std::pair<std::int64_t, std::int64_t> share(int t, int team, std::int64_t n,
                                              std::int64_t grain = 1) const {
    const auto at = [&](int s) -> std::int64_t {
      if (s == 0) return 0;
      if (s == team) return n;
      const double fraction =
          team + 1 == static_cast<int>(cut_.size()) ? cut_[s] : static_cast<double>(s) / team;
      const auto grains = static_cast<std::int64_t>(fraction * static_cast<double>(n) / grain);
      return std::min(n, grains * grain);
    };
    return {at(t), at(t + 1)};
  }

  // How long thread t's share took at this pass (each thread its own slot).
  void record(int t, double seconds) {
    if (t < static_cast<int>(seconds_.size())) seconds_[t] = seconds;
  }

  // Moves the cuts halfway towards equal times, once the team's times are recorded; they are
  // first added to `phase` of `profile` (where given) as its threads' time at work.
  void rebalance(PhaseProfile* profile = nullptr, int phase = 0) {
    if (profile != nullptr) profile->add_shares(phase, seconds_);
    const int team = static_cast<int>(seconds_.size());
    double total = 0.0;
    for (double s : seconds_) total += s;
    if (!(total > 0.0)) return;
    std::vector<double> next(cut_.size());
    next.front() = 0.0;
    next.back() = 1.0;
    // Walk the shares, each a run of time spread evenly over its fraction of the items.
    int s = 0;
    double reached = 0.0;  // the time of shares before s
    for (int t = 1; t < team; ++t) {
      const double target = total * t / team;
      while (s < team - 1 && reached + seconds_[s] < target) reached += seconds_[s++];
      const double within = seconds_[s] > 0.0 ? (target - reached) / seconds_[s] : 0.0;
      next[t] = cut_[s] + std::clamp(within, 0.0, 1.0) * (cut_[s + 1] - cut_[s]);
    }
    for (int t = 1; t < team; ++t) cut_[t] = 0.5 * (cut_[t] + next[t]);
    std::fill(seconds_.begin(), seconds_.end(), 0.0);
  }

  const std::vector<double>& cuts() const { return cut_; }
  // The team's time on the loop at this pass, its shares' times summed (until rebalance).
  double seconds() const {
    double total = 0.0;
    for (double s : seconds_) total += s;
    return total;
  }

 private:
  std::vector<double> cut_;      // fractions: cut_[0] = 0, cut_[threads] = 1, non-decreasing
  std::vector<double> seconds_;  // each share's time at the last pass
};

// Seconds since `start`, for BalancedSplit::record.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace granjet
