// The event calendar under an event-driven workload (Google Benchmark): N = 10,976 grains; each
// "collision" reschedules the grain on top and a random partner to exponentially distributed
// later times, as a collision does. Chooses the heap and the group size of ed::Calendar
// (event_driven/event_calendar.hpp).
#include <benchmark/benchmark.h>

#include <boost/heap/fibonacci_heap.hpp>
#include <cmath>

#include "core/random.hpp"
#include "event_driven/event_calendar.hpp"

namespace {

using granjet::ed::CalendarEntry;
using FibonacciHeap =
    boost::heap::fibonacci_heap<CalendarEntry, boost::heap::compare<granjet::ed::Later>>;

template <class Calendar>
void BM_Calendar(benchmark::State& state) {
  constexpr std::uint32_t kGrains = 10976;
  granjet::Random rng(7);
  const auto later = [&](double now) { return now - std::log(1.0 - rng.uniform()); };
  Calendar calendar(kGrains);
  for (std::uint32_t g = 0; g < kGrains; ++g) calendar.schedule(g, later(0.0));
  for (auto _ : state) {
    const CalendarEntry top = calendar.top();
    calendar.schedule(top.grain, later(top.time));
    calendar.schedule(static_cast<std::uint32_t>(rng.below(kGrains)), later(top.time));
  }
  state.SetItemsProcessed(state.iterations());
}

}  // namespace

using granjet::ed::DaryHeap;
using granjet::ed::EventCalendar;
// One entry per grain, by heap.
BENCHMARK(BM_Calendar<EventCalendar<DaryHeap<2>, 1>>);
BENCHMARK(BM_Calendar<EventCalendar<DaryHeap<4>, 1>>);
BENCHMARK(BM_Calendar<EventCalendar<DaryHeap<8>, 1>>);
BENCHMARK(BM_Calendar<EventCalendar<granjet::ed::PairingHeap, 1>>);
BENCHMARK(BM_Calendar<EventCalendar<FibonacciHeap, 1>>);
// One entry per group of grains, by group size and arity.
BENCHMARK(BM_Calendar<EventCalendar<DaryHeap<4>, 8>>);
BENCHMARK(BM_Calendar<EventCalendar<DaryHeap<4>, 16>>);
BENCHMARK(BM_Calendar<EventCalendar<DaryHeap<4>, 32>>);
BENCHMARK(BM_Calendar<EventCalendar<DaryHeap<2>, 16>>);
BENCHMARK(BM_Calendar<EventCalendar<DaryHeap<8>, 16>>);
