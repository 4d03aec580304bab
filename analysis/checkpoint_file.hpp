// A run's checkpoint, the state `granjet resume` goes on from, in a file of its own beside the
// run's file: run.h5.checkpoint for run.h5 (and its run.h5.partial). It is written whole as
// run.h5.checkpoint.partial and renamed into place, so a process killed at any instant (kill -9,
// the out-of-memory killer) or stopped by a full disk leaves the last complete checkpoint. The
// run's file only ever grows by frames between checkpoints: HDF5 writes its metadata in no
// fixed order, and a file that also created and deleted checkpoints could be left by a kill with
// that metadata half-written.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>

#include "core/state_archive.hpp"

namespace granjet::analysis {

// run.h5.checkpoint for run.h5 or run.h5.partial.
std::filesystem::path checkpoint_path(const std::filesystem::path& run_file);

// Rank r's share of a checkpoint split over the K ranks of a run (StateArchive::split_over),
// asked for once each, r = 1 .. K - 1 in order.
using ShareOfRank = std::function<StateArchive(int rank)>;

// Every entry of `archive`, bit for bit, one dataset each. An archive split over K ranks keeps
// its shared entries at the root and each rank's share under /shares/<rank>/ (rank 0's from
// `archive`, the others' from `share_of`), and /checkpoint/ranks says K. Throws
// std::runtime_error naming the file (DiskFullError when the disk is full) and leaves the
// previous checkpoint as it was.
void write_checkpoint_file(const std::filesystem::path& checkpoint, const StateArchive& archive,
                           const ShareOfRank& share_of = {});

// Removes the checkpoint and any half-written one beside it; missing files are no error.
void remove_checkpoint_file(const std::filesystem::path& checkpoint);

// Which shares of a checkpoint split over K ranks a reader joins to the root's entries: reader
// `reader` of `readers` takes the shares s with s * readers / K == reader (each of K ranks its
// own; one reader all; more readers than shares leave some with none, their entries empty);
// `readers` = 0 takes none.
struct ShareReader {
  int reader = 0;
  int readers = 1;
};

// The root's entries and the shares `who` takes, joined in rank order, the shares' entries
// known as such (StateArchive::in_share); a split checkpoint read by several readers also holds
// "checkpoint/readers". Throws InputError naming the file when it
// is missing or unreadable.
StateArchive read_checkpoint_file(const std::filesystem::path& checkpoint, ShareReader who = {});

// The sim time a run's checkpoint stores (run_loop.hpp's "app/time"); empty when there is no
// readable one.
std::optional<double> checkpoint_time(const std::filesystem::path& checkpoint);

}  // namespace granjet::analysis
