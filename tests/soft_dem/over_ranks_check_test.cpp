// dem::check_over_ranks: which scenes the soft DEM spreads over MPI ranks. The decomposition
// cuts open space, so the periodic gases run on one rank; every rank refuses them alike, with
// the launcher's rank count named, before any grain is built (run and resume check it first).
#include <gtest/gtest.h>

#include <string>

#include "core/errors.hpp"
#include "run/scene_file.hpp"
#include "soft_dem/scene_support.hpp"

namespace granjet {
namespace {

Scene shipped(const std::string& name) {
  return load_scene(std::string(GRANJET_SCENES_DIR) + "/" + name, {});
}

TEST(OverRanksCheck, RefusesAPeriodicBoxOnMoreThanOneRank) {
  for (const char* name : {"gas3d.ini", "gas2d.ini", "hcs3d.ini", "hcs2d.ini"}) {
    const Scene gas = shipped(name);
    EXPECT_NO_THROW(dem::check_over_ranks(gas, 1)) << name;
    try {
      dem::check_over_ranks(gas, 3);
      ADD_FAILURE() << name << " was not refused";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "mpirun -n 3") << name;
      EXPECT_NE(std::string(e.what()).find("a periodic box runs on one rank"), std::string::npos)
          << e.what();
    }
  }
}

TEST(OverRanksCheck, SpreadsTheOpenSpaceScenes) {
  for (const char* name : {"jet3d.ini", "jet2d.ini", "jet3d_large.ini", "binary.ini"})
    EXPECT_NO_THROW(dem::check_over_ranks(shipped(name), 16)) << name;
}

}  // namespace
}  // namespace granjet
