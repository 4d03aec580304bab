#include "core/merge_runs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

namespace granjet {
namespace {

std::vector<std::uint32_t> order_of(const std::vector<int>& values) {
  return merged_run_order(values.size(),
                          [&](std::size_t i, std::size_t j) { return values[i] < values[j]; });
}

std::vector<int> in_order(const std::vector<int>& values) {
  std::vector<int> out;
  for (std::uint32_t i : order_of(values)) out.push_back(values[i]);
  return out;
}

TEST(MergedRunOrder, EmptyAndOneRun) {
  EXPECT_TRUE(order_of({}).empty());
  EXPECT_EQ(order_of({1, 2, 5}), (std::vector<std::uint32_t>{0, 1, 2}));
}

TEST(MergedRunOrder, RunsOfRanksMergeIntoTheSortedWhole) {
  // Three "ranks" of 1, 4 and 2 values, and an odd run count at every level.
  EXPECT_EQ(in_order({7, 1, 3, 8, 9, 2, 5}), (std::vector<int>{1, 2, 3, 5, 7, 8, 9}));
  EXPECT_EQ(order_of({4, 5, 1, 2, 3}), (std::vector<std::uint32_t>{2, 3, 4, 0, 1}));
}

TEST(MergedRunOrder, AgreesWithAStableSortOnRandomRuns) {
  std::mt19937 random(3);
  for (int runs = 1; runs <= 9; ++runs) {
    std::vector<int> values;
    for (int r = 0; r < runs; ++r) {
      std::vector<int> run(random() % 40);
      for (int& v : run) v = static_cast<int>(random() % 50);  // ties across runs
      std::sort(run.begin(), run.end());
      values.insert(values.end(), run.begin(), run.end());
    }
    std::vector<std::uint32_t> expected(values.size());
    std::iota(expected.begin(), expected.end(), 0u);
    std::stable_sort(expected.begin(), expected.end(),
                     [&](std::uint32_t i, std::uint32_t j) { return values[i] < values[j]; });
    EXPECT_EQ(order_of(values), expected) << runs << " runs";
  }
}

}  // namespace
}  // namespace granjet
