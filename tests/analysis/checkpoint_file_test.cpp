// A run's checkpoint file (analysis/checkpoint_file.hpp): every entry back bit for bit, its name
// beside the run's file, and a failed or torn write that leaves the last complete one.
#include "analysis/checkpoint_file.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/archive_shares.hpp"
#include "core/errors.hpp"

namespace granjet::analysis {
namespace {

namespace fs = std::filesystem;

class CheckpointFile : public ::testing::Test {
 protected:
  void SetUp() override {
    // One directory per test: ctest runs them side by side.
    dir_ = fs::temp_directory_path() /
           (std::string("granjet_checkpoint_file_") +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  static StateArchive sample(double time) {
    StateArchive archive;
    archive.put("app/time", time);
    archive.put_reals("dem/force_prev", {1.0 / 3.0, -0.0, std::numeric_limits<double>::quiet_NaN(),
                                         std::numeric_limits<double>::denorm_min(), 1e308});
    archive.put_reals("dem/empty", {});
    archive.put_integers("writer/frames", {7});
    archive.put_integers("ids", {-1, 0, std::numeric_limits<std::int64_t>::max()});
    return archive;
  }
  static std::vector<std::uint64_t> bits(const std::vector<double>& values) {
    std::vector<std::uint64_t> out;
    for (double v : values) out.push_back(std::bit_cast<std::uint64_t>(v));
    return out;
  }

  fs::path dir_;
};

TEST_F(CheckpointFile, LiesBesideTheRunsFileWhetherItIsPartialOrNot) {
  EXPECT_EQ(checkpoint_path("out/run.h5"), fs::path("out/run.h5.checkpoint"));
  EXPECT_EQ(checkpoint_path("out/run.h5.partial"), fs::path("out/run.h5.checkpoint"));
}

TEST_F(CheckpointFile, GivesBackEveryEntryBitForBit) {
  const fs::path file = dir_ / "run.h5.checkpoint";
  const StateArchive written = sample(12.5);
  write_checkpoint_file(file, written);
  const StateArchive read = read_checkpoint_file(file);
  EXPECT_EQ(read.all_integers(), written.all_integers());
  ASSERT_EQ(read.all_reals().size(), written.all_reals().size());
  for (const auto& [name, values] : written.all_reals())
    EXPECT_EQ(bits(read.reals(name)), bits(values)) << name;
  EXPECT_EQ(checkpoint_time(file), 12.5);
  EXPECT_FALSE(fs::exists(dir_ / "run.h5.checkpoint.partial"));
}

TEST_F(CheckpointFile, ATornWriteBesideItLeavesTheLastComplete) {
  const fs::path file = dir_ / "run.h5.checkpoint";
  write_checkpoint_file(file, sample(4.0));
  std::string whole;
  {
    std::ifstream in(file, std::ios::binary);
    whole.assign(std::istreambuf_iterator<char>(in), {});
  }
  std::ofstream(dir_ / "run.h5.checkpoint.partial", std::ios::binary)
      << whole.substr(0, whole.size() / 3);
  EXPECT_EQ(checkpoint_time(file), 4.0);
  write_checkpoint_file(file, sample(6.0));  // the torn one is written over
  EXPECT_EQ(read_checkpoint_file(file).real("app/time"), 6.0);
  remove_checkpoint_file(file);
  EXPECT_TRUE(fs::is_empty(dir_));
  EXPECT_NO_THROW(remove_checkpoint_file(file));  // none left: no error
}

TEST_F(CheckpointFile, AWriteThatFailsKeepsTheLastOne) {
  const fs::path file = dir_ / "run.h5.checkpoint";
  write_checkpoint_file(file, sample(4.0));
  // A directory where the file being written would go: its creation fails.
  fs::create_directory(dir_ / "run.h5.checkpoint.partial");
  fs::create_directory(dir_ / "run.h5.checkpoint.partial" / "x");
  EXPECT_THROW(write_checkpoint_file(file, sample(6.0)), std::runtime_error);
  EXPECT_EQ(checkpoint_time(file), 4.0);
}

TEST_F(CheckpointFile, AMissingOrForeignOneIsAnInputErrorNamingIt) {
  const fs::path missing = dir_ / "none.h5.checkpoint";
  EXPECT_FALSE(checkpoint_time(missing).has_value());
  try {
    read_checkpoint_file(missing);
    FAIL() << "read a missing checkpoint";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
  const fs::path text = dir_ / "text.h5.checkpoint";
  std::ofstream(text) << "not HDF5\n";
  EXPECT_THROW(read_checkpoint_file(text), InputError);
  EXPECT_FALSE(checkpoint_time(text).has_value());
}

// Rank r's piece of an archive split over `ranks`: the shared entries alike on every rank (only
// rank 0's are stored), a share of r + 1 grains with ids 10 r .. 10 r + r, and an observer's
// member of its own (StateWriter::share) holding r.
StateArchive piece_of_rank(int r, int ranks) {
  StateArchive archive;
  archive.put("app/time", 3.0 + r);  // rank 0's must win
  archive.put_integers("writer/frames", {7});
  std::vector<std::int64_t> ids;
  std::vector<double> x;
  for (int k = 0; k <= r; ++k) {
    ids.push_back(10 * r + k);
    x.insert(x.end(), {1.0 / (r + 1), -0.0 * k});
  }
  archive.put_integers("dem/grains/id", ids);
  archive.put_reals("dem/grains/position", x);
  archive.put_reals("dem/history/shear", {});
  archive.split_over(ranks, {"dem/grains/", "dem/history/"});
  StateWriter(archive, "app/analysis").share("own")("rank", std::vector<int>{r});
  return archive;
}

std::vector<std::int64_t> ids_of_ranks(std::initializer_list<int> ranks) {
  std::vector<std::int64_t> ids;
  for (int r : ranks)
    for (int k = 0; k <= r; ++k) ids.push_back(10 * r + k);
  return ids;
}

TEST_F(CheckpointFile, SplitOverRanksEachReaderJoinsItsShares) {
  const fs::path file = dir_ / "run.h5.checkpoint";
  std::vector<int> asked;
  write_checkpoint_file(file, piece_of_rank(0, 3), [&](int r) {
    asked.push_back(r);
    return archive_from_bytes(share_bytes(piece_of_rank(r, 3)));
  });
  EXPECT_EQ(asked, (std::vector<int>{1, 2}));
  EXPECT_EQ(checkpoint_time(file), 3.0);

  const StateArchive whole = read_checkpoint_file(file);  // one reader joins all, in rank order
  EXPECT_EQ(whole.integers("dem/grains/id"), ids_of_ranks({0, 1, 2}));
  EXPECT_EQ(whole.reals("dem/grains/position").size(), 2u * 6u);
  EXPECT_EQ(bits(whole.reals("dem/grains/position")),
            bits({1.0, -0.0, 0.5, -0.0, 0.5, -0.0, 1.0 / 3, -0.0, 1.0 / 3, -0.0, 1.0 / 3, -0.0}));
  EXPECT_EQ(whole.real("app/time"), 3.0);
  EXPECT_EQ(whole.integer("checkpoint/ranks"), 3);
  EXPECT_FALSE(whole.contains("checkpoint/readers"));
  // Which entries came from the shares: those a follower takes as its own.
  EXPECT_EQ(whole.integers("app/analysis/own/rank"), (std::vector<std::int64_t>{0, 1, 2}));
  EXPECT_TRUE(StateReader(whole, "app/analysis/own").in_share("rank"));
  EXPECT_TRUE(StateReader(whole, "dem/grains").in_share("id"));
  EXPECT_FALSE(StateReader(whole, "app").in_share("time"));
  EXPECT_FALSE(StateReader(whole, "writer").in_share("frames"));

  // Three readers: each its own; two: the first takes shares 0 and 1 (s * 2 / 3 = 0), the
  // second share 2; five: two take none and still find every entry, empty.
  EXPECT_EQ(read_checkpoint_file(file, {1, 3}).integers("dem/grains/id"), ids_of_ranks({1}));
  EXPECT_EQ(read_checkpoint_file(file, {0, 2}).integers("dem/grains/id"), ids_of_ranks({0, 1}));
  EXPECT_EQ(read_checkpoint_file(file, {1, 2}).integers("dem/grains/id"), ids_of_ranks({2}));
  std::vector<std::int64_t> taken;
  for (int reader = 0; reader < 5; ++reader) {
    const StateArchive mine = read_checkpoint_file(file, {reader, 5});
    EXPECT_EQ(mine.integer("checkpoint/readers"), 5);
    EXPECT_EQ(mine.reals("dem/grains/position").size(), 2 * mine.integers("dem/grains/id").size());
    EXPECT_TRUE(mine.reals("dem/history/shear").empty());
    const std::vector<std::int64_t>& ids = mine.integers("dem/grains/id");
    taken.insert(taken.end(), ids.begin(), ids.end());
  }
  EXPECT_EQ(taken, ids_of_ranks({0, 1, 2}));

  const StateArchive root = read_checkpoint_file(file, {0, 0});  // the writer's counts alone
  EXPECT_EQ(root.integer("writer/frames"), 7);
  EXPECT_TRUE(root.integers("dem/grains/id").empty());
  EXPECT_TRUE(StateReader(root, "app/analysis/own").in_share("rank"));

  // A whole checkpoint (one process) has no shares: every reader takes all of it alike.
  StateArchive one = piece_of_rank(0, 1);
  write_checkpoint_file(file, one);
  EXPECT_FALSE(StateReader(read_checkpoint_file(file), "app/analysis/own").in_share("rank"));
}

TEST_F(CheckpointFile, AShareThatFailsToArriveKeepsTheLastOne) {
  const fs::path file = dir_ / "run.h5.checkpoint";
  write_checkpoint_file(file, sample(4.0));
  EXPECT_THROW(write_checkpoint_file(
                   file, piece_of_rank(0, 2),
                   [](int) -> StateArchive { throw std::runtime_error("rank 1 is gone"); }),
               std::runtime_error);
  EXPECT_EQ(checkpoint_time(file), 4.0);
  EXPECT_FALSE(fs::exists(dir_ / "run.h5.checkpoint.partial"));
}

}  // namespace
}  // namespace granjet::analysis
