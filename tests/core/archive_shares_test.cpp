// A rank's share of a checkpoint split over ranks (core/archive_shares.hpp, StateArchive's
// split_over): what it holds, its bytes back bit for bit, and a join in rank order (the
// travel to rank 0 is tested over ranks, tests/ranks).
#include "core/archive_shares.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

namespace granjet {
namespace {

StateArchive piece(double x) {
  StateArchive a;
  a.put("app/time", 2.0);
  a.put_reals("dem/grains/position", {x, -0.0, std::numeric_limits<double>::quiet_NaN()});
  a.put_integers("dem/grains/id", {7, std::numeric_limits<std::int64_t>::min()});
  a.put_reals("dem/history/shear", {});
  a.split_over(3, {"dem/grains/", "dem/history/"});
  return a;
}

std::vector<std::uint64_t> bits(const std::vector<double>& values) {
  std::vector<std::uint64_t> out;
  for (double v : values) out.push_back(std::bit_cast<std::uint64_t>(v));
  return out;
}

// A share as it arrives on rank 0.
StateArchive share_of(const StateArchive& a) { return archive_from_bytes(share_bytes(a)); }

TEST(ArchiveShares, AShareHoldsItsPrefixesEntriesAloneBitForBit) {
  const StateArchive a = piece(1.0 / 3.0);
  EXPECT_EQ(a.ranks(), 3);
  EXPECT_EQ(StateArchive().ranks(), 1);
  EXPECT_TRUE(a.in_share("dem/grains/id"));
  EXPECT_FALSE(a.in_share("app/time"));
  EXPECT_FALSE(a.in_share("dem/grainsize"));  // a prefix ends in '/' where it names a group
  const StateArchive back = share_of(a);
  EXPECT_FALSE(back.contains("app/time"));
  EXPECT_TRUE(back.reals("dem/history/shear").empty());
  EXPECT_EQ(back.integers("dem/grains/id"), a.integers("dem/grains/id"));
  EXPECT_EQ(bits(back.reals("dem/grains/position")), bits(a.reals("dem/grains/position")));
  EXPECT_EQ(back.all_reals().size() + back.all_integers().size(), 3u);
  std::vector<std::byte> cut = share_bytes(a);
  cut.pop_back();
  EXPECT_THROW(archive_from_bytes(cut), std::runtime_error);
  EXPECT_TRUE(archive_from_bytes({}).all_reals().empty());
}

TEST(ArchiveShares, JoinedSharesFollowOneAnotherInTheOrderJoined) {
  StateArchive joined = piece(1.0);
  joined.append_share(share_of(piece(2.0)));
  EXPECT_EQ(joined.integers("dem/grains/id").size(), 4u);
  EXPECT_EQ(joined.reals("dem/grains/position")[3], 2.0);
  EXPECT_EQ(joined.real("app/time"), 2.0);  // not a share's: untouched
  StateArchive none;                        // a reader that took no share still finds the entry
  none.append_share(share_of(piece(3.0)));
  EXPECT_EQ(none.reals("dem/grains/position")[0], 3.0);
}

}  // namespace
}  // namespace granjet
