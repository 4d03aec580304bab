// `mpirun -n K granjet run`: rank 0 runs the command as on one rank, through a RankLeader that
// hands each collective call of the soft-DEM simulator (soft_dem/domain.hpp) to the other
// ranks first; they follow in follow_leader, holding their share of the grains and writing
// nothing. A blow-up is raised on every rank alike: a follower waits for the leader's next
// call (its summary still asks for the energies) and leaves when the leader is done.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

#include "core/archive_shares.hpp"
#include "core/errors.hpp"
#include "core/rank_team.hpp"
#include "core/sample_region.hpp"
#include "core/simulator.hpp"
#include "core/state_archive.hpp"

namespace granjet {

enum class RankOrder : int {
  kAdvance,
  kParticles,
  kGrainCount,
  kParticlesIn,
  kTransfers,
  kTransfersIn,
  kSampleOwn,
  kJoinSamples,
  kStats,
  kForces,
  kEnergy,
  kFrame,
  kCheckpoint,
  kCheckpointShare,
  kRestore,
  kProfile,
  kDone
};

struct RankCall {
  RankOrder order = RankOrder::kDone;
  double value = 0.0;   // advance_to's time, checkpoint_share's rank, sample_own's elapsed
  SampleRegion region;  // particles_in's, collect_transfers_in's and sample_own's
  FrameAsk frame;       // frame's
};

// A follower's frame sink: only rank 0 hears of a frame.
template <int D>
struct NoFrame final : FrameSink<D> {
  void grains(GrainId, GrainId, const Particles<D>&, std::span<const Vec<D>>) override {}
  void contacts(std::span<const typename ForceSample<D>::Contact>) override {}
};

// Each rank's row, on rank 0 in rank order (none elsewhere). Collective.
inline std::vector<std::vector<double>> rows_on_rank0(const RankTeam& ranks,
                                                      const std::vector<double>& mine) {
  const std::vector<std::int64_t> sizes =
      ranks.gather<std::int64_t>(std::vector<std::int64_t>{std::ssize(mine)});
  const std::vector<double> all = ranks.gather<double>(mine);
  std::vector<std::vector<double>> rows;
  auto at = all.begin();
  for (std::int64_t size : sizes) {
    rows.emplace_back(at, at + size);
    at += size;
  }
  return rows;
}

template <int D>
class RankLeader final : public Simulator<D> {
 public:
  RankLeader(std::unique_ptr<Simulator<D>> sim, RankTeam ranks)
      : sim_(std::move(sim)), ranks_(ranks) {}
  ~RankLeader() override { call(RankOrder::kDone); }
  RankLeader(const RankLeader&) = delete;
  RankLeader& operator=(const RankLeader&) = delete;

  std::string_view backend() const override { return sim_->backend(); }
  double time() const override { return sim_->time(); }
  bool has_contact_forces() const override { return sim_->has_contact_forces(); }
  void stop_when(const std::atomic<bool>* flag) override { sim_->stop_when(flag); }
  PhaseProfile& profile() override { return sim_->profile(); }
  const PhaseProfile& profile() const override { return sim_->profile(); }

  void advance_to(double t) override {
    call(RankOrder::kAdvance, t);
    sim_->advance_to(t);
  }
  const Particles<D>& particles() const override {
    call(RankOrder::kParticles);
    return sim_->particles();
  }
  std::size_t grain_count() const override {
    call(RankOrder::kGrainCount);
    return sim_->grain_count();
  }
  const Particles<D>& particles_in(const SampleRegion& region) const override {
    call(RankOrder::kParticlesIn, 0.0, region);
    return sim_->particles_in(region);
  }
  // Alike on every rank: each sums the speeds the ranks agreed on.
  double travel() const override { return sim_->travel(); }
  void collect_transfers(std::vector<PairImpulse<D>>& out) override {
    call(RankOrder::kTransfers);
    sim_->collect_transfers(out);
  }
  void collect_transfers_in(std::vector<PairImpulse<D>>& out, const SampleRegion& region) override {
    call(RankOrder::kTransfersIn, 0.0, region);
    sim_->collect_transfers_in(out, region);
  }
  void sample_own(const SampleRegion& region, double elapsed, OwnSampler<D>& sampler) override {
    call(RankOrder::kSampleOwn, elapsed, region);
    sim_->sample_own(region, elapsed, sampler);
  }
  void join_samples(OwnSampler<D>& sampler) override {
    call(RankOrder::kJoinSamples);
    sim_->join_samples(sampler);
  }
  SimStats stats() const override {
    call(RankOrder::kStats);
    return sim_->stats();
  }
  void sample_forces(ForceSample<D>& out) const override {
    call(RankOrder::kForces);
    sim_->sample_forces(out);
  }
  EnergyBalance energy() const override {
    call(RankOrder::kEnergy);
    return sim_->energy();
  }
  void frame(const FrameAsk& ask, FrameSink<D>& sink) const override {
    call(RankOrder::kFrame, 0.0, {}, ask);
    sim_->frame(ask, sink);
  }
  void checkpoint(StateArchive& out) override {
    call(RankOrder::kCheckpoint);
    sim_->checkpoint(out);
  }
  StateArchive checkpoint_share(int rank) override {
    call(RankOrder::kCheckpointShare, rank);
    return share_on_rank0(ranks_, rank, {});
  }
  // The followers restore the archive they were given (their shares of the same file).
  void restore(const StateArchive& in) override {
    call(RankOrder::kRestore);
    sim_->restore(in);
  }
  std::vector<std::vector<double>> phase_seconds_by_rank() const override {
    call(RankOrder::kProfile);
    return rows_on_rank0(ranks_, sim_->profile().phase_seconds());
  }

