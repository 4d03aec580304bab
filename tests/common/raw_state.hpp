// A grain's state as raw doubles, for the tests that compare runs bit for bit (threads, ranks):
// its id, position and velocity per axis, then its spin.
#pragma once

#include <cstddef>
#include <vector>

#include "core/particles.hpp"

namespace granjet::testing {

template <int D>
void append_raw_state(std::vector<double>& out, const Particles<D>& p, std::size_t i) {
  out.push_back(static_cast<double>(p.id()[i]));
  for (int d = 0; d < D; ++d) out.insert(out.end(), {p.position()[i][d], p.velocity()[i][d]});
  const auto w = p.spin()[i];
  if constexpr (D == 2)
    out.push_back(w);
  else
    out.insert(out.end(), w.data(), w.data() + 3);
}

}  // namespace granjet::testing
