#include "analysis/h5md_writer.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "analysis/checkpoint_file.hpp"
#include "analysis/file_lock.hpp"
#include "analysis/h5md_reader.hpp"
#include "core/errors.hpp"
#include "core/plate_face.hpp"

namespace granjet::analysis {
namespace {

namespace fs = std::filesystem;

// Grain ids per frame, deliberately unsorted: the count shrinks 5 -> 4 -> 3.
const std::vector<std::vector<GrainId>> kFrames = {{40, 7, 19, 3, 25}, {25, 3, 40, 7}, {7, 40, 3}};
constexpr std::size_t kRows = 41;  // ids 0..40, one row each

// Distinct per grain, per frame and per axis, so a swapped row or axis shows.
template <int D>
Vec<D> position_of(GrainId id, std::size_t frame) {
  return Vec<D>::LinSpaced(D, 0.0, 1.0) + Vec<D>::Constant(static_cast<double>(id) + 0.25 * frame);
}
template <int D>
Vec<D> velocity_of(GrainId id, std::size_t frame) {
  return -0.5 * position_of<D>(id, frame);
}
double radius_of(GrainId id) { return 0.001 * static_cast<double>(id + 1); }

template <int D>
Particles<D> grains_of(std::size_t frame) {
  Particles<D> particles;
  for (GrainId id : kFrames[frame]) {
    particles.add(id, GrainKind::kFree, position_of<D>(id, frame), velocity_of<D>(id, frame),
                  radius_of(id), 1.0);
  }
  return particles;
}

RunMetadata metadata(int dimension) {
  RunMetadata meta;
  meta.creator_version = "0.1.0";
  meta.backend = "soft_dem";
  meta.scene_ini = "[scene]\nname = test\n";
  meta.dimension = dimension;
  return meta;
}

template <int D>
void write_frames(H5mdWriter<D>& writer, std::size_t count) {
  for (std::size_t k = 0; k < count; ++k) {
    writer.write_frame(100 * static_cast<std::int64_t>(k), 0.5 * k, grains_of<D>(k));
    writer.write_observables(100 * static_cast<std::int64_t>(k), 0.5 * k,
                             {1.0, 2.0, 3.0, 4.0, static_cast<std::int64_t>(kFrames[k].size())});
  }
}

template <int D>
void expect_frames_read_back(const fs::path& file, std::size_t count) {
  for (std::size_t k = 0; k < count; ++k) {
    SCOPED_TRACE("frame " + std::to_string(k));
    const Frame<D> frame = read_frame<D>(file, k);
    std::vector<GrainId> ids = kFrames[k];
    std::sort(ids.begin(), ids.end());
    EXPECT_EQ(frame.step, 100 * static_cast<std::int64_t>(k));
    EXPECT_EQ(frame.time, 0.5 * k);
    ASSERT_EQ(frame.id, ids);
    ASSERT_EQ(frame.position.size(), ids.size());
    ASSERT_EQ(frame.velocity.size(), ids.size());
    ASSERT_EQ(frame.radius.size(), ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) {
      EXPECT_EQ(frame.position[i], position_of<D>(ids[i], k)) << "grain " << ids[i];
      EXPECT_EQ(frame.velocity[i], velocity_of<D>(ids[i], k)) << "grain " << ids[i];
      EXPECT_EQ(frame.radius[i], radius_of(ids[i])) << "grain " << ids[i];
    }
  }
}

std::string contents(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

fs::path partial(fs::path file) {
  file += ".partial";
  return file;
}

// Runs `body` in a child process that then ends without destructors or closes, as if the run
// were killed; whether it got that far.
template <class Body>
bool in_a_killed_process(Body body) {
  const pid_t child = fork();
  if (child == 0) {
    body();
    std::_Exit(0);
  }
  int status = 0;
  return child > 0 && waitpid(child, &status, 0) == child && WIFEXITED(status) &&
         WEXITSTATUS(status) == 0;
}

// A dataset's stored values as bytes, whatever their type.
std::vector<char> dataset_bytes(const fs::path& file, const std::string& name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t set = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
  const hid_t stored = H5Dget_type(set);
  const hid_t type = H5Tget_native_type(stored, H5T_DIR_ASCEND);
  const hid_t space = H5Dget_space(set);
  std::vector<char> bytes(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)) *
                          H5Tget_size(type));
  if (set < 0 || H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()) < 0) bytes.clear();
  H5Sclose(space);
  H5Tclose(type);
  H5Tclose(stored);
  H5Dclose(set);
  H5Fclose(f);
  return bytes;
}

