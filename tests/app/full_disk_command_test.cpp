// A run on a filesystem too small for its frames: a clear error naming the cause (errno's text)
// and exit code 1, not a crash. The test mounts a 4 MB tmpfs, which needs root; elsewhere it
// is skipped with the reason.
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
  EXPECT_EQ(code, 1) << err_;
  EXPECT_NE(err_.find("No space left on device"), std::string::npos) << err_;
  EXPECT_FALSE(std::filesystem::exists(small_ / "j.h5"));  // never a file under the final name
}

}  // namespace
}  // namespace granjet
