// The rank team's exchanges and gathers between the MPI ranks this test was started on (mpirun
// -n K, K = 2..4; main is in decomposition_test.cpp). A message arrives whole at any length:
// either side of the piece that short messages are cut into, and of the longest message cut,
// whether the receiver knows its length or takes what comes. One of another length than the
// receiver expects is an error at once, not a wait for pieces that never come.
#include "core/rank_team.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace granjet {
namespace {

// Rank `from`'s message of `bytes` to rank `to`: each byte tells the pair and its place.
std::vector<std::uint8_t> message(int from, int to, std::size_t bytes) {
  std::vector<std::uint8_t> m(bytes);
  for (std::size_t k = 0; k < bytes; ++k)
    m[k] = static_cast<std::uint8_t>(31 * from + 7 * to + k % 251);
  return m;
}

std::vector<int> all_but_me(const RankTeam& team) {
  std::vector<int> others;
  for (int r = 0; r < team.size(); ++r)
    if (r != team.rank()) others.push_back(r);
  return others;
}

TEST(RankTeam, ExchangedMessagesArriveWholeAtAnyLength) {
  const RankTeam world = RankTeam::world();
  const int me = world.rank();
  const std::vector<int> others = all_but_me(world);
  // Around the piece (4000 bytes) and the longest message sent in pieces (16 KiB).
  for (std::size_t bytes : {0, 1, 3999, 4000, 4001, 8000, 15013, 16383, 16384, 16385, 200003}) {
    std::vector<std::vector<std::uint8_t>> to(world.size()), known(world.size());
    for (int r : others) {
      to[r] = message(me, r, bytes);
      known[r].assign(bytes, 0);
    }
    world.exchange_into(to, known, others, true);
    const std::vector<std::vector<std::uint8_t>> told = world.exchange_with(to, others);
    for (int r : others) {
      EXPECT_EQ(known[r], message(r, me, bytes)) << bytes << " bytes from rank " << r;
      EXPECT_EQ(told[r], message(r, me, bytes)) << bytes << " bytes from rank " << r << ", sized";
    }
  }
}

// Lengths unknown to the receiver differ from partner to partner and from call to call, as the
// ghost states of a step do; each kept list takes this call's length, longer or shorter than
// the last, across the piece and the longest message cut.
TEST(RankTeam, UnknownLengthsDifferByPartnerAndCall) {
  const RankTeam world = RankTeam::world();
  const int me = world.rank();
  const std::vector<int> others = all_but_me(world);
  std::vector<std::vector<std::uint8_t>> to(world.size()), from(world.size());
  const auto length = [](int call, int sender, int receiver) -> std::size_t {
    return (std::size_t{37'123} * (call + 1) + 4'001 * sender + 977 * receiver) % 21'000;
  };
  for (int call = 0; call < 6; ++call) {
    for (int r : others) to[r] = message(me, r, length(call, me, r));
    world.exchange_into(to, from, others, false);
    for (int r : others)
      EXPECT_EQ(from[r], message(r, me, length(call, r, me)))
          << "call " << call << ": " << length(call, r, me) << " bytes from rank " << r;
  }
}

TEST(RankTeam, AShorterMessageThanExpectedIsAnErrorNotAWait) {
  const RankTeam world = RankTeam::world();
  const int me = world.rank();
  if (me > 1) return;  // between ranks 0 and 1 only
  const int other = 1 - me;
  const std::vector<int> partner{other};
  std::vector<std::vector<std::uint8_t>> to(world.size()), from(world.size());
  to[other] = message(me, other, 5000);
  from[other].assign(me == 1 ? 9000 : 5000, 0);  // rank 1 expects more than rank 0 sends
  if (me == 1)
    EXPECT_THROW(world.exchange_into(to, from, partner, true), std::logic_error);
  else
    world.exchange_into(to, from, partner, true);
  // Nothing of the failed exchange is left posted to take the next one's message.
  to[other] = message(me, other, 100);
  const std::vector<std::vector<std::uint8_t>> next = world.exchange_with(to, partner);
  EXPECT_EQ(next[other], message(other, me, 100));
}

// A gather into a list kept from call to call (its memory reused) leaves in it only this
// call's values, in rank order, whether the list held more before or fewer.
TEST(RankTeam, GatherIntoAKeptListHoldsOnlyThisCallsValues) {
  const RankTeam world = RankTeam::world();
  std::vector<std::int64_t> on_rank0(1000, -1), everywhere(1000, -1);
  for (int round : {1, 2, 3}) {
    // Rank r sends round * (r + 1) values r * 100 + k.
    std::vector<std::int64_t> mine, expected;
    for (int r = 0; r < world.size(); ++r)
      for (int k = 0; k < round * (r + 1); ++k) {
        if (r == world.rank()) mine.push_back(100 * r + k);
        expected.push_back(100 * r + k);
      }
    if (round == 3) {  // fewer than the last round
      mine.resize(1);
      expected.clear();
      for (int r = 0; r < world.size(); ++r) expected.push_back(100 * r);
    }
    world.gather_into<std::int64_t>(mine, on_rank0);
    world.all_gather_into<std::int64_t>(mine, everywhere);
    EXPECT_EQ(everywhere, expected) << "round " << round;
    if (world.rank() == 0)
      EXPECT_EQ(on_rank0, expected) << "round " << round;
    else
      EXPECT_TRUE(on_rank0.empty()) << "round " << round << ": rank " << world.rank();
  }
}

}  // namespace
}  // namespace granjet
