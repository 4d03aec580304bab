// Per-grain neighbour lists with a shell, for dense periodic gases (the scheme of Smallenburg's
// EDMD, Eur. Phys. J. E 45, 22 (2022), written anew here). Each grain has a centre, where it
// stood at its last renewal, and lists the grains whose centres lie within kShell (r_i + r_k)
// of its own. It renews its list once it has moved (kShell - 1) r_i from its centre (an event
// of its own, in place of the cell path's crossings). Until then a grain it does not list is at
// least r_i + r_k away: the centres are kShell (r_i + r_k) apart and each grain is within
// (kShell - 1) of its radius of its centre. So a prediction scans the listed grains only (some
// 18 at phi = 0.45, against 24 in the 27 cells of the cell path).
//
// Lists are symmetric: a renewal takes the grain out of its old neighbours' lists and puts it
// into its new ones'. The centres are binned in cells at least kShell d wide (CentreGrid), which
// only renewals touch. The box must be three such cells wide (fits()); the nearest image of a
// listed pair is then the one within reach (kShell < 2: listed grains are at most
// (2 kShell - 1) d < 1.5 kShell d apart).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "event_driven/centre_grid.hpp"
#include "event_driven/flight.hpp"

namespace granjet::ed {

template <int D>
class NeighbourShells {
 public:
  // The fastest shell on the dense gas (BM_EdGas3d/45, bench/ed_gas_bench.cpp): a wider one
  // renews less often but scans more grains at every prediction, a narrower one the reverse.
  // (At phi = 0.3 the wider shells are faster, but the cells faster still.)
  static constexpr double kShell = 1.7;
  static_assert(kShell > 1.0 && kShell < 2.0, "see the minimum-image note above");

  // Whether a periodic box takes cells of kShell * diameter, three per axis.
  static bool fits(const Vec<D>& box, double diameter) {
    return (box.array() >= 3.0 * kShell * diameter).all();
  }

  // The grains' radii, in a periodic box that fits() their largest diameter.
  NeighbourShells(std::vector<double> radius, const Vec<D>& box)
      : radius_(std::move(radius)),
        grid_(box, kShell * 2.0 * *std::max_element(radius_.begin(), radius_.end()),
              radius_.size()),
        count_(radius_.size(), 0),
        mark_(radius_.size(), 0),
        list_(radius_.size() * stride_) {}

  std::span<const std::uint32_t> of(std::uint32_t grain) const {
    return {list_.data() + grain * stride_, count_[grain]};
  }

  // Lists every grain anew around its position x[i] (all in the box), the grains whose `live`
  // is 0 left out.
  void build(std::span<const Vec<D>> x, std::span<const std::uint8_t> live) {
    std::fill(count_.begin(), count_.end(), 0);
    grid_.clear();
    for (std::uint32_t i = 0; i < x.size(); ++i)
      if (live[i]) grid_.insert(i, x[i], radius_[i]);
    for (std::uint32_t i = 0; i < x.size(); ++i) {
      if (!live[i]) continue;
      const std::size_t n = grid_.gather_within(x[i], radius_[i], kShell, near_);
      for (std::size_t m = 0; m < n; ++m)
        if (near_[m] > i) link(i, near_[m]);
    }
  }

  // Makes x (in the box) the grain's centre and lists its neighbours anew. Most of them stay
  // (the grain moved a fraction of the shell): only those that come or go have their own lists
  // changed, so the others' lists are not even read. The old neighbours are marked to tell them.
  void renew(std::uint32_t i, const Vec<D>& x) {
    const std::span<const std::uint32_t> old = of(i);
    was_.assign(old.begin(), old.end());
    ++stamp_;
    for (std::uint32_t k : was_) mark_[k] = stamp_;
    count_[i] = 0;
    grid_.remove(i);
    const std::size_t n = grid_.gather_within(x, radius_[i], kShell, near_);
    grid_.insert(i, x, radius_[i]);
    for (std::size_t m = 0; m < n; ++m) {
      const std::uint32_t k = near_[m];
      append(i, k);
      if (mark_[k] == stamp_)
        mark_[k] = 0;  // stays: k lists i already
      else
        append(k, i);
    }
    for (std::uint32_t k : was_)
      if (mark_[k] == stamp_) unlist(k, i);  // left the shell
  }

  // When the grain at x (at its own time) with velocity v is (kShell - 1) r_i from its centre:
  // the larger root of |x - centre + v t|^2 = reach^2, cancellation-free for either sign of b.
  double exit_delay(std::uint32_t i, const Vec<D>& x, const Vec<D>& v) const {
    const Vec<D> d = x - grid_.centre(i);
    const double reach = (kShell - 1.0) * radius_[i];
    const double a = v.squaredNorm(), b = d.dot(v), c = d.squaredNorm() - reach * reach;
    if (a == 0.0) return kNever;
    const double s = std::sqrt(std::max(b * b - a * c, 0.0));
    return std::max(b > 0.0 ? -c / (b + s) : (s - b) / a, 0.0);
  }

 private:
  void link(std::uint32_t i, std::uint32_t k) {
    append(i, k);
    append(k, i);
  }

  void append(std::uint32_t i, std::uint32_t k) {
    if (count_[i] == stride_) widen();
    list_[i * stride_ + count_[i]++] = k;
  }

  // Takes k out of i's list (order is not kept).
  void unlist(std::uint32_t i, std::uint32_t k) {
    std::uint32_t* l = list_.data() + i * stride_;
    const std::uint32_t n = count_[i];
    const std::uint32_t at = static_cast<std::uint32_t>(std::find(l, l + n, k) - l);
    l[at] = l[n - 1];
    --count_[i];
  }

  // A list is full: every list gets twice the room (rare: a grain has some 18 neighbours at
  // phi = 0.45, and room starts at 32).
  void widen() {
    std::vector<std::uint32_t> wider(list_.size() * 2);
    for (std::size_t i = 0; i < count_.size(); ++i)
      std::copy_n(list_.data() + i * stride_, count_[i], wider.data() + i * 2 * stride_);
    list_ = std::move(wider);
    stride_ *= 2;
  }

  std::vector<double> radius_;
  CentreGrid<D> grid_;               // each grain's centre: where it stood at its last renewal
  std::vector<std::uint32_t> near_;  // scratch: the grains within a renewal's shell
  std::vector<std::uint32_t> count_;
  std::vector<std::uint64_t> mark_;  // == stamp_: listed before the renewal under way
  std::uint64_t stamp_ = 0;
  std::vector<std::uint32_t> was_;  // the list before the renewal under way
  std::size_t stride_ = 32;
  std::vector<std::uint32_t> list_;  // grain i's neighbours at [i * stride_, + count_[i])
};

}  // namespace granjet::ed
