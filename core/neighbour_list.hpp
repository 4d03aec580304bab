// Verlet half neighbour list built from a cell grid: every pair closer than
// R_i + R_j + skin, stored once (i < j) in compressed rows. It stays valid until some grain has
// moved more than skin/2 since the build (DisplacementWatch), not rebuilt every step.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/cell_grid.hpp"

namespace granjet {

struct PairList {
  std::vector<std::uint32_t> first;    // partners of i: partner[first[i] .. first[i+1])
  std::vector<std::uint32_t> partner;  // always > i
  std::size_t size() const { return partner.size(); }
};

// `positions` must already be in grid order (cell c holds indices start(c)..start(c+1)-1).
// `excluded(i, j)` drops pairs that never interact (e.g. two wall grains).
template <int D, class Excluded>
void build_half_pairs(const CellGrid<D>& grid, std::span<const Vec<D>> positions,
                      std::span<const double> radius, double skin, Excluded&& excluded,
                      PairList& out) {
  const std::size_t n = positions.size();
  out.first.assign(n + 1, 0);
  out.partner.clear();
  auto consider = [&](std::uint32_t i, std::uint32_t j) {
    const double cut = radius[i] + radius[j] + skin;
    if ((positions[i] - positions[j]).squaredNorm() < cut * cut && !excluded(i, j))
      out.partner.push_back(j);
  };
  std::vector<std::pair<std::uint32_t, std::uint32_t>> ranges;  // the forward cells' grains
  for (std::size_t c = 0; c < grid.cells(); ++c) {
    const std::uint32_t begin = grid.start(c), end = grid.start(c + 1);
    if (begin == end) continue;
    ranges.clear();
    grid.for_each_forward_neighbour(c, [&](std::size_t other) {
      if (grid.start(other) != grid.start(other + 1))
        ranges.emplace_back(grid.start(other), grid.start(other + 1));
    });
    for (std::uint32_t i = begin; i < end; ++i) {
      for (std::uint32_t j = i + 1; j < end; ++j) consider(i, j);
      // Forward cells come later in memory, so j > i here too.
      for (const auto& [first, last] : ranges)
        for (std::uint32_t j = first; j < last; ++j) consider(i, j);
      out.first[i + 1] = static_cast<std::uint32_t>(out.partner.size());
    }
  }
}

}  // namespace granjet
