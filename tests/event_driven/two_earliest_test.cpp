// two_earliest (event_driven/two_earliest.hpp) keeps what a scan in index order with strict
// comparisons keeps: the earliest time at its first index, then the earliest of the rest, ties
// included, whatever lane the times fall in.
#include "event_driven/two_earliest.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "core/random.hpp"

namespace granjet::ed {
namespace {

Earliest scanned(const std::vector<double>& t) {
  Earliest e;
  for (std::size_t m = 0; m < t.size(); ++m) {
    if (t[m] < e.first) {
      e.second = e.first;
      e.second_at = e.first_at;
      e.first = t[m];
      e.first_at = m;
    } else if (t[m] < e.second) {
      e.second = t[m];
      e.second_at = m;
    }
  }
  return e;
}

TEST(TwoEarliest, KeepsWhatAStrictScanInIndexOrderKeeps) {
  Random rng(11);
  for (int round = 0; round < 20000; ++round) {
    // Few distinct values, so that ties are common, and some never.
    const std::size_t n = kEarliestLanes * (1 + rng.below(8));
    std::vector<double> t(n);
    for (double& x : t) x = rng.below(5) == 0 ? kNever : static_cast<double>(rng.below(6));
    const Earliest want = scanned(t), got = two_earliest(t.data(), n);
    ASSERT_EQ(got.first, want.first) << round;
    ASSERT_EQ(got.second, want.second) << round;
    if (want.first < kNever) {
      ASSERT_EQ(got.first_at, want.first_at) << round;
    }
    if (want.second < kNever) {
      ASSERT_EQ(got.second_at, want.second_at) << round;
    }
  }
}

}  // namespace
}  // namespace granjet::ed
