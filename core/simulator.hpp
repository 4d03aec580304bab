// The backend-neutral interface. Virtual per call, never per contact or event: time and
// momentum transfer are the common currency through which analysis sees either backend.
#pragma once

#include <atomic>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/particles.hpp"
#include "core/phase_profile.hpp"
#include "core/sample_region.hpp"
#include "core/state_archive.hpp"

namespace granjet {

// Momentum handed from grain j to grain i, with both positions at the moment of transfer, so
// the analysis can apportion the contact stress along the segment r_i -> r_j [C.31]-[C.33].
template <int D>
struct PairImpulse {
  GrainId i = 0;
  GrainId j = 0;
  Vec<D> position_i;
  Vec<D> position_j;
  Vec<D> impulse;  // on i from j
};

// The forces of one instant, for per-grain output (H5MD force, force chains).
template <int D>
struct ForceSample {
  // A touching pair, or a grain and the plate (j = kPlateId): the force on i from j split
  // along the contact normal, and the overlap.
  struct Contact {
    GrainId i = 0;
    GrainId j = 0;
    Vec<D> normal_force;
    Vec<D> tangential_force;
    double overlap = 0.0;
  };
  std::vector<Contact> contacts;
  // Each grain's total force (contacts, plate, tethers), in the order of particles().
  std::vector<Vec<D>> total;
};

// What a frame asks of the simulator (Simulator::frame).
struct FrameAsk {
  std::size_t rows = 0;        // grain ids 0..rows-1
  std::size_t block_rows = 0;  // ids per block: over MPI ranks, rank 0 holds no more grains
  bool force = false;          // each grain's total force
  bool contacts = false;       // the touching pairs, with their forces
};

// Where a frame goes: its grains one block of ids at a time, the blocks in ascending order,
// then its contacts.
template <int D>
class FrameSink {
 public:
  virtual ~FrameSink() = default;
  // The grains whose ids lie in [first, end), in any order; `force`, when asked, their total
  // forces in the same order (empty otherwise).
  virtual void grains(GrainId first, GrainId end, const Particles<D>& grains,
                      std::span<const Vec<D>> force) = 0;
  virtual void contacts(std::span<const typename ForceSample<D>::Contact> contacts) = 0;
};

struct SimStats {
  std::int64_t steps = 0;           // DEM time steps (0 for event-driven)
  std::int64_t particle_steps = 0;  // sum over steps of the grains integrated (free grains)
  std::int64_t contacts = 0;        // contacts at the last step
  std::int64_t neighbour_rebuilds = 0;
  std::int64_t removed = 0;  // grains that left the region and were removed
  std::int64_t events = 0;   // event-driven only
  std::int64_t collisions = 0;
  std::int64_t cell_crossings = 0;
  // One run over MPI ranks (soft_dem/work_balance.hpp): how many, the busiest rank's work over
  // the ranks' mean, and how often the parts were cut anew; the ghost states all ranks sent a
  // step (soft_dem/domain.hpp), and what share of the ghosts they held those were. Counted
  // since this process started; not kept in checkpoints.
  int ranks = 1;
  double imbalance = 1.0;
  std::int64_t recuts = 0;
  double ghost_states_per_step = 0.0;
  double ghost_states_share = 0.0;
};

inline void put_stats(StateArchive& a, const std::string& name, const SimStats& s) {
  a.put_integers(name, {s.steps, s.particle_steps, s.contacts, s.neighbour_rebuilds, s.removed,
                        s.events, s.collisions, s.cell_crossings});
}
inline SimStats get_stats(const StateArchive& a, const std::string& name) {
  const std::vector<std::int64_t>& v = a.integers(name);
  if (v.size() != 8) throw std::runtime_error("checkpoint entry " + name + " is not 8 counts");
  return {v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]};
}

struct EnergyBalance {
  double kinetic = 0.0;  // translational, free and wall grains
  double rotational = 0.0;
  double elastic = 0.0;     // contact and tether springs
  double removed = 0.0;     // carried away by removed grains
  double dissipated = 0.0;  // initial total minus all of the above
  double total() const { return kinetic + rotational + elastic; }
};

class RankTeam;

// What a look at a run measures of its grains and contacts as sums that may be taken apart and
// joined (the analysis' bins): over MPI ranks each rank samples its own (Simulator::sample_own)
// and the ranks join their sums onto rank 0 (Simulator::join_samples), so that no rank gathers
// the grains.
template <int D>
class OwnSampler {
 public:
  virtual ~OwnSampler() = default;
  // `grains`: those the look's region holds (and every target grain held); `transfers`: the
  // momentum transfers since the last collect, covering `elapsed` (none at elapsed = 0).
  virtual void sample(const Particles<D>& grains, std::span<const PairImpulse<D>> transfers,
                      double elapsed) = 0;
  // Collective over `team`: rank 0 ends with every rank's samples joined, the others with none.
  virtual void join(const RankTeam& team) = 0;
  // What a rank keeps of its own samples after a join, in its share of a checkpoint
  // (StateWriter::share), and back on a resume: only what its shares held (StateReader::in_share),
  // for a checkpoint that one process wrote holds it all for rank 0.
  virtual void save_own(StateWriter& out) = 0;
  virtual void restore_own(StateReader& in) = 0;
};