// Bytes per grain row of a frame in the per-grain series `name` (3D).
std::size_t raw_row_bytes(const std::string& name) {
  return name.find("position") != std::string::npos ? 3 * sizeof(double) : sizeof(GrainId);
}

class H5mdWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() / ("granjet_h5md_test_" + std::to_string(std::random_device{}()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
};

TEST_F(H5mdWriterTest, FinishedRunReadsBackIn3D) {
  const fs::path file = dir_ / "run.h5";
  {
    H5mdWriter<3> writer(file, metadata(3), kRows);
    EXPECT_TRUE(fs::exists(partial(file)));
    EXPECT_FALSE(fs::exists(file));
    write_frames(writer, 3);
    writer.finish();
  }
  EXPECT_TRUE(fs::exists(file));
  EXPECT_FALSE(fs::exists(partial(file)));

  const FileSummary summary = read_summary(file);
  EXPECT_EQ(summary.h5md_version, (std::array<int, 2>{1, 1}));
  EXPECT_EQ(summary.creator, "granjet");
  EXPECT_EQ(summary.creator_version, "0.1.0");
  EXPECT_EQ(summary.backend, "soft_dem");
  EXPECT_EQ(summary.status, "complete");
  EXPECT_EQ(summary.dimension, 3);
  EXPECT_EQ(summary.frames, 3u);
  EXPECT_EQ(summary.max_grains, kRows);
  EXPECT_EQ(summary.first_time, 0.0);
  EXPECT_EQ(summary.last_time, 1.0);
  EXPECT_EQ(summary.last_step, 200);
  EXPECT_EQ(summary.observable_rows, 3u);
  EXPECT_EQ(summary.scene_ini, "[scene]\nname = test\n");
  expect_frames_read_back<3>(file, 3);
  EXPECT_THROW(read_frame<3>(file, 3), std::runtime_error);
  EXPECT_THROW(read_frame<2>(file, 0), std::runtime_error);

  const std::string xmf = contents(dir_ / "run.xmf");
  EXPECT_NE(xmf.find("run.h5:/particles/all/position/value"), std::string::npos);
  EXPECT_EQ(xmf.find(dir_.string()), std::string::npos) << "the .h5 must be named relatively";
}

TEST_F(H5mdWriterTest, FinishedRunReadsBackIn2D) {
  const fs::path file = dir_ / "flat.h5";
  {
    H5mdWriter<2> writer(file, metadata(2), kRows);
    write_frames(writer, 3);
    writer.finish();
  }
  const FileSummary summary = read_summary(file);
  EXPECT_EQ(summary.dimension, 2);
  EXPECT_EQ(summary.frames, 3u);
  EXPECT_EQ(summary.max_grains, kRows);
  expect_frames_read_back<2>(file, 3);
  EXPECT_THROW(read_frame<3>(file, 0), std::runtime_error);
  EXPECT_TRUE(fs::exists(dir_ / "flat.xmf"));
}

// A damaged header that claims another number of rows for one series (here the radii,
// shortened by one) is refused as bad input before anything is allocated from it.
TEST_F(H5mdWriterTest, FramesWhoseSeriesDisagreeInRowsAreRefused) {
  const fs::path file = dir_ / "damaged.h5";
  {
    H5mdWriter<2> writer(file, metadata(2), kRows);
    write_frames(writer, 2);
    writer.finish();
  }
  {
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t radius = H5Dopen2(f, "/particles/all/radius/value", H5P_DEFAULT);
    const hsize_t shorter[2] = {2, kRows - 1};
    ASSERT_GE(H5Dset_extent(radius, shorter), 0);
    H5Dclose(radius);
    H5Fclose(f);
  }
  try {
    read_frame<2>(file, 0);
    FAIL() << "a frame with disagreeing series must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rows disagree"), std::string::npos) << e.what();
  }
}

