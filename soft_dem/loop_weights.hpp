// How a rank's measured pass time is shared among its grains for a re-cut of the parts
// (soft_dem/work_balance.hpp): each timed loop's seconds go to the items it went through, each
// grain weighed by its count of them; the time no loop accounts for is spread evenly. A weight
// that follows the loops keeps a rank's contacts, not its quiet grains, carrying its contact
// time: a cut weighted by a cruder count and scaled to the measured time hands the impact
// region back and forth between the two ranks beside it (docs/performance.md, "What the cut
// cannot even out").
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

namespace granjet::dem {

struct TimedLoop {
  double seconds;                 // the loop's time since the last look
  std::span<const double> items;  // per grain: how many of the loop's items are its (a pair: half)
};

// Each of `grains` grains' share of `total` seconds (the rank's time since the last look,
// summed over its threads as the loops' times are). A loop without items leaves its time to the
// even rest; loops that add up to more than `total` leave no rest.
inline std::vector<double> spread_loop_times(double total, std::size_t grains,
                                             std::span<const TimedLoop> loops) {
  std::vector<double> weight(grains, 0.0);
  if (grains == 0) return weight;
  double rest = total;
  for (const TimedLoop& loop : loops) {
    double count = 0.0;
    for (double c : loop.items) count += c;
    if (!(count > 0.0)) continue;
    rest -= loop.seconds;
    const double per_item = loop.seconds / count;
    for (std::size_t i = 0; i < grains; ++i) weight[i] += per_item * loop.items[i];
  }
  const double per_grain = std::max(rest, 0.0) / static_cast<double>(grains);
  for (double& w : weight) w += per_grain;
  return weight;
}

}  // namespace granjet::dem
