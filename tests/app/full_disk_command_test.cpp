// A run on a filesystem too small for its frames: a clear error naming the cause (errno's text)
// and exit code 4, not a crash; once space is free, `granjet resume` goes on from the .partial's
// last checkpoint to the run's file bit for bit. The test mounts small tmpfs filesystems, which
// needs root; elsewhere it is skipped with the reason.
#include <sys/mount.h>

#include <cerrno>
#include <cstring>

#include "command_fixture.hpp"

namespace granjet {
namespace {

class FullDisk : public testing::CommandTest {
 protected:
  void SetUp() override {
    CommandTest::SetUp();
    small_ = dir_ / "small";
    std::filesystem::create_directories(small_);
    if (::mount("tmpfs", small_.c_str(), "tmpfs", 0, "size=4m") != 0)
      GTEST_SKIP() << "cannot mount a 4 MB tmpfs here (" << std::strerror(errno) << "; needs root)";
    mounted_ = true;
  }
  void TearDown() override {
    if (mounted_) ::umount(small_.c_str());
    CommandTest::TearDown();
  }
  std::filesystem::path small_;
  bool mounted_ = false;
};

TEST_F(FullDisk, RunNamesNoSpaceAndExitsWithoutACrash) {
  const int code = granjet("run " + scene("jet3d.ini") +
                           " --quiet --set run.t_end=20 --set output.interval=1 --out " +
                           (small_ / "j.h5").string());
  EXPECT_EQ(code, 4) << err_;
  EXPECT_NE(err_.find("No space left on device"), std::string::npos) << err_;
  EXPECT_FALSE(std::filesystem::exists(small_ / "j.h5"));  // never a file under the final name
}

TEST_F(FullDisk, RunResumesFromItsLastCheckpointOnceSpaceIsFree) {
  // 40 MB hold a checkpoint (t = 12) before the frames fill the disk; then 200 MB hold it all.
  ASSERT_EQ(::mount("tmpfs", small_.c_str(), "tmpfs", MS_REMOUNT, "size=40m"), 0)
      << std::strerror(errno);
  const std::string run = "run " + scene("jet3d.ini") +
                          " --quiet --no-log --set run.t_end=20 --set output.interval=1"
                          " --set run.checkpoint_interval=2 --out ";
  ASSERT_EQ(granjet(run + (small_ / "j.h5").string()), 4) << err_;
  EXPECT_NE(err_.find("No space left on device"), std::string::npos) << err_;
  ASSERT_EQ(::mount("tmpfs", small_.c_str(), "tmpfs", MS_REMOUNT, "size=200m"), 0)
      << std::strerror(errno);
  ASSERT_EQ(granjet("resume " + (small_ / "j.h5.partial").string() + " --quiet --no-log"), 0)
      << err_;
  ASSERT_EQ(granjet(run + (dir_ / "straight.h5").string()), 0) << err_;
  for (const char* group : {"/particles", "/observables"})
    EXPECT_TRUE(same_hdf5(small_ / "j.h5", dir_ / "straight.h5", group)) << group;
}

}  // namespace
}  // namespace granjet
