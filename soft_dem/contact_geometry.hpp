// What every contact law is evaluated on: the geometry of a contact and the relative velocity
// of the two surfaces at its contact point, written once for Eigen's Vec<D> (one contact at a
// time: plate, sampling, tests) and for the force pass's LaneVec<D> columns.
#pragma once

#include <bit>
#include <cstdint>

#include "core/dim.hpp"
#include "soft_dem/lane_vec.hpp"

namespace granjet::dem {

// Geometry of one contact between grains i and j: n points from j to i, the lever arms reach
// the common contact point on the line of centres (l_i + l_j = |r_i - r_j|), so the tangential
// force conserves angular momentum exactly. V is Vec<D>, or LaneVec<D> in the force pass.
template <class V>
struct ContactGeometryOf {
  V n;
  double overlap;
  double lever_i;
  double lever_j;
};
template <int D>
using ContactGeometry = ContactGeometryOf<Vec<D>>;

template <class V>
inline ContactGeometryOf<V> contact_geometry(const V& r_ij, double dist, double radius_i,
                                             double radius_j) {
  const double overlap = radius_i + radius_j - dist;
  return {r_ij * (1.0 / dist), overlap, radius_i - 0.5 * overlap, radius_j - 0.5 * overlap};
}

// a if `pick`, else b, one component at a time and in bits: GCC's vectoriser if-converts
// that, where a ?: between whole vectors stays a branch in the contact loop (then scalar, and
// mispredicted: in a jet about half the contacts slide). V is Vec<D> or LaneVec<D>.
template <int D, class V>
inline V select_components(bool pick, const V& a, const V& b) {
  const std::uint64_t mask = std::uint64_t{0} - std::uint64_t{pick};  // all bits, or none
  V out = b;
  for (int d = 0; d < D; ++d)
    out[d] = std::bit_cast<double>((std::bit_cast<std::uint64_t>(a[d]) & mask) |
                                   (std::bit_cast<std::uint64_t>(b[d]) & ~mask));
  return out;
}

inline Vec<2> spin_cross(double w, const Vec<2>& r) { return Dim<2>::spin_cross(w, r); }
inline Vec<3> spin_cross(const Vec<3>& w, const Vec<3>& r) { return Dim<3>::spin_cross(w, r); }

// The velocity of i's surface relative to j's at their contact point (w: spins, kRotation:
// whether the grains turn): du_t/dt of [3.2] with its rotation term, and du_n/dt of [3.1]. V is
// Vec<D> with Dim<D>::Spin, or LaneVec<D> with its spin type.
template <bool kRotation, class V, class S>
inline V relative_velocity(const V& v_i, const V& v_j, const S& w_i, const S& w_j,
                           const ContactGeometryOf<V>& g) {
  V v_rel = v_i - v_j;
  if constexpr (kRotation) v_rel -= spin_cross(S(g.lever_i * w_i + g.lever_j * w_j), g.n);
  return v_rel;
}

}  // namespace granjet::dem
