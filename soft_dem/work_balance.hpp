// When a run over ranks cuts its parts anew (soft_dem/domain.hpp). The ranks meet at every step
// (the ghost states), so what a step costs is the slowest rank's pass, and the cut balances exactly
// that: each rank's work is the wall time of its per-step passes (forces and update; Verlet's
// predictor), not its rebuilds and the quiet pairs' classifications, which come once in many steps
// (a cut that evened them out would leave every other step uneven), nor rank 0's output and
// analysis, which no cut can share. Every kRebuildsPerLook neighbour rebuilds the ranks compare
// their work since the last look; when the busiest rank's exceeds the mean by kRecutImbalance, the
// parts are cut anew, each rank's grains weighted to add up to its work. The run's imbalance is the
// busiest rank's work over the mean, summed over the looks: the share of the passes' wall time an
// even split would save.
//
// A re-cut moves grains, and the moves cost: in a column of 1e6 grains in flight a re-cut moved
// a slab of it at 0.13-0.20 s, more than the imbalance it removed. So a re-cut must also pay
// for itself, as in renting against buying: what the busiest rank spent beyond the mean since
// the last re-cut, the time an even split would have saved, must exceed what the last re-cut's
// moves cost (the slowest rank's). A lasting imbalance passes that after a few looks; one
// that comes and goes with the measuring noise never does.
//
// The ranks look at every rebuild: in a jet of touching grains the impact sends a compression
// front up the column at about 20 d per unit of time, and the contacts behind it are the
// costliest part of the pass. A look every 4 rebuilds let the front run about 12 d past each
// cut and left the rank holding the column's top with several times the mean work
// (docs/performance.md, "A compression front outruns the cut").
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/rank_team.hpp"

namespace granjet::dem {

class WorkBalance {
 public:
  static constexpr double kRecutImbalance = 1.03;
  static constexpr std::int64_t kRebuildsPerLook = 1;

  // Adds its scope's wall time to the rank's work: wraps a per-step pass.
  class Pass {
   public:
    explicit Pass(WorkBalance& balance)
        : balance_(balance), start_(std::chrono::steady_clock::now()) {}
    ~Pass() {
      balance_.work_ +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }
    Pass(const Pass&) = delete;
    Pass& operator=(const Pass&) = delete;

   private:
    WorkBalance& balance_;
    std::chrono::steady_clock::time_point start_;
  };

  // Whether the next rebuild looks (and may re-cut).
  bool looks_at_next_rebuild() const { return rebuilds_ + 1 >= kRebuildsPerLook; }

  // At a rebuild (collective): this rank's work since the last look when the parts should be
  // cut anew, none otherwise.
  std::optional<double> at_rebuild(const RankTeam& team) {
    if (++rebuilds_ < kRebuildsPerLook) return std::nullopt;
    const double work = work_;
    struct Look {
      double work, recut_seconds;
    };
    const std::vector<Look> each = team.all_gather<Look>(std::vector<Look>{{work, recut_seconds_}});
    double total = 0.0, busiest = 0.0, recut_cost = 0.0;
    for (const Look& l : each) {
      total += l.work;
      busiest = std::max(busiest, l.work);
      recut_cost = std::max(recut_cost, l.recut_seconds);
    }
    const double mean = total / static_cast<double>(each.size());
    rebuilds_ = 0;
    work_ = 0.0;
    if (!started_) {  // the first look spans the start: nothing to compare yet
      started_ = true;
      return std::nullopt;
    }
    busiest_ += busiest;
    mean_ += mean;
    excess_ += busiest - mean;
    if (!(busiest > kRecutImbalance * mean) || !(excess_ > recut_cost)) return std::nullopt;
    ++recuts_;
    excess_ = 0.0;
    return work;
  }

  // The wall time of the rebuild that followed the last re-cut (the moves, this rank's part).
  void recut_took(double seconds) { recut_seconds_ = seconds; }

  // This rank's work since the last look.
  double work() const { return work_; }
  double imbalance() const { return mean_ > 0.0 ? busiest_ / mean_ : 1.0; }
  std::int64_t recuts() const { return recuts_; }

 private:
  std::int64_t rebuilds_ = kRebuildsPerLook - 1;  // the first rebuild starts the count
  bool started_ = false;
  double work_ = 0.0;                  // since the last look
  double busiest_ = 0.0, mean_ = 0.0;  // summed over the looks
  double recut_seconds_ = 0.0;         // the last re-cut's moves, on this rank
  double excess_ = 0.0;  // the busiest rank's work beyond the mean, since the last re-cut
  std::int64_t recuts_ = 0;
};

}  // namespace granjet::dem
