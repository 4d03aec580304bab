// The earliest two contacts of one grain with a list of partners, as vector code: kEarliestLanes
// partners at a time, each step loading their flights, taking the pair quadratics and contact
// times (flight.hpp) and keeping the earliest two (two_earliest.hpp) in one pass, without a
// branch on the data. The compiler does not vectorise the per-partner loop by itself: its loads
// are indexed. A flight is one cache line of two halves, (x, t) and (v, radius): the lanes of
// four partners are two 4 x 4 transposes of those halves. Each lane computes what pair_quadratic
// and contact_delay compute, operation for operation: without fused multiply-adds (the tests)
// the times are the scalar ones, bit for bit. The backend lets the compiler fuse
// (event_driven/CMakeLists.txt), where it chooses per code path, so its times may differ from
// the scalar ones in the last bits.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "event_driven/flight.hpp"
#include "event_driven/two_earliest.hpp"

namespace granjet::ed {

template <int D>
using LaneVec = std::array<detail::Lanes, D>;
// The positions in the list of the partners in the lanes.
using LaneAt = std::array<std::size_t, kEarliestLanes>;

namespace detail {

using Indices = std::int32_t __attribute__((vector_size(kEarliestLanes * sizeof(std::int32_t))));

inline Lanes broadcast(double x) { return Lanes{} + x; }

// The compiler turns the lane loops into one vector instruction each.
inline Lanes lane_sqrt(Lanes x) {
  for (std::size_t l = 0; l < kEarliestLanes; ++l) x[l] = __builtin_sqrt(x[l]);
  return x;
}
// std::max(x, y) per lane, NaN and signed zeros included.
inline Lanes lane_max(Lanes x, Lanes y) { return x < y ? y : x; }

// The rows of four cache lines' first or second half, as columns.
inline std::array<Lanes, 4> transpose(Lanes r0, Lanes r1, Lanes r2, Lanes r3) {
  const Lanes t0 = __builtin_shufflevector(r0, r1, 0, 4, 2, 6);
  const Lanes t1 = __builtin_shufflevector(r0, r1, 1, 5, 3, 7);
  const Lanes t2 = __builtin_shufflevector(r2, r3, 0, 4, 2, 6);
  const Lanes t3 = __builtin_shufflevector(r2, r3, 1, 5, 3, 7);
  return {__builtin_shufflevector(t0, t2, 0, 1, 4, 5), __builtin_shufflevector(t1, t3, 0, 1, 4, 5),
          __builtin_shufflevector(t0, t2, 2, 3, 6, 7), __builtin_shufflevector(t1, t3, 2, 3, 6, 7)};
}

inline Lanes half_row(const void* line, std::size_t half) {
  Lanes row;
  std::memcpy(&row, static_cast<const char*>(line) + half * sizeof row, sizeof row);
  return row;
}

// Eigen's order of a dot product of fixed size 2 or 3: (e0 + e1) + e2.
template <int D>
Lanes dot(const LaneVec<D>& p, const LaneVec<D>& q) {
  Lanes sum = p[0] * q[0] + p[1] * q[1];
  if constexpr (D == 3) sum = sum + p[2] * q[2];
  return sum;
}

}  // namespace detail

// A partner's separation from the grain as periodic lists take it: the nearest image.
// (x + 1.5 * 2^52) - 1.5 * 2^52 rounds x to the nearest integer, ties to even, as nearbyint
// does for |x| < 2^51; separations are a few box lengths at most.
template <int D>
struct NearestImage {
  LaneVec<D> operator()(const LaneAt&, const LaneVec<D>& x_k) const {
    constexpr double kRound = 0x1.8p52;
    LaneVec<D> dr;
    for (int a = 0; a < D; ++a) {
      const detail::Lanes r = x_k[a] - x_i[a];
      dr[a] = r - box[a] * ((r * inv_box[a] + kRound) - kRound);
    }
    return dr;
  }
  Vec<D> x_i, box, inv_box;
};

// As the cells take it when no image is shifted (x_k + 0 would be x_k): the partner where it is.
template <int D>
struct SameImage {
  LaneVec<D> operator()(const LaneAt&, const LaneVec<D>& x_k) const {
    LaneVec<D> dr;
    for (int a = 0; a < D; ++a) dr[a] = x_k[a] - x_i[a];
    return dr;
  }
  Vec<D> x_i;
};

// As the cells take it: partner m's image is shifted by shift[image[m]] (CellList's
// Neighbourhood).
template <int D>
struct ShiftedImage {
  LaneVec<D> operator()(const LaneAt& m, const LaneVec<D>& x_k) const {
    LaneVec<D> dr;
    for (int a = 0; a < D; ++a) {
      detail::Lanes s;
      for (std::size_t l = 0; l < kEarliestLanes; ++l) s[l] = shift[image[m[l]]][a];
      dr[a] = (x_k[a] + s) - x_i[a];
    }
    return dr;
  }
  Vec<D> x_i;
  const Vec<D>* shift;
  const std::uint8_t* image;
};

// The grain whose partners are scanned, at the time `now`.
template <int D>
struct Scanner {
  double now;
  Vec<D> v;
  double radius;
  // A partner that collided last with the grain and still touches within echo_tolerance of
  // sigma^2 is taken as receding (b = 0); -1 when there is none.
  std::int32_t echo_partner;
  double echo_tolerance;
};

// The earliest two contact times (now + contact_delay) of the grain with flight[grain[m]],
// m < n, at their first m among equal times. `separation` gives the partners' separations from
// their positions at `now`.
template <int D, class Separation>
Earliest earliest_contacts(const Scanner<D>& self, const Flight<D>* flight,
                           const std::uint32_t* grain, std::size_t n,
                           const Separation& separation) {
  using detail::Lanes;
  static_assert(sizeof(Flight<D>) == 8 * sizeof(double) && std::is_standard_layout_v<Flight<D>>);
  static_assert(offsetof(Flight<D>, t) == D * sizeof(double) &&
                    offsetof(Flight<D>, v) == 4 * sizeof(double) &&
                    offsetof(Flight<D>, radius) == (4 + D) * sizeof(double),
                "halves (x, t) and (v, radius)");
  const Lanes now = detail::broadcast(self.now), never = detail::broadcast(kNever);
  const Lanes echo_partner = detail::broadcast(self.echo_partner);
  LaneVec<D> v_i;
  for (int a = 0; a < D; ++a) v_i[a] = detail::broadcast(self.v[a]);
  TwoEarliest earliest;
  for (std::size_t base = 0; base < n; base += kEarliestLanes) {
    // The last step's lanes beyond n repeat its first partner and end at kNever.
    LaneAt m;
    detail::Indices k;
    for (std::size_t l = 0; l < kEarliestLanes; ++l) {
      m[l] = base + l < n ? base + l : base;
      k[l] = static_cast<std::int32_t>(grain[m[l]]);
    }
    const Flight<D>* f[kEarliestLanes] = {flight + k[0], flight + k[1], flight + k[2],
                                          flight + k[3]};
    const auto lo = detail::transpose(detail::half_row(f[0], 0), detail::half_row(f[1], 0),
                                      detail::half_row(f[2], 0), detail::half_row(f[3], 0));
    const auto hi = detail::transpose(detail::half_row(f[0], 1), detail::half_row(f[1], 1),
                                      detail::half_row(f[2], 1), detail::half_row(f[3], 1));
    const Lanes dt = now - lo[D];
    LaneVec<D> x_k, dv;
    for (int a = 0; a < D; ++a) {
      x_k[a] = lo[a] + hi[a] * dt;
      dv[a] = hi[a] - v_i[a];
    }
    const LaneVec<D> dr = separation(m, x_k);
    const Lanes sigma = self.radius + hi[D];
    Lanes b = detail::dot<D>(dr, dv);
    const Lanes c = detail::dot<D>(dr, dr) - sigma * sigma;
    const Lanes a = detail::dot<D>(dv, dv);
    const auto echo = (__builtin_convertvector(k, Lanes) == echo_partner) &
                      (c < self.echo_tolerance * sigma * sigma);
    b = echo ? Lanes{} : b;
    // contact_delay, lane by lane.
    const Lanes disc = b * b - a * c;
    const Lanes root =
        detail::lane_max(c / (-b + detail::lane_sqrt(detail::lane_max(disc, Lanes{}))), Lanes{});
    const Lanes time = now + ((b < 0.0) & (disc > 0.0) ? root : never);
    const Lanes at = detail::broadcast(static_cast<double>(base)) + Lanes{0.0, 1.0, 2.0, 3.0};
    earliest.add(at < static_cast<double>(n) ? time : never);
  }
  return earliest.result();
}

}  // namespace granjet::ed
