// Scene files: the shipped scenes load, the resolved INI reproduces the scene, and every bad
// input is refused with an InputError naming the key and what is allowed.
#include "run/scene_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/errors.hpp"

namespace granjet {
namespace {

const std::string kScenes = GRANJET_SCENES_DIR;

// The scene read back from its resolved INI, as `granjet info --scene` gives it.
Scene reparsed(const std::string& ini) {
  std::istringstream in(ini);
  return parse_scene(in, "resolved", {});
}

TEST(SceneFile, ShippedScenesLoad) {
  const Scene jet3d = load_scene(kScenes + "/jet3d.ini", {});
  EXPECT_EQ(jet3d.dimension, 3);
  EXPECT_EQ(jet3d.jet.grains, 20000);
  EXPECT_DOUBLE_EQ(jet3d.contact.friction, 0.2);
  EXPECT_DOUBLE_EQ(jet3d.dt(), 0.002);  // 0.02 t_c
  const Scene jet2d = load_scene(kScenes + "/jet2d.ini", {});
  EXPECT_EQ(jet2d.dimension, 2);
  EXPECT_EQ(jet2d.jet.dispersity, Dispersity::kBi);
  EXPECT_DOUBLE_EQ(jet2d.wall.diameter, 2.2 * jet2d.jet.diameter);
  EXPECT_EQ(load_scene(kScenes + "/binary.ini", {}).kind, SceneKind::kBinary);
}

TEST(SceneFile, OverridesWinAndResolvedIniReproducesTheScene) {
  const Scene s = load_scene(kScenes + "/jet3d.ini",
                             {"contact.restitution=0.9", "wall.kind=fixed", "run.seed=7"});
  EXPECT_DOUBLE_EQ(s.contact.restitution, 0.9);
  EXPECT_EQ(s.wall.kind, WallKind::kFixed);
  const std::string ini = scene_to_ini(s);
  const Scene again = reparsed(ini);
  EXPECT_EQ(scene_to_ini(again), ini);
  EXPECT_NE(ini.find("dt = 0.002"), std::string::npos);  // dt stored resolved
}

// The flat target plate is a third target kind; it survives the resolved INI.
TEST(SceneFile, WallKindPlateParsesAndRoundTrips) {
  const Scene s = load_scene(kScenes + "/jet2d.ini", {"wall.kind=plate"});
  EXPECT_EQ(s.wall.kind, WallKind::kPlate);
  const std::string ini = scene_to_ini(s);
  EXPECT_NE(ini.find("kind = plate"), std::string::npos);
  EXPECT_EQ(reparsed(ini).wall.kind, WallKind::kPlate);
}

// Spec §6 "Height origin": a scene key, wall_centres by default, stored in the resolved scene.
TEST(SceneFile, AnalysisHeightOriginParsesAndRoundTrips) {
  EXPECT_EQ(load_scene(kScenes + "/binary.ini", {}).analysis.height_origin,
            HeightOrigin::kWallCentres);  // a scene without the key: the default
  const Scene centres = load_scene(kScenes + "/jet3d.ini", {});
  EXPECT_EQ(centres.analysis.height_origin, HeightOrigin::kWallCentres);
  EXPECT_NE(scene_to_ini(centres).find("height_origin = wall_centres"), std::string::npos);
  const Scene s = load_scene(kScenes + "/jet2d.ini", {"analysis.height_origin=wall_surface"});
  EXPECT_EQ(s.analysis.height_origin, HeightOrigin::kWallSurface);
  const std::string ini = scene_to_ini(s);
  EXPECT_NE(ini.find("height_origin = wall_surface"), std::string::npos);
  EXPECT_EQ(reparsed(ini).analysis.height_origin, HeightOrigin::kWallSurface);
}

// Spec §5 anisotropy runs: the rectangular jet's keys parse and are stored in the resolved scene.
TEST(SceneFile, RectangularJetKeysParseAndRoundTrip) {
  EXPECT_EQ(load_scene(kScenes + "/jet3d.ini", {}).jet.shape, JetShape::kCylinder);
  const Scene s = load_scene(kScenes + "/jet3d.ini",
                             {"jet.shape=rectangle", "jet.aspect_ratio=3", "jet.area=16"});
  EXPECT_EQ(s.jet.shape, JetShape::kRectangle);
  EXPECT_DOUBLE_EQ(s.jet.long_side(), std::sqrt(48.0));
  EXPECT_DOUBLE_EQ(s.jet.short_side(), std::sqrt(16.0 / 3.0));
  const std::string ini = scene_to_ini(s);
  for (const char* line : {"shape = rectangle", "aspect_ratio = 3", "area = 16"})
    EXPECT_NE(ini.find(line), std::string::npos) << line;
  EXPECT_EQ(scene_to_ini(reparsed(ini)), ini);
}

// Target lattices, the scatter radius and the normal-force clamp are stored in the resolved
// scene.
TEST(SceneFile, WallLatticeAndScatterRadiusKeysRoundTrip) {
  const Scene s = load_scene(kScenes + "/jet3d.ini",
                             {"wall.lattice=square", "wall.spacing=1.5", "wall.jitter=0.125",
                              "analysis.scatter_radius=30", "contact.clamp_normal=true"});
  EXPECT_EQ(s.wall.lattice, WallLattice::kSquare);
  const std::string ini = scene_to_ini(s);
  for (const char* line : {"lattice = square", "spacing = 1.5", "jitter = 0.125",
                           "scatter_radius = 30", "clamp_normal = true"})
    EXPECT_NE(ini.find(line), std::string::npos) << line;
  EXPECT_EQ(scene_to_ini(reparsed(ini)), ini);
}

// Expects an InputError whose message names `key` and contains `allowed`.
void expect_refused(const std::vector<std::string>& overrides, const std::string& key,
                    const std::string& allowed) {
  try {
    load_scene(kScenes + "/jet3d.ini", overrides);
    ADD_FAILURE() << "accepted " << overrides.front();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(allowed), std::string::npos) << e.what();
  }
}

// The readings the study leaves open (model §6, [4.3]): psi0 from the departure directions or the
// momentum balance, the fields' contact stress with or without the target's contacts. Defaults
// keep the measurement as it was; both survive the resolved INI; anything else is refused.
TEST(SceneFile, AnalysisReadingsParseRoundTripAndRefuseOthers) {
  const Scene plain = load_scene(kScenes + "/jet3d.ini", {});
  EXPECT_EQ(plain.analysis.psi0, Psi0Reading::kDeparture);
  EXPECT_EQ(plain.analysis.stress_wall_contacts, WallContacts::kInclude);
  const Scene s = load_scene(kScenes + "/jet3d.ini",
                             {"analysis.psi0=momentum", "analysis.stress_wall_contacts=exclude"});
  const std::string ini = scene_to_ini(s);
  EXPECT_NE(ini.find("psi0 = momentum"), std::string::npos);
  EXPECT_NE(ini.find("stress_wall_contacts = exclude"), std::string::npos);
  EXPECT_EQ(reparsed(ini).analysis.psi0, Psi0Reading::kMomentum);
  EXPECT_EQ(reparsed(ini).analysis.stress_wall_contacts, WallContacts::kExclude);
  expect_refused({"analysis.psi0=force"}, "analysis.psi0", "departure | momentum");
  expect_refused({"analysis.stress_wall_contacts=no"}, "analysis.stress_wall_contacts",
                 "include | exclude");
}

TEST(SceneFile, BadValuesNameTheKeyAndTheAllowedRange) {
  expect_refused({"contact.restitution=0"}, "contact.restitution", "(0, 1]");
  expect_refused({"contact.restitution=1.5"}, "contact.restitution", "(0, 1]");
  expect_refused({"contact.contact_time=0"}, "contact.contact_time", "> 0");
  expect_refused({"contact.contact_time=-1"}, "contact.contact_time", "> 0");
  expect_refused({"contact.friction=-0.1"}, "contact.friction", ">= 0");
  expect_refused({"run.dt=0.1"}, "run.dt", "smaller than contact.contact_time");
  expect_refused({"run.dt=0.2"}, "run.dt", "smaller than contact.contact_time");
  expect_refused({"jet.phi_tilde=0"}, "jet.phi_tilde", "(0, 1]");
  expect_refused({"jet.phi_tilde=1.01"}, "jet.phi_tilde", "(0, 1]");
  expect_refused({"contact.restitution=abc"}, "contact.restitution", "not a finite number");
  expect_refused({"contact.restitution=nan"}, "contact.restitution", "not a finite number");
  expect_refused({"wall.kind=soft"}, "wall.kind", "tethered | fixed | plate");
  expect_refused({"analysis.height_origin=surface"}, "analysis.height_origin",
                 "wall_centres | wall_surface");
  expect_refused({"jet.shape=square"}, "jet.shape", "cylinder | rectangle");
  expect_refused({"jet.aspect_ratio=0.5"}, "jet.aspect_ratio", ">= 1");
  expect_refused({"jet.area=0"}, "jet.area", "> 0");
  // The rectangle is a 3D cross section (model §5); the 2D jet is a strip.
  expect_refused({"scene.dimension=2", "jet.shape=rectangle"}, "jet.shape", "3D");
  expect_refused({"jet.grains=2.5"}, "jet.grains", "integer in [1, 1000000000]");
  // Integers are range-checked before they are narrowed: 2^32 + 2 does not wrap to 2.
  expect_refused({"run.threads=4294967296"}, "run.threads", "in [1, 256]");
  expect_refused({"run.threads=4294967298"}, "run.threads", "in [1, 256]");
  expect_refused({"run.threads=257"}, "run.threads", "in [1, 256]");
  expect_refused({"analysis.lateral_bins=4294967297"}, "analysis.lateral_bins",
                 "in [1, 2147483647]");
  expect_refused({"gas.grains=9223372036854775808"}, "gas.grains", "in [2, 1000000000]");
  expect_refused({"gas.grains=9223372036854775807"}, "gas.grains", "in [2, 1000000000]");
  expect_refused({"run.skin=1e12"}, "run.skin", "(0, 5]");
  // Target lattices (model §4 leaves them open): no jitter into overlaps, no ambiguous tether
  // neighbours; a spacing below 1 overlaps the grains into a smoother layer, down to 0.5.
  expect_refused({"contact.clamp_normal=yes"}, "contact.clamp_normal", "false | true");
  expect_refused({"wall.lattice=random"}, "wall.lattice", "hexagonal | square");
  expect_refused({"wall.spacing=0.4"}, "wall.spacing", ">= 0.5");
  EXPECT_EQ(load_scene(kScenes + "/jet3d.ini", {"wall.spacing=0.75"}).wall.spacing, 0.75);
  expect_refused({"wall.spacing=0.75", "wall.jitter=0.05"}, "wall.jitter", "0 below spacing 1");
  expect_refused({"wall.jitter=0.1"}, "wall.jitter", "at most (wall.spacing - 1)/2 = 0");
  expect_refused({"wall.spacing=1.2", "wall.jitter=0.15"}, "wall.jitter", "at most");
  expect_refused({"wall.lattice=square", "wall.spacing=3", "wall.jitter=0.9"}, "wall.jitter",
                 "next-nearest");
  expect_refused({"scene.dimension=2", "wall.lattice=square"}, "wall.lattice", "3D lattice");
  expect_refused({"analysis.scatter_radius=44"}, "analysis.scatter_radius",
                 "smaller than region.radius = 44");
  // A removal region inside the jet took its outer grains before they reached the target.
  expect_refused({"region.radius=5"}, "region.radius", "cuts the jet (outer radius 5)");
  expect_refused({"no.such_key=1"}, "no.such_key", "unknown key");
  expect_refused({"run.tend=5"}, "run.tend", "unknown key; did you mean run.t_end?");
  expect_refused({"contact.fricton=0"}, "contact.fricton", "did you mean contact.friction?");
  expect_refused({"contact.restitution"}, "contact.restitution", "section.key=value");
}

TEST(SceneFile, OutputFieldsListTheOptionalPerGrainData) {
  const Scene plain = load_scene(kScenes + "/jet3d.ini", {});
  EXPECT_FALSE(plain.output.omega || plain.output.force || plain.output.contacts);
  const Scene chains = load_scene(kScenes + "/jet3d.ini",
                                  {"output.fields= id, position,velocity , radius,contacts"});
  EXPECT_TRUE(chains.output.contacts);
  EXPECT_FALSE(chains.output.omega || chains.output.force);
  const Scene again = reparsed(scene_to_ini(chains));
  EXPECT_TRUE(again.output.contacts && !again.output.omega && !again.output.force);
  expect_refused({"output.fields=position,velocity,radius,id,spin"}, "output.fields",
                 "'spin' is not one of");
  expect_refused({"output.fields=position,velocity,id,force"}, "output.fields", "lacks radius");
  expect_refused({"output.fields=position,velocity,radius,id,force,force"}, "output.fields",
                 "listed twice");
  expect_refused({"output.unit_labels=SI"}, "output.unit_labels", "mdanalysis | reduced");
}

TEST(SceneFile, UnknownKeyInFileAndMissingFileAreRefused) {
  std::istringstream in("[contact]\nrestitution = 0.8\nrestitutoin = 0.9\n");
  EXPECT_THROW(
      {
        try {
          parse_scene(in, "typo.ini", {});
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("contact.restitutoin"), std::string::npos);
          EXPECT_NE(std::string(e.what()).find("did you mean contact.restitution?"),
                    std::string::npos);
          throw;
        }
      },
      InputError);
  EXPECT_THROW(load_scene("/nonexistent/scene.ini", {}), InputError);
}

