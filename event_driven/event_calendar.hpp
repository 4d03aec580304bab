// The event calendar [model §8]: per grain the time of its earliest event, popped in the order of
// (time, grain) so that simultaneous events always pop in the same order. What the event is
// lives with the simulator; an entry only says when and whose. Events whose partner has changed
// since the prediction are discarded lazily by the simulator (per-grain event counters), so the
// calendar never searches for them.
//
// The grains are taken in groups of kGroup consecutive indices: a plain array holds every
// grain's time, and a mutable Boost.Heap holds one entry per group, its earliest (time, grain).
// The heap is kGroup times smaller (a few levels, in L1 cache, where one entry per grain means
// a cache miss at every level of every sift), and a reschedule that changes no group's earliest
// costs no heap operation at all; a group's earliest is found again by scanning its kGroup
// times. kGroup = 1 is the classic one-entry-per-grain calendar.
#pragma once

#include <array>
#include <bit>
#include <boost/heap/d_ary_heap.hpp>
#include <boost/heap/pairing_heap.hpp>
#include <cstdint>
#include <limits>
#include <vector>

namespace granjet::ed {

struct CalendarEntry {
  double time;
  std::uint32_t grain;
};

// Boost heaps put the greatest element on top: "greater" here is earlier, then smaller id.
struct Later {
  bool operator()(const CalendarEntry& a, const CalendarEntry& b) const {
    return a.time > b.time || (a.time == b.time && a.grain > b.grain);
  }
};

template <class Heap, std::uint32_t kGroup>
class EventCalendar {
  static_assert(kGroup >= 1 && kGroup <= 32, "a group's grains are one 32-bit mask");

 public:
  explicit EventCalendar(std::size_t grains)
      : time_((grains + kGroup - 1) / kGroup * kGroup, kUnscheduled),
        handles_(time_.size() / kGroup),
        in_heap_(time_.size() / kGroup, 0) {}

  bool empty() const { return heap_.empty(); }
  const CalendarEntry& top() const { return heap_.top(); }

  // Sets the grain's entry to `time`, earlier or later than before.
  void schedule(std::uint32_t grain, double time) {
    time_[grain] = time;
    const std::uint32_t group = grain / kGroup;
    if (!in_heap_[group]) {
      handles_[group] = heap_.push(CalendarEntry{time, grain});
      in_heap_[group] = 1;
      return;
    }
    const CalendarEntry earliest = *handles_[group];
    if (Later{}(earliest, CalendarEntry{time, grain})) {
      // The group's new earliest: it only sifts up ("greater" is earlier).
      heap_.increase(handles_[group], CalendarEntry{time, grain});
    } else if (grain == earliest.grain) {
      refresh(group);  // was the earliest, now later: the group's earliest may be another
    }
  }

  void cancel(std::uint32_t grain) {
    time_[grain] = kUnscheduled;
    const std::uint32_t group = grain / kGroup;
    if (in_heap_[group] && (*handles_[group]).grain == grain) refresh(group);
  }

  // Moves the time origin forward by `dt`: every entry becomes dt earlier. The order is
  // unchanged, but Boost.Heap has no in-place key shift, so the heap is refilled.
  void shift(double dt) {
    for (double& t : time_) t -= dt;  // kUnscheduled stays infinite
    std::vector<CalendarEntry> entries;
    entries.reserve(heap_.size());
    for (const CalendarEntry& e : heap_) entries.push_back({e.time - dt, e.grain});
    heap_.clear();
    for (const CalendarEntry& e : entries) handles_[e.grain / kGroup] = heap_.push(e);
  }

 private:
  static constexpr double kUnscheduled = std::numeric_limits<double>::infinity();
  static constexpr std::uint32_t kLanes = kGroup % 4 == 0 ? 4 : 1;

  // Finds the group's earliest after its entry in the heap became later or went away: the
  // minimum in independent lanes (vector code, no branch on the data), then the first grain at
  // that time, the smallest index among ties.
  void refresh(std::uint32_t group) {
    const double* t = time_.data() + group * kGroup;
    std::array<double, kLanes> lane;
    lane.fill(kUnscheduled);
    for (std::uint32_t k = 0; k < kGroup; k += kLanes)
      for (std::uint32_t l = 0; l < kLanes; ++l) lane[l] = t[k + l] < lane[l] ? t[k + l] : lane[l];
    double earliest = kUnscheduled;
    for (double x : lane) earliest = x < earliest ? x : earliest;
    if (earliest == kUnscheduled) {
      heap_.erase(handles_[group]);
      in_heap_[group] = 0;
      return;
    }
    std::uint32_t at_earliest = 0;
    for (std::uint32_t k = 0; k < kGroup; ++k)
      at_earliest |= static_cast<std::uint32_t>(t[k] == earliest) << k;
    const auto first = static_cast<std::uint32_t>(std::countr_zero(at_earliest));
    heap_.decrease(handles_[group], CalendarEntry{earliest, group * kGroup + first});
  }

  std::vector<double> time_;  // per grain; kUnscheduled when it has no entry
  Heap heap_;
  std::vector<typename Heap::handle_type> handles_;  // per group
  std::vector<std::uint8_t> in_heap_;                // per group
};

template <unsigned kArity>
using DaryHeap = boost::heap::d_ary_heap<CalendarEntry, boost::heap::arity<kArity>,
                                         boost::heap::mutable_<true>, boost::heap::compare<Later>>;
using PairingHeap = boost::heap::pairing_heap<CalendarEntry, boost::heap::compare<Later>>;

// The calendar of the simulator: groups of 16 grains in a 4-ary heap, the fastest of the
// arities, group sizes and Boost heaps measured (bench/ed_calendar_bench.cpp and the gas
// benchmark; the numbers are in docs/performance.md).
using Calendar = EventCalendar<DaryHeap<4>, 16>;

}  // namespace granjet::ed
