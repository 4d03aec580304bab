// spread_loop_times: a rank's measured time shared among its grains by the loops' items.
#include "soft_dem/loop_weights.hpp"

#include <gtest/gtest.h>

#include <numeric>
#include <vector>

namespace granjet::dem {
namespace {

double sum(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

TEST(LoopWeights, EachLoopGoesToItsItemsAndTheRestEvenly) {
  // 10 s: a loop of 4 s over 4 items (1 s each), one of 2 s over 1 item, 4 s left for 4 grains.
  const std::vector<double> pairs{1.0, 1.0, 0.0, 2.0}, contacts{0.0, 0.0, 1.0, 0.0};
  const std::vector<TimedLoop> loops{{4.0, pairs}, {2.0, contacts}};
  const std::vector<double> w = spread_loop_times(10.0, 4, loops);
  ASSERT_EQ(w.size(), 4u);
  EXPECT_DOUBLE_EQ(w[0], 2.0);
  EXPECT_DOUBLE_EQ(w[1], 2.0);
  EXPECT_DOUBLE_EQ(w[2], 3.0);
  EXPECT_DOUBLE_EQ(w[3], 3.0);
  EXPECT_DOUBLE_EQ(sum(w), 10.0);
}

TEST(LoopWeights, ALoopWithoutItemsLeavesItsTimeToTheRest) {
  const std::vector<double> pairs{1.0, 3.0}, none{0.0, 0.0};
  const std::vector<TimedLoop> with_empty{{4.0, pairs}, {3.0, none}};
  const std::vector<TimedLoop> without{{4.0, pairs}};
  EXPECT_EQ(spread_loop_times(8.0, 2, with_empty), spread_loop_times(8.0, 2, without));
  const std::vector<double> w = spread_loop_times(8.0, 2, with_empty);
  EXPECT_DOUBLE_EQ(w[0], 1.0 + 2.0);  // 1 s of pairs, half the 4 s left
  EXPECT_DOUBLE_EQ(w[1], 3.0 + 2.0);
}

TEST(LoopWeights, LoopsBeyondTheTotalLeaveNoRestAndNoNegativeWeight) {
  // Timers that overlap can add up to more than the rank's time: the grains keep the loops'.
  const std::vector<double> items{1.0, 0.0, 1.0};
  const std::vector<TimedLoop> loops{{6.0, items}};
  const std::vector<double> w = spread_loop_times(5.0, 3, loops);
  EXPECT_DOUBLE_EQ(w[0], 3.0);
  EXPECT_DOUBLE_EQ(w[1], 0.0);
  EXPECT_DOUBLE_EQ(w[2], 3.0);
}

TEST(LoopWeights, QuietGrainsWeighLittleBesideContacts) {
  // A rank of 1000 quiet grains and 10 in contact, whose contacts take 90% of its time: the
  // contact grains carry it, where "1 + tested pairs" would have the quiet grains carry most.
  std::vector<double> contacts(1010, 0.0);
  for (int i = 1000; i < 1010; ++i) contacts[i] = 6.0;
  const std::vector<TimedLoop> loops{{0.9, contacts}};
  const std::vector<double> w = spread_loop_times(1.0, 1010, loops);
  const double quiet = std::accumulate(w.begin(), w.begin() + 1000, 0.0);
  EXPECT_NEAR(quiet, 0.1 * 1000.0 / 1010.0, 1e-12);
  EXPECT_NEAR(sum(w), 1.0, 1e-12);
}

TEST(LoopWeights, NoGrainsNoWeights) { EXPECT_TRUE(spread_loop_times(1.0, 0, {}).empty()); }

}  // namespace
}  // namespace granjet::dem
