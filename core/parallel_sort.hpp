// A sort shared among threads: each sorts its own stretch, then neighbouring stretches are
// merged pairwise, in parallel, until one is left. The result is the one std::sort gives for
// any thread count whenever no two elements compare equal (the only use: unique keys).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace granjet {

template <class T, class Less>
void parallel_sort(std::vector<T>& values, Less less, int threads) {
  const auto n = static_cast<std::int64_t>(values.size());
  if (threads <= 1 || n < 4096) {  // below a few thousand the threads' start costs more
    std::sort(values.begin(), values.end(), less);
    return;
  }
  std::vector<std::int64_t> edge(threads + 1);
  for (int t = 0; t <= threads; ++t) edge[t] = n * t / threads;
  const auto at = [&](int t) { return values.begin() + edge[t]; };
#pragma omp parallel for num_threads(threads) schedule(static, 1)
  for (int t = 0; t < threads; ++t) std::sort(at(t), at(t + 1), less);
  for (int width = 1; width < threads; width *= 2) {
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
    for (int t = 0; t < threads - width; t += 2 * width)
      std::inplace_merge(at(t), at(t + width), at(std::min(threads, t + 2 * width)), less);
  }
}

}  // namespace granjet
