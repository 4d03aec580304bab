// When a run over ranks cuts its parts anew (soft_dem/domain.hpp). Every kRebuildsPerLook
// neighbour rebuilds the ranks compare their work since the last look: wall time outside MPI
// calls, so that rank 0's output and analysis count and waiting for another rank does not. When
// the busiest rank's work exceeds the mean by kRecutImbalance, the parts are cut anew, each
// rank's grains weighted to add up to its work. The run's imbalance is the busiest rank's work
// over the mean, summed over the looks: the share of wall time an even split would save.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <numeric>
#include <optional>
#include <vector>

#include "core/rank_team.hpp"

namespace granjet::dem {

class WorkBalance {
 public:
  static constexpr double kRecutImbalance = 1.05;
  static constexpr std::int64_t kRebuildsPerLook = 8;

  // At a rebuild (collective): this rank's work since the last look when the parts should be
  // cut anew, none otherwise.
  std::optional<double> at_rebuild(const RankTeam& team) {
    if (++rebuilds_ < kRebuildsPerLook) return std::nullopt;
    const auto now = std::chrono::steady_clock::now();
    const double calls = RankTeam::seconds_in_calls();
    const double work = std::chrono::duration<double>(now - since_).count() - (calls - calls_);
    const std::vector<double> each = team.all_gather<double>(std::vector<double>{work});
    const double mean = std::accumulate(each.begin(), each.end(), 0.0) / each.size();
    const double busiest = *std::max_element(each.begin(), each.end());
    rebuilds_ = 0;
    since_ = now;
    calls_ = RankTeam::seconds_in_calls();
    if (!started_) {  // the first look spans the start: nothing to compare yet
      started_ = true;
      return std::nullopt;
    }
    busiest_ += busiest;
    mean_ += mean;
    if (!(busiest > kRecutImbalance * mean)) return std::nullopt;
    ++recuts_;
    return work;
  }

  double imbalance() const { return mean_ > 0.0 ? busiest_ / mean_ : 1.0; }
  std::int64_t recuts() const { return recuts_; }

 private:
  std::int64_t rebuilds_ = kRebuildsPerLook - 1;  // the first rebuild starts the clock
  bool started_ = false;
  std::chrono::steady_clock::time_point since_ = std::chrono::steady_clock::now();
  double calls_ = 0.0;
  double busiest_ = 0.0, mean_ = 0.0;  // summed over the looks
  std::int64_t recuts_ = 0;
};

}  // namespace granjet::dem
