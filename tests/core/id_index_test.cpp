// IdIndex: grain id -> where the grain lies, for the grains one process holds.
#include "core/id_index.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <vector>

namespace granjet {
namespace {

// Distinct ids: runs of consecutive ones (a rank's layers of a jet) and scattered large ones.
std::vector<GrainId> some_ids(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::set<GrainId> ids;
  while (ids.size() < n) {
    const GrainId start = static_cast<GrainId>(random() % 4'000'000'000'000ull);
    for (GrainId k = 0; k < 1 + static_cast<GrainId>(random() % 300) && ids.size() < n; ++k)
      ids.insert(start + k);
  }
  std::vector<GrainId> shuffled(ids.begin(), ids.end());
  std::shuffle(shuffled.begin(), shuffled.end(), random);
  return shuffled;
}

// Every held id finds its place and every other id none, on 1 and on 4 threads.
TEST(IdIndex, FindsEveryHeldIdAndNoOther) {
  for (const int threads : {1, 4}) {
    const std::vector<GrainId> ids = some_ids(50'000, 7);
    IdIndex index;
    index.assign(ids, threads);
    for (std::size_t i = 0; i < ids.size(); ++i)
      ASSERT_EQ(index[ids[i]], i) << "id " << ids[i] << ", " << threads << " threads";
    const std::set<GrainId> held(ids.begin(), ids.end());
    std::mt19937_64 random(11);
    for (int k = 0; k < 50'000; ++k) {
      const GrainId probe = static_cast<GrainId>(random() % 4'000'000'000'000ull);
      if (!held.count(probe)) {
        ASSERT_EQ(index[probe], IdIndex::kAbsent) << probe;
      }
      if (!held.count(probe + 1)) {
        ASSERT_EQ(index[probe + 1], IdIndex::kAbsent) << probe + 1;
      }
    }
  }
}

// A new assignment forgets the grains of the last (a grain that left, or was removed).
TEST(IdIndex, AssignForgetsTheGrainsHeldBefore) {
  const std::vector<GrainId> before{5, 6, 7, 1'000'000}, after{7, 8};
  IdIndex index;
  EXPECT_EQ(index[5], IdIndex::kAbsent);  // nothing held yet
  index.assign(before);
  EXPECT_EQ(index[1'000'000], 3u);
  index.assign(after);
  EXPECT_EQ(index[7], 0u);
  EXPECT_EQ(index[8], 1u);
  for (GrainId gone : {5, 6, 1'000'000}) EXPECT_EQ(index[gone], IdIndex::kAbsent) << gone;
}

// Its memory follows the grains held, not the largest id: what a rank holding 1e4 grains of a
// 1e8-grain run pays (a table indexed by id would take 400 MB).
TEST(IdIndex, MemoryFollowsTheGrainsHeldNotTheLargestId) {
  std::vector<GrainId> ids(10'000);
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = 99'990'000 + static_cast<GrainId>(i);
  IdIndex index;
  index.assign(ids);
  EXPECT_LE(index.bytes(), 4 * 12 * ids.size());
  EXPECT_EQ(index[99'999'999], 9'999u);
}

// An id held twice, or a negative one, is a caller's error, not a silent overwrite.
TEST(IdIndex, RepeatedOrNegativeIdsAreRefused) {
  IdIndex index;
  EXPECT_THROW(index.assign(std::vector<GrainId>{3, 4, 3}), std::logic_error);
  EXPECT_THROW(index.assign(std::vector<GrainId>{3, -1}), std::logic_error);
}

}  // namespace
}  // namespace granjet