// The last of two assignments does not silently win: both lines are named.
TEST(SceneFile, DuplicateKeyIsRefusedNamingBothLines) {
  std::istringstream in(
      "[scene]\nkind = jet\n[contact]\nrestitution = 0.8\n# e\n"
      "restitution = 0.9\n");
  try {
    parse_scene(in, "twice.ini", {});
    ADD_FAILURE() << "a duplicate key was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "contact.restitution");
    EXPECT_NE(std::string(e.what()).find("lines 4 and 6"), std::string::npos) << e.what();
  }
}

// A directory, an empty file or one with only comments used to run the default jet3d.
TEST(SceneFile, SceneMustBeARegularFileThatNamesItsKind) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("granjet_scene_kind_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "empty.ini").close();
  std::ofstream(dir / "comments.ini") << "# a scene to be\n[contact]\n# restitution = 0.8\n";
  std::ofstream(dir / "kinded.ini") << "[scene]\nkind = binary\n";
  const auto refused = [](const std::filesystem::path& file, const std::string& why) {
    try {
      load_scene(file, {});
      ADD_FAILURE() << file << " was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), file.string());
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  };
  refused(dir, "not a regular file");
  refused(dir / "empty.ini", "names no scene.kind");
  refused(dir / "comments.ini", "names no scene.kind");
  EXPECT_EQ(load_scene(dir / "kinded.ini", {}).kind, SceneKind::kBinary);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace granjet
