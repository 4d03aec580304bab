// What one look at a run needs of it (an analysis sample), so that a run over MPI ranks gathers
// only that to rank 0 (Simulator::particles_in, collect_transfers_in): the grains farther than
// `beyond` from the jet axis (the scattered ones; no farther than `until`, where farther ones
// were all seen at an earlier look), every wall grain, and the grains and
// momentum transfers that reach into the cylinder (3D; 2D the strip) of radius `within` about
// the jet axis between `low` and `high` along it (the measuring bins). A grain reaches into it
// by its radius, a transfer by the segment between its two positions. The tests are loosened
// by a relative 1e-9, so that at an edge the looker's own test decides: it may get more than it
// asked for, never less.
#pragma once

#include <cmath>
#include <limits>

#include "core/dim.hpp"
#include "core/jet_geometry.hpp"
#include "core/particles.hpp"

namespace granjet {

struct SampleRegion {
  double beyond = std::numeric_limits<double>::infinity();
  double until = std::numeric_limits<double>::infinity();
  double within = -1.0;  // negative: no cylinder
  double low = 0.0, high = 0.0;

  template <int D>
  bool holds_grain(const Vec<D>& x, double radius, GrainKind kind) const {
    const double across = distance_from_axis<D>(x);
    // A NaN position fails every comparison and is held.
    return kind == GrainKind::kWall ||
           (!(across <= beyond * (1.0 - kLoose)) && !(across > until * (1.0 + kLoose))) ||
           reaches(across, x[kJetAxis<D>], radius);
  }
  // The transfer between a and b (the partner's image), by its end a.
  template <int D>
  bool holds_transfer(const Vec<D>& a, const Vec<D>& b) const {
    return reaches(distance_from_axis<D>(a), a[kJetAxis<D>], (a - b).norm());
  }

 private:
  static constexpr double kLoose = 1e-9;

  template <int D>
  static double distance_from_axis(const Vec<D>& x) {
    Vec<D> across = x;
    across[kJetAxis<D>] = 0.0;
    return across.norm();
  }
  // Whether a point `across` from the axis and `along` it lies within `reach` of the cylinder.
  bool reaches(double across, double along, double reach) const {
    if (!(within >= 0.0)) return false;
    const double pad = reach + kLoose * (within + std::abs(low) + std::abs(high) + std::abs(reach));
    return !(across > within + pad || along < low - pad || along > high + pad);
  }
};

}  // namespace granjet
