// The event calendar against a sort oracle [model §8]: random schedules, reschedules (earlier and
// later) and cancellations; every pop must be the earliest (time, grain) of a plain reference
// table, ties included. The seed is printed so a failure can be replayed.
#include "event_driven/event_calendar.hpp"

#include <gtest/gtest.h>

#include <map>

#include "core/random.hpp"
#include "event_driven/flight.hpp"

namespace granjet::ed {
namespace {

template <class Calendar>
class EventCalendarOrder : public ::testing::Test {};
using Calendars =
    ::testing::Types<EventCalendar<DaryHeap<4>, 1>, EventCalendar<DaryHeap<8>, 1>,
                     EventCalendar<PairingHeap, 1>, EventCalendar<DaryHeap<4>, 16>,
                     EventCalendar<DaryHeap<4>, 32>, EventCalendar<PairingHeap, 8>, Calendar>;
TYPED_TEST_SUITE(EventCalendarOrder, Calendars);

TYPED_TEST(EventCalendarOrder, PopsInTheOrderOfASortedReference) {
  constexpr std::uint32_t kGrains = 500;
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    Random rng(seed);
    TypeParam calendar(kGrains);
    std::map<std::uint32_t, double> reference;  // grain -> time of the scheduled ones
    // Coarse times (multiples of 1/8) make ties frequent, so the id tie-break is exercised.
    const auto random_time = [&](double now) { return now + rng.below(64) / 8.0; };
    double now = 0.0;
    for (int step = 0; step < 20000; ++step) {
      const auto grain = static_cast<std::uint32_t>(rng.below(kGrains));
      const std::uint64_t action = rng.below(10);
      if (action < 5) {  // (re)schedule a random grain, earlier or later than before
        const double t = random_time(now);
        calendar.schedule(grain, t);
        reference[grain] = t;
      } else if (action == 5) {
        calendar.cancel(grain);
        reference.erase(grain);
      } else if (!reference.empty()) {  // pop: the earliest, the smallest grain among ties
        auto expected = reference.begin();
        for (auto it = reference.begin(); it != reference.end(); ++it)
          if (it->second < expected->second) expected = it;
        ASSERT_FALSE(calendar.empty());
        const CalendarEntry top = calendar.top();
        ASSERT_EQ(top.grain, expected->first) << "step " << step;
        ASSERT_EQ(top.time, expected->second) << "step " << step;
        now = top.time;
        // As after an event: the grain either gets a later event or none.
        if (action < 9) {
          const double t = random_time(now);
          calendar.schedule(top.grain, t);
          reference[top.grain] = t;
        } else {
          calendar.cancel(top.grain);
          reference.erase(top.grain);
        }
      }
    }
    EXPECT_EQ(calendar.empty(), reference.empty());
  }
}

TYPED_TEST(EventCalendarOrder, ShiftingTheOriginKeepsOrderAndMovesTimes) {
  TypeParam calendar(4);
  calendar.schedule(2, 10.5);
  calendar.schedule(0, 12.0);
  calendar.schedule(3, 10.5);
  calendar.schedule(1, kNever);
  calendar.shift(10.0);
  EXPECT_EQ(calendar.top().grain, 2u);
  EXPECT_EQ(calendar.top().time, 0.5);
  calendar.cancel(2);
  EXPECT_EQ(calendar.top().grain, 3u);
  calendar.schedule(3, 3.0);
  EXPECT_EQ(calendar.top().grain, 0u);
  EXPECT_EQ(calendar.top().time, 2.0);
}

}  // namespace
}  // namespace granjet::ed
