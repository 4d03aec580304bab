// A free cluster for conservation tests: grains on a square (cubic) lattice of spacing 1.05 d,
// velocities uniform in [-speed, speed] per component, masses uniform in [1, 1 + mass_spread].
#pragma once

#include <cmath>
#include <cstdint>

#include "core/particles.hpp"
#include "core/random.hpp"

namespace granjet::testing {

template <int D>
Particles<D> lattice_cluster(int per_side, std::uint64_t seed, double speed, double mass_spread) {
  Random rng(seed);
  Particles<D> p;
  const int total = static_cast<int>(std::pow(per_side, D));
  for (int n = 0; n < total; ++n) {
    Vec<D> x, v;
    int rest = n;
    for (int d = 0; d < D; ++d) {
      x[d] = 1.05 * (rest % per_side);
      rest /= per_side;
      v[d] = speed * (2.0 * rng.uniform() - 1.0);
    }
    p.add(n, GrainKind::kFree, x, v, 0.5, 1.0 + mass_spread * rng.uniform());
  }
  return p;
}

}  // namespace granjet::testing
