#include "analysis/strain_rate.hpp"

#include <initializer_list>
#include <limits>

namespace granjet::analysis {
namespace {

// The merged sums of the half-cells lateral a0..a1 x normal b0..b1.
template <int D>
HalfCellSums<D> region(const BinGrid& grid, std::span<const HalfCellSums<D>> cells, int a0, int a1,
                       int b0, int b1) {
  HalfCellSums<D> sum;
  for (int b = b0; b <= b1; ++b)
    for (int a = a0; a <= a1; ++a) {
      const HalfCellSums<D>& c = cells[grid.half_cell(a, b)];
      sum.mass += c.mass;
      sum.momentum += c.momentum;
      sum.lateral += c.lateral;
      sum.height += c.height;
    }
  return sum;
}

}  // namespace

template <int D>
double shear_rate(const BinGrid& grid, std::span<const HalfCellSums<D>> cells, int bin,
                  int lateral_axis, int normal_axis) {
  const int k = grid.lateral_of(bin), l = grid.layer_of(bin);
  // Bin k holds lateral half-cells 2k+1, 2k+2; layer l normal half-cells 2l, 2l+1 (bin_grid.hpp).
  const auto lower = region(grid, cells, 2 * k + 1, 2 * k + 2, 2 * l, 2 * l);
  const auto upper = region(grid, cells, 2 * k + 1, 2 * k + 2, 2 * l + 1, 2 * l + 1);
  const auto left = region(grid, cells, 2 * k, 2 * k + 1, 2 * l, 2 * l + 1);
  const auto right = region(grid, cells, 2 * k + 2, 2 * k + 3, 2 * l, 2 * l + 1);
  for (const auto* r : {&lower, &upper, &left, &right})
    if (r->mass <= 0.0) return std::numeric_limits<double>::quiet_NaN();
  const double dvlat_dh =
      (upper.momentum[lateral_axis] / upper.mass - lower.momentum[lateral_axis] / lower.mass) /
      (upper.height / upper.mass - lower.height / lower.mass);
  const double dvh_dlat =
      (right.momentum[normal_axis] / right.mass - left.momentum[normal_axis] / left.mass) /
      (right.lateral / right.mass - left.lateral / left.mass);
  return 0.5 * (dvlat_dh + dvh_dlat);
}

template double shear_rate<2>(const BinGrid&, std::span<const HalfCellSums<2>>, int, int, int);
template double shear_rate<3>(const BinGrid&, std::span<const HalfCellSums<3>>, int, int, int);

}  // namespace granjet::analysis
