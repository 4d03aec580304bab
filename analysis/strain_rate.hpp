// Shear strain rate per bin from half-bin differences (model §6): D = (dv_lat/dh + dv_h/dlat)/2,
// i.e. D_rz = (dv_r/dz + dv_z/dr)/2 in 3D and D_xy = (dv_y/dx + dv_x/dy)/2 in 2D.
//  - normal derivative: the upper and lower halves of the bin;
//  - lateral derivative: the two bins shifted by half a bin whose centres are the bin's edges.
// Each difference is divided by the difference of the mass-weighted mean positions of the two
// regions rather than by the nominal spacing, so a linear velocity field gives its gradient
// exactly whatever the grain positions (in a ring the mean radius is not the mid-radius).
#pragma once

#include <span>

#include "analysis/bin_grid.hpp"
#include "core/dim.hpp"

namespace granjet::analysis {

// Sums over the grains of one half-cell and over the samples.
template <int D>
struct HalfCellSums {
  double mass = 0.0;
  Vec<D> momentum = Vec<D>::Zero();  // local frame
  double lateral = 0.0;              // sum of m * lateral coordinate
  double height = 0.0;               // sum of m * h
};

// D of `bin`; NaN when a region it needs holds no grain. `lateral_axis` and `normal_axis` are
// the local-frame indices of v_lat and v_h.
template <int D>
double shear_rate(const BinGrid& grid, std::span<const HalfCellSums<D>> cells, int bin,
                  int lateral_axis, int normal_axis);

extern template double shear_rate<2>(const BinGrid&, std::span<const HalfCellSums<2>>, int, int,
                                     int);
extern template double shear_rate<3>(const BinGrid&, std::span<const HalfCellSums<3>>, int, int,
                                     int);

}  // namespace granjet::analysis