TEST_F(H5mdWriterTest, AbandonedRunStaysPartialAndReadable) {
  const fs::path file = dir_ / "run.h5";
  fs::path kept;
  {
    H5mdWriter<3> writer(file, metadata(3), kRows);
    write_frames(writer, 2);
    kept = writer.abandon("blow-up at step 7");
  }
  EXPECT_EQ(kept, partial(file));
  EXPECT_FALSE(fs::exists(file));
  EXPECT_TRUE(fs::exists(kept));
  EXPECT_FALSE(fs::exists(dir_ / "run.xmf"));
  const FileSummary summary = read_summary(kept);
  EXPECT_EQ(summary.status, "blow-up at step 7");
  EXPECT_EQ(summary.frames, 2u);
  EXPECT_EQ(summary.last_step, 100);
  expect_frames_read_back<3>(kept, 2);
}

TEST_F(H5mdWriterTest, DestroyedWriterLeavesPartialMarkedRunning) {
  const fs::path file = dir_ / "run.h5";
  {
    H5mdWriter<3> writer(file, metadata(3), kRows);
    write_frames(writer, 1);
  }
  EXPECT_FALSE(fs::exists(file));
  const FileSummary summary = read_summary(partial(file));
  EXPECT_EQ(summary.status, "running");
  EXPECT_EQ(summary.frames, 1u);
  expect_frames_read_back<3>(partial(file), 1);
}

TEST_F(H5mdWriterTest, FlushedFramesSurviveAKilledRun) {
  const fs::path file = dir_ / "run.h5";
  ASSERT_TRUE(in_a_killed_process([&] {
    H5mdWriter<3> writer(file, metadata(3), kRows);
    write_frames(writer, 2);
  }));
  const FileSummary summary = read_summary(partial(file));
  EXPECT_EQ(summary.status, "running");
  EXPECT_EQ(summary.frames, 2u);
  expect_frames_read_back<3>(partial(file), 2);
}

