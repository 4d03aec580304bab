// The contacts of one force pass, one array per component (structure of arrays): each
// contact's geometry and relative velocity in, its force and torques out. The law runs over a
// stretch of contacts on LaneVec<D> values, a loop GCC vectorises (see lane_vec.hpp); the sums
// per grain read the results back one contact at a time.
#pragma once

#include <array>
#include <cstddef>
#include <type_traits>
#include <vector>

#include "core/dim.hpp"
#include "soft_dem/contact_geometry.hpp"
#include "soft_dem/lane_vec.hpp"
#include "soft_dem/rolling_resistance.hpp"

namespace granjet::dem {

// Read-only raw pointers to W columns, for loops that also store through Eigen: its stores
// may alias anything, so reads through the owning vectors would reload their pointers.
template <int W>
struct ColumnsView {
  std::array<const double*, W> col;

  // As an Eigen vector, or a double when W = 1.
  template <class V>
  V get(std::size_t c) const {
    if constexpr (std::is_arithmetic_v<V>) {
      return col[0][c];
    } else {
      V v;
      for (int d = 0; d < W; ++d) v[d] = col[d][c];
      return v;
    }
  }
};

// W arrays of one per-contact quantity (a vector, or with W = 1 a scalar such as a 2D spin).
template <int W>
class Columns {
 public:
  void resize(std::size_t n) {
    for (std::vector<double>& col : col_) col.resize(n);
  }
  void swap(Columns& other) { col_.swap(other.col_); }

  LaneVec<W> load(std::size_t c) const {
    LaneVec<W> v;
    for (int d = 0; d < W; ++d) v.c[d] = col_[d][c];
    return v;
  }
  // A spin: a scalar in 2D (W = 1), a LaneVec<3> in 3D.
  auto load_spin(std::size_t c) const {
    if constexpr (W == 1)
      return col_[0][c];
    else
      return load(c);
  }
  void store(std::size_t c, const LaneVec<W>& v) {
    for (int d = 0; d < W; ++d) col_[d][c] = v.c[d];
  }
  ColumnsView<W> view() const {
    ColumnsView<W> v;
    for (int d = 0; d < W; ++d) v.col[d] = col_[d].data();
    return v;
  }
  template <class V>
  V get(std::size_t c) const {
    return view().template get<V>(c);
  }
  // From an Eigen vector, a LaneVec, or a double when W = 1.
  template <class V>
  void set(std::size_t c, const V& v) {
    if constexpr (std::is_arithmetic_v<V>) {
      col_[0][c] = v;
    } else {
      for (int d = 0; d < W; ++d) col_[d][c] = v[d];
    }
  }

 private:
  std::array<std::vector<double>, W> col_;
};

// kRotation: whether the law's forces turn the grains (the torque columns exist only then);
// kRolling: whether it resists the grains' rolling (rolling_resistance.hpp), which needs the
// contacts' relative spins.
template <int D, bool kRotation, bool kRolling = false>
class ContactTable {
 public:
  static constexpr int kSpinWidth = D == 3 ? 3 : 1;

  void resize(std::size_t n) {
    normal_.resize(n);
    overlap_.resize(n);
    lever_i_.resize(n);
    lever_j_.resize(n);
    v_rel_.resize(n);
    force_.resize(n);
    if constexpr (kRotation) {
      torque_i_.resize(n);
      torque_j_.resize(n);
    }
    if constexpr (kRolling) w_rel_.resize(n);
  }
  template <class V>  // Vec<D> or LaneVec<D>
  void set(std::size_t c, const ContactGeometryOf<V>& g, const V& v_rel) {
    normal_.set(c, g.n);
    overlap_[c] = g.overlap;
    lever_i_[c] = g.lever_i;
    lever_j_[c] = g.lever_j;
    v_rel_.set(c, v_rel);
  }
  // Rolling laws: the spin of i relative to j.
  template <class S>
  void set_relative_spin(std::size_t c, const S& w_rel) {
    w_rel_.set(c, w_rel);
  }

  // The contact law on contacts [begin, end); shear holds their u_t (laws with history).
  template <class Law>
  [[gnu::flatten]]  // the law inlined: only then is the loop vectorised
  void
  apply(const Law& law, Columns<D>& shear, std::size_t begin, std::size_t end) {
    static_assert(Law::kNeedsRotation == kRotation && rolls<Law> == kRolling);
    // Each contact touches only its own row of every column.
#pragma GCC ivdep
    for (std::size_t c = begin; c < end; ++c) {
      const ContactGeometryOf<LaneVec<D>> g{normal_.load(c), overlap_[c], lever_i_[c], lever_j_[c]};
      LaneVec<D> u_t = LaneVec<D>::Zero();
      if constexpr (Law::kNeedsHistory) u_t = shear.load(c);
      const LaneVec<D> f = law.force(g, v_rel_.load(c), u_t);
      force_.store(c, f);
      if constexpr (Law::kNeedsHistory) shear.store(c, u_t);
      if constexpr (kRotation) {
        // Only the tangential part has a lever arm: tau = (contact - centre) x F.
        const auto t = cross(g.n, f);
        if constexpr (kRolling) {
          // Stored as what is subtracted: i gains the rolling torque, j loses it.
          const auto m = law.rolling_torque(g, w_rel_.load_spin(c), f);
          torque_i_.set(c, g.lever_i * t - m);
          torque_j_.set(c, g.lever_j * t + m);
        } else {
          torque_i_.set(c, g.lever_i * t);
          torque_j_.set(c, g.lever_j * t);
        }
      }
    }
  }

  double overlap(std::size_t c) const { return overlap_[c]; }
  // The law's results: force on i, and the torques to subtract from i's and j's.
  ColumnsView<D> forces() const { return force_.view(); }
  ColumnsView<kSpinWidth> torques_i() const { return torque_i_.view(); }
  ColumnsView<kSpinWidth> torques_j() const { return torque_j_.view(); }

 private:
  Columns<D> normal_;
  std::vector<double> overlap_, lever_i_, lever_j_;
  Columns<D> v_rel_;
  Columns<D> force_;
  Columns<kSpinWidth> torque_i_, torque_j_;
  Columns<kSpinWidth> w_rel_;
};

}  // namespace granjet::dem
