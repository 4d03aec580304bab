// The earliest two of a grain's predicted collision times, found without a branch on the data:
// a scan that asks of each time "earlier than the best so far?" mispredicts whenever the answer
// is yes, a few times per scan at random (merge in ed_simulator.cpp).
#pragma once

#include <cstddef>

#include "event_driven/flight.hpp"

namespace granjet::ed {

// Times are taken this many at a time (one AVX2 register of doubles); callers pad with kNever.
inline constexpr std::size_t kEarliestLanes = 4;

struct Earliest {
  double first = kNever;
  std::size_t first_at = 0;
  double second = kNever;
  std::size_t second_at = 0;
};

namespace detail {

// GCC's vector extension: left to itself the compiler turns the selects below into branches.
// Indices are carried as doubles, as wide as the times, so that both fill one register.
using Lanes = double __attribute__((vector_size(kEarliestLanes * sizeof(double))));

// Per lane the earliest two (t1, m1) <= (t2, m2) in the order of (time, index).
struct EarliestLanes {
  Lanes t1, m1, t2, m2;
};

using Mask = decltype(Lanes{} < Lanes{});

inline Mask earlier(Lanes a, Lanes at_a, Lanes b, Lanes at_b) {
  return (a < b) | ((a == b) & (at_a < at_b));
}

// Ranks each lane's two with those of the lanes `other` names.
inline EarliestLanes rank_with(const EarliestLanes& e, const EarliestLanes& o) {
  const Mask first_mine = earlier(e.t1, e.m1, o.t1, o.m1);
  const Lanes lo_t = first_mine ? e.t1 : o.t1, lo_m = first_mine ? e.m1 : o.m1;
  const Lanes hi_t = first_mine ? o.t1 : e.t1, hi_m = first_mine ? o.m1 : e.m1;
  const Mask second_mine = earlier(e.t2, e.m2, o.t2, o.m2);
  const Lanes s_t = second_mine ? e.t2 : o.t2, s_m = second_mine ? e.m2 : o.m2;
  const Mask hi_first = earlier(hi_t, hi_m, s_t, s_m);
  return {lo_t, lo_m, hi_first ? hi_t : s_t, hi_first ? hi_m : s_m};
}

inline EarliestLanes swapped(const EarliestLanes& e, int half) {
  const auto swap = [half](Lanes v) {
    return half == 2 ? __builtin_shufflevector(v, v, 2, 3, 0, 1)
                     : __builtin_shufflevector(v, v, 1, 0, 3, 2);
  };
  return {swap(e.t1), swap(e.m1), swap(e.t2), swap(e.m2)};
}

}  // namespace detail

// The earliest time fed and the earliest of the others, each at the smallest index among equal
// times: what a scan in the order of the index with strict comparisons keeps. Times come
// kEarliestLanes at a time, at indices 0, 1, 2, ... in turn. Each lane keeps the earliest two of
// its times (its indices rise, so a strict comparison keeps the smaller index), then the lanes
// are ranked together, halves against halves.
class TwoEarliest {
 public:
  void add(detail::Lanes time) {
    const detail::Mask before_first = time < e_.t1, before_second = time < e_.t2;
    e_.t2 = before_first ? e_.t1 : before_second ? time : e_.t2;
    e_.m2 = before_first ? e_.m1 : before_second ? at_ : e_.m2;
    e_.t1 = before_first ? time : e_.t1;
    e_.m1 = before_first ? at_ : e_.m1;
    at_ += static_cast<double>(kEarliestLanes);
  }

  Earliest result() const {
    static_assert(kEarliestLanes == 4, "the lanes are ranked together in two rounds of four");
    detail::EarliestLanes e = detail::rank_with(e_, detail::swapped(e_, 2));
    e = detail::rank_with(e, detail::swapped(e, 1));
    return {e.t1[0], static_cast<std::size_t>(e.m1[0]), e.t2[0],
            static_cast<std::size_t>(e.m2[0])};
  }

 private:
  static constexpr detail::Lanes kNeverLanes = {kNever, kNever, kNever, kNever};
  detail::EarliestLanes e_{kNeverLanes, detail::Lanes{}, kNeverLanes, detail::Lanes{}};
  detail::Lanes at_ = {0.0, 1.0, 2.0, 3.0};
};

// The earliest two of t[0, n), n a multiple of kEarliestLanes.
inline Earliest two_earliest(const double* t, std::size_t n) {
  TwoEarliest earliest;
  for (std::size_t base = 0; base < n; base += kEarliestLanes) {
    detail::Lanes time;
    __builtin_memcpy(&time, t + base, sizeof time);
    earliest.add(time);
  }
  return earliest.result();
}

}  // namespace granjet::ed
