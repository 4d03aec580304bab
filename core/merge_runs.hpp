// The order that sorts values which come as a few ascending runs, found by merging the runs
// pairwise: O(n log runs) comparisons of indices, no value moved. The values a domain
// decomposition gathers come so (each rank's in the order of the whole), one run per rank.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

namespace granjet {

// less(i, j): whether value i comes before value j (a strict weak order). Returns the indices
// in that order; values that compare equal keep their original order.
template <class Less>
std::vector<std::uint32_t> merged_run_order(std::size_t n, Less&& less) {
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::vector<std::size_t> start{0};  // where each ascending run begins, then n
  for (std::size_t i = 1; i < n; ++i)
    if (less(i, i - 1)) start.push_back(i);
  start.push_back(n);
  std::vector<std::uint32_t> merged(n);
  while (start.size() > 2) {
    std::vector<std::size_t> next{0};
    for (std::size_t r = 0; r + 1 < start.size(); r += 2) {
      const auto begin = order.begin();
      const std::size_t mid = start[r + 1], end = r + 2 < start.size() ? start[r + 2] : mid;
      std::merge(begin + start[r], begin + mid, begin + mid, begin + end, merged.begin() + start[r],
                 less);
      next.push_back(end);
    }
    order.swap(merged);
    start.swap(next);
  }
  return order;
}

}  // namespace granjet
