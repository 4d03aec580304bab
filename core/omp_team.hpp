// The calling thread's place in its OpenMP team, for loops that share work out by hand (each
// thread its own stretch, joined in order so that results do not depend on the thread count).
// Outside a parallel region, or built without OpenMP: thread 0 of a team of one.
#pragma once

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

}  // namespace granjet