template <int D>
class Simulator {
 public:
  virtual ~Simulator() = default;
  virtual std::string_view backend() const = 0;
  // Advances the state to time t (time-stepped backends stop at the first step at or after t).
  // Throws BlowUpError on a numerical blow-up.
  virtual void advance_to(double t) = 0;
  virtual double time() const = 0;
  virtual const Particles<D>& particles() const = 0;
  // particles().size(), which over MPI ranks needs no grain gathered.
  virtual std::size_t grain_count() const { return particles().size(); }
  // At least the grains `region` holds (core/sample_region.hpp), in particles()'s order: a look
  // that needs only those need not gather the rest over MPI ranks. Without ranks, and by
  // default, particles() itself.
  virtual const Particles<D>& particles_in(const SampleRegion& region) const {
    (void)region;
    return particles();
  }
  // A bound on how far any grain has moved since this simulator was made (or restored), the
  // sum of each step's time times its largest speed: between two reads it bounds every grain's
  // displacement (in a periodic box, up to the wraps by whole box lengths). Infinity where the
  // backend keeps none.
  virtual double travel() const { return std::numeric_limits<double>::infinity(); }
  // Appends the momentum transfers since the last call (soft DEM: the current pair forces
  // times the time since the last call, a sampled estimate; event-driven: every impulse).
  virtual void collect_transfers(std::vector<PairImpulse<D>>& out) = 0;
  // At least those of them that `region` holds, in collect_transfers' order; by default all.
  virtual void collect_transfers_in(std::vector<PairImpulse<D>>& out, const SampleRegion& region) {
    (void)region;
    collect_transfers(out);
  }
  // Hands `sampler` the grains `region` holds and collect_transfers_in's (covering `elapsed`).
  // Over MPI ranks each rank hands its own sampler its own grains and contacts, with no gather
  // (collective); alone, all of them.
  virtual void sample_own(const SampleRegion& region, double elapsed, OwnSampler<D>& sampler) {
    std::vector<PairImpulse<D>> collected;
    collect_transfers_in(collected, region);
    sampler.sample(particles_in(region), collected, elapsed);
  }
  // Over MPI ranks: every rank's sampler joins onto rank 0's (collective). Alone: nothing.
  virtual void join_samples(OwnSampler<D>& sampler) { (void)sampler; }
  // Backends that must record transfers as they happen (event-driven: every collision impulse)
  // keep them only while asked to, so a run that never collects them does not hoard memory.
  // Time-stepped backends sample on demand and ignore this.
  virtual void record_transfers(bool on) { (void)on; }
  virtual SimStats stats() const = 0;
  // Whether sample_forces() has something to say: hard spheres interact by impulses only.
  virtual bool has_contact_forces() const { return false; }
  // The forces at the current state, sampled without advancing anything (contact histories
  // are read, not stepped).
  virtual void sample_forces(ForceSample<D>& out) const {
    (void)out;
    throw std::logic_error(std::string(backend()) + " has no contact forces");
  }
  virtual EnergyBalance energy() const = 0;
  // The grains and forces a frame stores, handed to `sink` in blocks of ask.block_rows ids or
  // fewer (one process may hand all in one block). Over MPI ranks collective, and only rank
  // 0's sink hears of it, one block at a time: no rank gathers the whole run.
  virtual void frame(const FrameAsk& ask, FrameSink<D>& sink) const {
    ForceSample<D> forces;
    if (ask.force || ask.contacts) sample_forces(forces);
    sink.grains(0, static_cast<GrainId>(ask.rows), particles(),
                ask.force ? std::span<const Vec<D>>(forces.total) : std::span<const Vec<D>>());
    if (ask.contacts) sink.contacts(forces.contacts);
  }
  // Checkpoint: brings the state into a form that a simulator built anew from the same scene
  // takes over exactly (soft DEM: a neighbour-list rebuild; event-driven: every grain at one
  // time and the calendar predicted anew), then stores it. The run goes on bit-identically
  // in this simulator or in one that restore()d the archive, which must come from a simulator
  // of the same scene and backend.
  virtual void checkpoint(StateArchive& out) = 0;
  virtual void restore(const StateArchive& in) = 0;
  // Over MPI ranks, where checkpoint() gave rank 0 an archive split over them
  // (StateArchive::split_over): rank `rank`'s share of it, on rank 0. Collective.
  virtual StateArchive checkpoint_share(int rank) {
    throw std::logic_error(std::string(backend()) + " holds no other rank's share (rank " +
                           std::to_string(rank) + ")");
  }

  // While *flag is set, advance_to returns early: after the current step (soft DEM) or event
  // (event-driven), with time() where it stopped. The app sets it from a signal handler.
  virtual void stop_when(const std::atomic<bool>* flag) { stop_ = flag; }

  // Wall time per phase of advance_to, once enabled (`granjet run --profile`); the phases are
  // the backend's own.
  virtual PhaseProfile& profile() { return profile_; }
  virtual const PhaseProfile& profile() const { return profile_; }
  // profile()'s phase_seconds() on each MPI rank that shares the run, in rank order, on rank 0
  // (collective; the others get none); this process's alone when it runs alone.
  virtual std::vector<std::vector<double>> phase_seconds_by_rank() const {
    return {profile().phase_seconds()};
  }

 protected:
  bool stop_requested() const { return stop_ != nullptr && stop_->load(std::memory_order_relaxed); }

 private:
  const std::atomic<bool>* stop_ = nullptr;
  PhaseProfile profile_;
};

}  // namespace granjet
