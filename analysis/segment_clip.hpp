// Exact partition of a segment among the bins [C.31]-[C.33]: the contact stress of a momentum
// transfer between grains i and j is shared among the bins in proportion to the length of the
// segment r_i -> r_j inside each.
#pragma once

#include <algorithm>
#include <vector>

#include "analysis/bin_grid.hpp"

namespace granjet::analysis {

// Calls piece(bin, s0, s1) for every stretch a + s (b - a), s in [s0, s1], that lies in one bin.
// The breakpoints are the exact crossings of every bin border (quadratic in s for cylinders,
// linear for planes), so each stretch lies in a single bin or none, which its midpoint decides.
// `scratch` is reused between calls to avoid allocations.
template <class Coordinates, class Piece>
void clip_segment(const Coordinates& coords, const typename Coordinates::VecT& a,
                  const typename Coordinates::VecT& b, std::vector<double>& scratch,
                  Piece&& piece) {
  const BinGrid& grid = coords.grid();
  const double ha = coords.height(a), hb = coords.height(b);
  if (std::max(ha, hb) < 0.0 || std::min(ha, hb) > grid.top()) return;
  const auto [lo, hi] = coords.lateral_extent(a, b);
  if (hi < grid.lateral_edge(0) || lo > grid.lateral_edge(grid.lateral_bins())) return;

  scratch.assign({0.0, 1.0});
  for (int k = 0; k <= grid.lateral_bins(); ++k) {
    const double edge = grid.lateral_edge(k);
    if (edge >= lo && edge <= hi) coords.lateral_crossings(a, b, edge, scratch);
  }
  if (ha != hb)
    for (int l = 0; l <= grid.layers(); ++l) {
      const double s = (grid.normal_edge(l) - ha) / (hb - ha);
      if (s > 0.0 && s < 1.0) scratch.push_back(s);
    }
  std::sort(scratch.begin(), scratch.end());
  for (std::size_t k = 0; k + 1 < scratch.size(); ++k) {
    const double s0 = scratch[k], s1 = scratch[k + 1];
    if (s1 <= s0) continue;
    const typename Coordinates::VecT mid = a + 0.5 * (s0 + s1) * (b - a);
    const int bin = grid.bin_at(coords.lateral(mid), coords.height(mid));
    if (bin >= 0) piece(bin, s0, s1);
  }
}

}  // namespace granjet::analysis