// Killed while it appended a frame after its checkpoint: the frame reached some series only
// (here the steps, one row longer than the rest). The summary counts the frames every series
// holds, and a resume drops the torn one with everything after the checkpoint, goes on, and
// removes the checkpoint once published.
TEST_F(H5mdWriterTest, AFrameTornByAKillIsNotCountedAndAResumeDropsIt) {
  const fs::path file = dir_ / "run.h5";
  ASSERT_TRUE(in_a_killed_process([&] {
    H5mdWriter<3> writer(file, metadata(3), kRows);
    write_frames(writer, 1);
    StateArchive state;
    state.put("app/time", 0.25);
    writer.write_checkpoint(state);
    writer.write_frame(100, 0.5, grains_of<3>(1));
  }));
  {
    const hid_t f = H5Fopen(partial(file).c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t step = H5Dopen2(f, "/particles/all/position/step", H5P_DEFAULT);
    const hsize_t longer[1] = {3};
    ASSERT_GE(H5Dset_extent(step, longer), 0);
    H5Dclose(step);
    H5Fclose(f);
  }
  const FileSummary torn = read_summary(partial(file));
  EXPECT_EQ(torn.frames, 2u);
  EXPECT_EQ(torn.last_time, 0.5);
  EXPECT_TRUE(torn.checkpoint);
  EXPECT_EQ(torn.checkpoint_time, 0.25);
  {
    H5mdWriter<3> writer(file, H5mdWriter<3>::Resume{});
    writer.write_frame(100, 0.5, grains_of<3>(1));
    writer.write_frame(200, 1.0, grains_of<3>(2));
    writer.finish();
  }
  EXPECT_EQ(read_summary(file).frames, 3u);
  expect_frames_read_back<3>(file, 3);
  EXPECT_FALSE(fs::exists(checkpoint_path(file)));
}

// Killed after it completed, while it stored its analysis: the group's header was never
// written (here: zeroed), so HDF5 can neither read nor delete it. A resume from the checkpoint
// drops it with /fields, keeps the frames up to the checkpoint, and goes on.
TEST_F(H5mdWriterTest, AResumeAfterAKillThatTornTheAnalysisDropsIt) {
  const fs::path file = dir_ / "run.h5";
  {
    H5mdWriter<3> writer(file, metadata(3), kRows);
    write_frames(writer, 2);
    StateArchive state;
    state.put("app/time", 0.5);
    writer.write_checkpoint(state);
    write_frames(writer, 3);  // frames 0 and 1 again: rows need not differ here
    writer.complete();
  }  // the destructor leaves the .partial: never published
  haddr_t header = HADDR_UNDEF;
  {
    const hid_t f = H5Fopen(partial(file).c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    for (const char* group : {"/fields", "/analysis"})
      H5Gclose(H5Gcreate2(f, group, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    H5O_info_t info;
    ASSERT_GE(H5Oget_info_by_name2(f, "/analysis", &info, H5O_INFO_BASIC, H5P_DEFAULT), 0);
    header = info.addr;
    H5Fclose(f);
  }
  {
    std::fstream bytes(partial(file), std::ios::in | std::ios::out | std::ios::binary);
    bytes.seekp(static_cast<std::streamoff>(header));
    const std::string zeros(64, '\0');
    bytes.write(zeros.data(), static_cast<std::streamsize>(zeros.size()));
  }
  {
    const hid_t f = H5Fopen(partial(file).c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    H5E_BEGIN_TRY { EXPECT_LT(H5Ldelete(f, "/analysis", H5P_DEFAULT), 0); }
    H5E_END_TRY;
    H5Fclose(f);
  }
  EXPECT_TRUE(read_summary(partial(file)).checkpoint);  // complete, yet not published
  {
    H5mdWriter<3> writer(file, H5mdWriter<3>::Resume{});
    writer.write_frame(200, 1.0, grains_of<3>(2));
    writer.finish();
  }
  expect_frames_read_back<3>(file, 3);
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_EQ(H5Lexists(f, "/analysis", H5P_DEFAULT), 0);
  EXPECT_EQ(H5Lexists(f, "/fields", H5P_DEFAULT), 0);
  H5Fclose(f);
}

// Whatever else a run stores (/fields, /analysis) goes into the .partial between complete() and
// publish(): until the rename nothing is under the final name, and the sidecar is already there.
TEST_F(H5mdWriterTest, CompletedRunStaysPartialUntilPublished) {
  const fs::path file = dir_ / "run.h5";
  H5mdWriter<3> writer(file, metadata(3), kRows);
  write_frames(writer, 2);
  EXPECT_EQ(writer.complete(), partial(file));
  EXPECT_FALSE(fs::exists(file));
  EXPECT_EQ(read_summary(partial(file)).status, "complete");
  EXPECT_TRUE(fs::exists(dir_ / "run.xmf"));
  EXPECT_FALSE(fs::exists(dir_ / "run.xmf.partial"));
  writer.publish();
  EXPECT_TRUE(fs::exists(file));
  EXPECT_FALSE(fs::exists(partial(file)));
}

// A second writer of the same file finds it busy and leaves the first one's frames alone.
TEST_F(H5mdWriterTest, SecondWriterOfTheSameFileIsRefused) {
  const fs::path file = dir_ / "run.h5";
  H5mdWriter<3> first(file, metadata(3), kRows);
  write_frames(first, 2);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    try {
      H5mdWriter<3> second(file, metadata(3), kRows);
    } catch (const FileBusyError&) {
      std::_Exit(2);
    }
    std::_Exit(0);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2);
  first.finish();
  expect_frames_read_back<3>(file, 2);
}

TEST_F(H5mdWriterTest, WritingAfterFinishIsRefused) {
  H5mdWriter<3> writer(dir_ / "run.h5", metadata(3), kRows);
  writer.finish();
  EXPECT_THROW(writer.write_frame(0, 0.0, grains_of<3>(0)), std::logic_error);
}

TEST_F(H5mdWriterTest, GrainIdsBeyondTheRowsAreRefusedAndLeaveNoFrame) {
  const fs::path file = dir_ / "run.h5";
  {
    H5mdWriter<3> writer(file, metadata(3), kRows - 1);  // no row for id 40
    EXPECT_THROW(writer.write_frame(0, 0.0, grains_of<3>(0)), std::invalid_argument);
    Particles<3> without_40;
    without_40.add(7, GrainKind::kFree, position_of<3>(7, 0), velocity_of<3>(7, 0), radius_of(7),
                   1.0);
    writer.write_frame(100, 0.5, without_40);
    writer.finish();
  }
  EXPECT_EQ(read_summary(file).frames, 1u);
  const Frame<3> frame = read_frame<3>(file, 0);
  EXPECT_EQ(frame.step, 100);
  EXPECT_EQ(frame.id, std::vector<GrainId>{7});
  for (const char* set :
       {"/particles/all/position/value", "/particles/all/present/value", "/particles/all/id/value"})
    EXPECT_EQ(dataset_bytes(file, set).size(), raw_row_bytes(set) * (kRows - 1)) << set;
}

// A simulator that hands the frames of kFrames, with forces and contacts, in stretches of
// ask.block_rows ids, each stretch's grains last first, and the contacts in pieces of a quarter
// as many (the plate's among them); a stretch of ids at or past `fail_from` fails, and with
// `fail_in_contacts` the frame fails after its first piece of contacts.
class StretchedFrames final : public Simulator<3> {
 public:
  explicit StretchedFrames(std::size_t frame, GrainId fail_from = kRows,
                           bool fail_in_contacts = false)
      : frame_(frame), fail_from_(fail_from), fail_in_contacts_(fail_in_contacts) {}

  static ForceSample<3> forces(std::size_t frame) {
    ForceSample<3> f;
    for (GrainId id : kFrames[frame]) f.total.push_back(Vec<3>(id, -id, 0.5 * id));
    const auto& ids = kFrames[frame];
    for (std::size_t k = 0; k + 1 < ids.size(); ++k)
      f.contacts.push_back({ids[k], ids[k + 1], Vec<3>(1.0 * k, 0, 0), Vec<3>(0, 2.0 * k, 0),
                            0.01 * static_cast<double>(k)});
    f.contacts.push_back({ids[0], kPlateId, Vec<3>(0, 0, 1), Vec<3>::Zero(), 0.5});
    return f;
  }

  void frame(const FrameAsk& ask, FrameSink<3>& sink) const override {
    const Particles<3> all = grains_of<3>(frame_);
    const ForceSample<3> f = forces(frame_);
    for (std::size_t first = 0; first < ask.rows; first += ask.block_rows) {
      const auto low = static_cast<GrainId>(first);
      const auto end = static_cast<GrainId>(std::min(first + ask.block_rows, ask.rows));
      if (end > fail_from_) throw std::runtime_error("this stretch fails");
      std::vector<std::uint32_t> in;
      for (auto k = static_cast<std::uint32_t>(all.size()); k-- > 0;)
        if (all.id()[k] >= low && all.id()[k] < end) in.push_back(k);
      Particles<3> stretch = all;
      stretch.gather(in);
      std::vector<Vec<3>> force;
      for (std::uint32_t k : in) force.push_back(f.total[k]);
      sink.grains(low, end, stretch, ask.force ? force : std::vector<Vec<3>>());
    }
    if (!ask.contacts) return;
    const std::span<const ForceSample<3>::Contact> contacts(f.contacts);
    const std::size_t piece = std::max<std::size_t>(ask.block_rows / 4, 1);
    for (std::size_t first = 0; first < contacts.size(); first += piece) {
      sink.contacts(contacts.subspan(first, std::min(piece, contacts.size() - first)));
      if (fail_in_contacts_) throw std::runtime_error("this frame's contacts fail");
    }
  }

  std::string_view backend() const override { return "stretched frames"; }
  void advance_to(double) override {}
  double time() const override { return 0.5 * static_cast<double>(frame_); }
  const Particles<3>& particles() const override { throw std::logic_error("not asked"); }
  void collect_transfers(std::vector<PairImpulse<3>>&) override {}
  SimStats stats() const override { return {}; }
  EnergyBalance energy() const override { return {}; }
  void checkpoint(StateArchive&) override {}
  void restore(const StateArchive&) override {}

 private:
  std::size_t frame_;
  GrainId fail_from_;
  bool fail_in_contacts_;
};

TEST_F(H5mdWriterTest, AFrameTakenInStretchesOfIdsIsTheFrameWrittenWhole) {
  RunMetadata meta = metadata(3);
  meta.omega = meta.force = meta.contacts = true;
  const fs::path whole = dir_ / "whole.h5", stretched = dir_ / "stretched.h5";
  {
    H5mdWriter<3> a(whole, meta, kRows), b(stretched, meta, kRows);
    for (std::size_t k = 0; k < kFrames.size(); ++k) {
      const ForceSample<3> f = StretchedFrames::forces(k);
      a.write_frame(100 * static_cast<std::int64_t>(k), 0.5 * k, grains_of<3>(k), &f);
      // 41 rows in stretches of 8, 32 and 128 (one stretch for all); the 5, 4 and 3 contacts
      // in pieces of 2, 8 and 32
      const std::size_t grains = b.write_frame(100 * static_cast<std::int64_t>(k), 0.5 * k,
                                               StretchedFrames(k), std::size_t{8} << (k * 2));
      EXPECT_EQ(grains, kFrames[k].size());
    }
    a.finish();
    b.finish();
  }
  const std::string all = "/particles/all/";
  for (const std::string& set :
       {all + "position/value", all + "velocity/value", all + "radius/value", all + "id/value",
        all + "present/value", all + "omega/value", all + "force/value", all + "position/step",
        all + "position/time", std::string("/connectivity/contacts/value"),
        std::string("/contacts/normal_force/value"),
        std::string("/contacts/tangential_force/value"), std::string("/contacts/overlap/value"),
        std::string("/observables/frame_grains/value"),
        std::string("/observables/frame_contacts/value")}) {
    const std::vector<char> expected = dataset_bytes(whole, set);
    EXPECT_FALSE(expected.empty()) << set;
    EXPECT_EQ(expected, dataset_bytes(stretched, set)) << set;
  }
}

TEST_F(H5mdWriterTest, AFrameThatFailsHalfWayLeavesNoneOfItsRows) {
  const fs::path file = dir_ / "run.h5";
  {
    H5mdWriter<3> writer(file, metadata(3), kRows);
    writer.write_frame(0, 0.0, StretchedFrames(0), 8);
    EXPECT_THROW(writer.write_frame(100, 0.5, StretchedFrames(1, 30), 8), std::runtime_error);
    writer.write_frame(100, 0.5, StretchedFrames(1), 8);
    writer.finish();
  }
  EXPECT_EQ(read_summary(file).frames, 2u);
  expect_frames_read_back<3>(file, 2);
  EXPECT_EQ(dataset_bytes(file, "/particles/all/position/value").size(),
            2 * kRows * 3 * sizeof(double));
}

// The contacts of a frame that fails between its pieces go with it, and so does the room it
// made for them: the file is the one written without that frame.
TEST_F(H5mdWriterTest, AFrameThatFailsBetweenItsContactsLeavesNoneOfThem) {
  RunMetadata meta = metadata(3);
  meta.contacts = true;
  const fs::path failed = dir_ / "failed.h5", clean = dir_ / "clean.h5";
  {
    H5mdWriter<3> a(failed, meta, kRows), b(clean, meta, kRows);
    a.write_frame(0, 0.0, StretchedFrames(2), 128);  // 3 contacts, 2 pairs
    b.write_frame(0, 0.0, StretchedFrames(2), 128);
    // 5 contacts in pieces of 4: the first widens the file to 4 pairs before the frame fails
    EXPECT_THROW(a.write_frame(100, 0.5, StretchedFrames(0, kRows, true), 16), std::runtime_error);
    a.finish();
    b.finish();
  }
  EXPECT_EQ(read_summary(failed).frames, 1u);
  for (const char* set : {"/connectivity/contacts/value", "/contacts/normal_force/value",
                          "/contacts/tangential_force/value", "/contacts/overlap/value"}) {
    EXPECT_FALSE(dataset_bytes(clean, set).empty()) << set;
    EXPECT_EQ(dataset_bytes(failed, set), dataset_bytes(clean, set)) << set;
  }
}

TEST_F(H5mdWriterTest, MissingDirectoryThrowsNamingThePath) {
  const fs::path file = dir_ / "no_such_dir" / "run.h5";
  try {
    H5mdWriter<3> writer(file, metadata(3), kRows);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
}

TEST_F(H5mdWriterTest, NonHdf5FileThrowsNamingTheFile) {
  const fs::path file = dir_ / "scene.ini";
  std::ofstream(file) << "[scene]\n";
  try {
    read_summary(file);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace granjet::analysis
