// The calling thread's place in its OpenMP team, for loops that share work out by hand (each
// thread its own stretch, joined in order so that results do not depend on the thread count).
// Outside a parallel region, or built without OpenMP: thread 0 of a team of one.
#pragma once

#include <atomic>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace granjet {

inline int team_index() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

inline int team_size() {
#ifdef _OPENMP
  return omp_get_num_threads();
#else
  return 1;
#endif
}

// Runs `serial` on the last thread of the team to arrive, then waits for it at a barrier: one
// barrier where a barrier and a single would take two, and the serial part starts as soon as the
// team's work before it is done. `arrived`: shared by the team, zero on entry.
template <class Serial>
void on_last_arrival(std::atomic<int>& arrived, Serial&& serial) {
  if (arrived.fetch_add(1, std::memory_order_acq_rel) == team_size() - 1) serial();
#pragma omp barrier
}

}  // namespace granjet
