// Writes a run as an H5MD 1.1 file (https://www.nongnu.org/h5md/h5md.html) plus an XDMF sidecar
// for ParaView. The file is written as <path>.partial and renamed to <path> only by finish(), so
// a file under its final name always holds a complete run.
//
// Grain data keep one row per grain id for the whole run (row r holds grain r), so that a row
// means the same grain in every frame; a grain removed during the run keeps its row with the
// fill values (id -1, H5MD's mark of a particle that does not exist; NaN elsewhere):
//
//   /particles/all/{position,velocity}/value [frames][rows][D], radius/value, id/value
//   [frames][rows]
//                  present/value [frames][rows]   the rows present, ascending, then -1
//                  (omega/value [frames][rows](x3 in 3D), force/value [frames][rows][D])
//                  box  dimension, boundary; with a periodic box edges/value [frames][D][D]
//   /connectivity/contacts/value [frames][C][2]   touching grain pairs (grain ids), then -1
//   /contacts/{normal_force,tangential_force}/value [frames][C][D], overlap/value [frames][C]
//   /observables/{kinetic_energy,...,frame_grains,frame_contacts,dt}/value, one row per frame
//
// Every time series shares the frames' step and time (hard links). Units: RunMetadata's labels.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "analysis/checkpoint_file.hpp"
#include "core/particles.hpp"
#include "core/scene.hpp"
#include "core/simulator.hpp"
#include "core/state_archive.hpp"

namespace granjet::analysis {

struct RunMetadata {
  std::string author = "granjet user";
  std::string creator = "granjet";
  std::string creator_version;  // e.g. "0.1.0"
  std::string backend;          // "soft_dem" | "event_driven"
  std::string scene_ini;        // the full scene as the backend ran it, as INI text, so the
                                // run can be redone
  // The scene as requested, where the backend adapted it (/parameters/granjet/requested_scene;
  // empty: none).
  std::string requested_scene_ini;
  int dimension = 3;  // must match the writer's D
  // What each frame stores beyond position, velocity, radius and id (OutputSpec), and the
  // unit attributes.
  bool omega = false;
  bool force = false;
  bool contacts = false;
  UnitLabels unit_labels = UnitLabels::kMdAnalysis;
  // The edges of the periodic box (gas scenes); empty: no axis wraps around.
  std::vector<double> periodic_box;
  // Sim time between stored frames, stored as the observable dt (MDAnalysis's Timestep.dt).
  double frame_interval = 1.0;
  // An ensemble file (no frames; /fields and /analysis combined over seeds): its member runs'
  // files, relative to its directory.
  std::vector<std::string> members;
};

struct Observables {
  double kinetic_energy = 0;
  double rotational_energy = 0;
  double elastic_energy = 0;
  double energy_dissipated = 0;
  std::int64_t grains = 0;
};

namespace detail {
class H5mdFile;  // the dimension-free part; defined in h5md_writer.cpp to keep <hdf5.h> private
}  // namespace detail

template <int D>
class H5mdWriter {
 public:
  // Creates `path` + ".partial" (never `path` itself) and holds a lock on it until publish();
  // an earlier run's checkpoint beside it goes.
  // max_grains (> 0) is the number of grain ids 0..max_grains-1, one row each: grains may only
  // be removed during a run. Throws FileBusyError (analysis/file_lock.hpp) when another run writes
  // the same file, std::runtime_error naming the file when it cannot be created.
  H5mdWriter(std::filesystem::path path, const RunMetadata& meta, std::size_t max_grains);
  // Reopens `path` + ".partial" at its checkpoint (checkpoint_file.hpp): frames and observables
  // written after it are dropped and the status is "running" again; the run goes on from
  // there.
  struct Resume {};
  H5mdWriter(std::filesystem::path path, Resume);
  H5mdWriter(const H5mdWriter&) = delete;
  H5mdWriter& operator=(const H5mdWriter&) = delete;
  // If neither finish() nor abandon() ran: closes the file and leaves it as .partial, with
  // status "running" and every frame written so far.
  ~H5mdWriter();

  // Ids per stretch of a frame's rows taken at once from a simulator: 32 chunks, some 67 MB of
  // grains in 3D, so that rank 0 of a run over MPI ranks holds that much of a frame at a time.
  static constexpr std::size_t kFrameBlockRows = std::size_t{1} << 19;

  // Stores each grain in the row of its id and flushes, so the frame survives a later crash.
  // `forces` (the same instant's) is required when RunMetadata asked for force or contacts.
  void write_frame(std::int64_t step, double time, const Particles<D>& particles,
                   const ForceSample<D>* forces = nullptr);
  // The frame of `sim` (Simulator::frame), taken in stretches of at most block_rows ids, with
  // the forces and contacts the file stores; returns its grain count. Over MPI ranks rank 0
  // calls it (through RankLeader), and no rank holds more than a stretch of it.
  std::size_t write_frame(std::int64_t step, double time, const Simulator<D>& sim,
                          std::size_t block_rows = kFrameBlockRows);
  // Appends one row; it becomes durable with the next frame's flush or at the end.
  void write_observables(std::int64_t step, double time, const Observables& obs);
  // Flushes the file and stores the run's state, with the count of frames and observables so
  // far, in the checkpoint file beside it (checkpoint_file.hpp), replacing the last one; an
  // archive split over ranks takes the other ranks' shares from `share_of`.
  void write_checkpoint(const StateArchive& archive, const ShareOfRank& share_of = {});
  // The stored scenes (RunMetadata::scene_ini, requested_scene_ini), replaced: a resume that
  // extends run.t_end.
  void replace_scenes(const std::string& scene_ini, const std::string& requested_scene_ini);
  // Marks the run complete, closes the file and writes the .xmf sidecar next to the final
  // name. Returns the .partial path, where the caller may add what else the run produced
  // (/fields, /analysis) before publish() renames it: a file under its final name is complete.
  std::filesystem::path complete();
  // Renames the .partial to `path` and removes the checkpoint.
  void publish();
  // complete() and publish().
  void finish();
  // Stores `reason` as the status, closes the file and keeps it readable as .partial (no
  // sidecar). Returns the .partial path.
  std::filesystem::path abandon(const std::string& reason);

 private:
  // A frame that `fill` hands to a sink; one that fails half-way leaves nothing of itself.
  std::size_t write_frame(std::int64_t step, double time,
                          const std::function<void(FrameSink<D>&)>& fill);

  std::unique_ptr<detail::H5mdFile> file_;
};

extern template class H5mdWriter<2>;
extern template class H5mdWriter<3>;

}  // namespace granjet::analysis
