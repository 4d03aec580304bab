// The two kinds of space grains live in, as small policies for the pair loop: open space (jets,
// binary collisions), where a separation is a plain difference, and a periodic box [0, box)
// (gas scenes), where it is the minimum image. The neighbour cells are at least three per axis
// and one cut-off wide, so the nearest image is the only one that can be within reach.
#pragma once

#include <cmath>

#include "core/dim.hpp"

namespace granjet {

template <int D>
struct OpenSpace {
  static constexpr bool kPeriodic = false;
  // V: Vec<D>, or the force pass's plain LaneVec<D>.
  template <class V>
  V separation(const V& a, const V& b) const {
    return a - b;
  }
  void wrap(Vec<D>&) const {}
};

template <int D>
struct PeriodicBox {
  static constexpr bool kPeriodic = true;
  explicit PeriodicBox(const Vec<D>& edges) : box(edges), inv_box(edges.cwiseInverse()) {}

  // a - b shifted by whole box lengths into [-box/2, box/2].
  template <class V>
  V separation(const V& a, const V& b) const {
    return minimum_image<V>(a - b);
  }
  // The separation r shifted so.
  template <class V>
  V minimum_image(V r) const {
    for (int d = 0; d < D; ++d) r[d] -= box[d] * std::nearbyint(r[d] * inv_box[d]);
    return r;
  }
  // Back into [0, box) (grains drift out between neighbour-list builds).
  void wrap(Vec<D>& x) const {
    for (int d = 0; d < D; ++d) {
      x[d] -= box[d] * std::floor(x[d] * inv_box[d]);
      if (x[d] >= box[d]) x[d] = 0.0;  // -tiny wraps to box[d] in floating point
    }
  }

  Vec<D> box;
  Vec<D> inv_box;
};

}  // namespace granjet
