// How wide the cells of a neighbour-search grid are, for both backends' grids (core/cell_grid.hpp,
// event_driven/cell_list.hpp): as narrow as reach allows, unless a few grains scattered far away
// would make the grid over their box huge and nearly empty. Then the cells grow, by a quarter at
// a time, until there are at most `max_cells`; larger cells stay correct, only slower. How many
// empty cells are affordable is each grid's own cost: one the soft DEM walks in full at every
// rebuild, one the event-driven backend only touches around an event.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/dim.hpp"

namespace granjet {

// How a grid meets its box: whole cells stretched to tile it (at least `edge` wide, so the count
// rounds down), or cells exactly `edge` wide covering it (the last one sticking out: up).
enum class CellFit { kTile, kCover };

// The cells of a grid over `extent` with edge `edge`, at least one per axis.
template <int D>
double cells_across(const Vec<D>& extent, double edge, CellFit fit) {
  double n = 1.0;
  for (int d = 0; d < D; ++d) {
    const double across = extent[d] / edge;
    n *= std::max(1.0, fit == CellFit::kTile ? std::floor(across) : std::ceil(across));
  }
  return n;
}

// The edge, from `min_edge`, of a grid over `extent` with at most `max_cells` cells.
template <int D>
double capped_cell_edge(const Vec<D>& extent, double min_edge, double max_cells, CellFit fit) {
  double edge = min_edge;
  while (cells_across<D>(extent, edge, fit) > max_cells) edge *= 1.25;
  return edge;
}

}  // namespace granjet