 private:
  void call(RankOrder order, double value = 0.0, const SampleRegion& region = {},
            const FrameAsk& frame = {}) const {
    RankCall c{order, value, region, frame};
    ranks_.broadcast(c);
  }

  std::unique_ptr<Simulator<D>> sim_;
  RankTeam ranks_;
};

// The sampler a follower was given for the leader's looks; none is a logic error (the run
// builds one wherever its looks sample apart).
template <int D>
OwnSampler<D>& own_sampler(OwnSampler<D>* sampler) {
  if (sampler == nullptr)
    throw std::logic_error("the leader samples apart but this rank was given no sampler");
  return *sampler;
}

// A rank other than 0: makes each call the leader makes, until it is done. `archive`: the
// checkpoint a resumed run restores (this rank's read of it); `sampler`: this rank's part of
// what the leader's looks sample apart (Simulator::sample_own), if they do, whose own state
// lies in checkpoints under `sampler_state` (where rank 0's observer keeps the same).
template <int D>
void follow_leader(Simulator<D>& sim, const RankTeam& ranks, const StateArchive* archive,
                   OwnSampler<D>* sampler, const std::string& sampler_state = {}) {
  std::vector<std::byte> share;  // of the last checkpoint, until rank 0 takes it
  for (;;) {
    RankCall c;
    ranks.broadcast(c);
    switch (c.order) {
      case RankOrder::kAdvance:
        try {
          sim.advance_to(c.value);
        } catch (const BlowUpError&) {  // the leader reports it
        }
        break;
      case RankOrder::kParticles:
        sim.particles();
        break;
      case RankOrder::kGrainCount:
        sim.grain_count();
        break;
      case RankOrder::kParticlesIn:
        sim.particles_in(c.region);
        break;
      case RankOrder::kTransfers: {
        std::vector<PairImpulse<D>> ignored;
        sim.collect_transfers(ignored);
        break;
      }
      case RankOrder::kTransfersIn: {
        std::vector<PairImpulse<D>> ignored;
        sim.collect_transfers_in(ignored, c.region);
        break;
      }
      case RankOrder::kSampleOwn:
        sim.sample_own(c.region, c.value, own_sampler(sampler));
        break;
      case RankOrder::kJoinSamples:
        sim.join_samples(own_sampler(sampler));
        break;
      case RankOrder::kStats:
        sim.stats();
        break;
      case RankOrder::kForces: {
        ForceSample<D> ignored;
        sim.sample_forces(ignored);
        break;
      }
      case RankOrder::kEnergy:
        sim.energy();
        break;
      case RankOrder::kFrame: {
        NoFrame<D> ignored;
        sim.frame(c.frame, ignored);
        break;
      }
      case RankOrder::kCheckpoint: {
        StateArchive checkpoint;
        sim.checkpoint(checkpoint);
        if (sampler != nullptr) {
          StateWriter own(checkpoint, sampler_state);
          sampler->save_own(own);
        }
        share = share_bytes(checkpoint);
        break;
      }
      case RankOrder::kCheckpointShare:
        share_on_rank0(ranks, static_cast<int>(c.value), share);
        if (c.value == ranks.rank()) share = {};
        break;
      case RankOrder::kRestore:
        sim.restore(*archive);
        if (sampler != nullptr) {
          StateReader own(*archive, sampler_state);
          sampler->restore_own(own);
        }
        break;
      case RankOrder::kProfile:
        rows_on_rank0(ranks, sim.profile().phase_seconds());
        break;
      case RankOrder::kDone:
        return;
    }
  }
}

}  // namespace granjet
