// BalancedSplit: every item in exactly one share whatever the cuts, and cuts that move towards
// equal times for items whose cost is known.
#include "core/balanced_split.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace granjet {
namespace {

// The shares of n items for a team of `team` cover [0, n) in order, each a multiple of grain
// long (but the last).
void expect_cover(const BalancedSplit& split, int team, std::int64_t n, std::int64_t grain) {
  std::int64_t next = 0;
  for (int t = 0; t < team; ++t) {
    const auto [begin, end] = split.share(t, team, n, grain);
    EXPECT_EQ(begin, next) << "thread " << t;
    EXPECT_LE(begin, end);
    if (t + 1 < team) {
      EXPECT_EQ((end - begin) % grain, 0) << "thread " << t;
    }
    next = end;
  }
  EXPECT_EQ(next, n);
}

// The time each share of a loop takes whose item k costs cost(k / n), a density on [0, 1).
template <class Cost>
std::vector<double> share_times(const BalancedSplit& split, int team, std::int64_t n, Cost&& cost) {
  std::vector<double> times(team, 0.0);
  for (int t = 0; t < team; ++t) {
    const auto [begin, end] = split.share(t, team, n);
    for (std::int64_t k = begin; k < end; ++k)
      times[t] += cost(static_cast<double>(k) / static_cast<double>(n));
  }
  return times;
}

TEST(BalancedSplit, StartsEvenAndCoversEveryItem) {
  const BalancedSplit split(4);
  expect_cover(split, 4, 1000, 1);
  expect_cover(split, 4, 1003, 32);
  expect_cover(split, 4, 3, 32);    // fewer items than threads
  expect_cover(split, 3, 1000, 1);  // a team of another size: shared evenly
  EXPECT_EQ(split.share(1, 4, 1000), std::make_pair(std::int64_t{250}, std::int64_t{500}));
}

// Items whose cost rises linearly along the loop (cost 2x on [0, 1)): equal shares of time cut
// at x_t = sqrt(t / team). The cuts halve their distance to that at every pass.
TEST(BalancedSplit, ConvergesToEqualTimesForALinearCost) {
  const int team = 4;
  const std::int64_t n = 100000;
  BalancedSplit split(team);
  const auto cost = [](double x) { return 2.0 * x; };
  for (int pass = 0; pass < 30; ++pass) {
    const std::vector<double> times = share_times(split, team, n, cost);
    for (int t = 0; t < team; ++t) split.record(t, times[t]);
    split.rebalance();
    expect_cover(split, team, n, 1);
  }
  for (int t = 1; t < team; ++t)
    EXPECT_NEAR(split.cuts()[t], std::sqrt(static_cast<double>(t) / team), 1e-3) << t;
  const std::vector<double> times = share_times(split, team, n, cost);
  for (int t = 1; t < team; ++t) EXPECT_NEAR(times[t] / times[0], 1.0, 0.01) << t;
}

// Work crowded into one end (the impact region's contacts): cost 9 on the first tenth of the
// items and 1 on the rest, 0.9 of time each, so two threads share equal times cut at x = 0.1.
// The slow case: the first share's average cost overstates the cost at its cut by up to 9x, so
// each pass closes about 1/18 of the gap (a hundred passes are a hundred steps of a run).
TEST(BalancedSplit, FindsTheCutOfAStepDensity) {
  BalancedSplit split(2);
  const std::int64_t n = 100000;
  const auto cost = [](double x) { return x < 0.1 ? 9.0 : 1.0; };
  for (int pass = 0; pass < 200; ++pass) {
    const std::vector<double> times = share_times(split, 2, n, cost);
    split.record(0, times[0]);
    split.record(1, times[1]);
    split.rebalance();
  }
  EXPECT_NEAR(split.cuts()[1], 0.1, 1e-3);
}

TEST(BalancedSplit, KeepsItsCutsWithoutTimes) {
  BalancedSplit split(3);
  split.rebalance();  // nothing recorded
  EXPECT_DOUBLE_EQ(split.cuts()[1], 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(split.cuts()[2], 2.0 / 3.0);
}

TEST(BalancedSplit, SumsTheTeamsTimeUntilItRebalances) {
  BalancedSplit split(3);
  split.record(0, 1.5);
  split.record(2, 0.25);
  split.record(1, 0.5);
  split.record(1, 0.75);  // a thread's slot holds its latest time
  EXPECT_DOUBLE_EQ(split.seconds(), 2.5);
  split.rebalance();
  EXPECT_DOUBLE_EQ(split.seconds(), 0.0);
}

}  // namespace
}  // namespace granjet
