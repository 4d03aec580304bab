// Which listed pairs the force pass must test for contact. A jet flies as a lattice whose
// neighbours are 1e-9 d apart (core/initial_state.cpp), so most of its listed pairs join grains
// that have not touched anything yet and share one velocity, bit for bit. Such a grain is quiet:
// no force at the last pass (nor at this one, checked after it), so its velocity stays and
// every quiet grain moves by the same increment each step; the separation of two of them
// changes only by the rounding of their positions, at most sqrt(D) 2^-52 max|x| per step. A pair of
// quiet grains apart by more than that drift over kMaxAge passes cannot touch within them while
// both stay quiet, so the pass skips it. A quiet grain can only be pushed through a tested pair (a
// partner that is not quiet) or the plate; once one is, the classification is redone before the
// next pass. The contacts found are the same ones in the same order, so results are bit-identical.
//
// Only grains whose listed partners are all quiet, kMargin times over, are trusted (eroded
// inwards from the quiet region's edge): the impact's compression wave then has to cross a few
// layers of tested pairs before it pushes a trusted grain and forces a new classification.
//
// A neighbour rebuild keeps the trusted grains while none of them has been pushed since they were
// classified: they are still quiet, so the rebuild carries their marks along as it reorders the
// grains (gather, compact) and only the skip test runs again, on the new list from the positions
// of now (relist). The vote and the margin's sweeps over all pairs, most of a classification's
// cost, come only when a trusted grain is pushed.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include "core/balanced_split.hpp"
#include "core/dim.hpp"
#include "core/neighbour_list.hpp"
#include "core/omp_team.hpp"
#include "core/particles.hpp"
#include "core/phase_profile.hpp"

namespace granjet::dem {

template <int D>
class QuietPairs {
 public:
  // Passes a listing of the pairs to test serves at most, from a classification or a rebuild's
  // relisting (the drift bound above grows with it).
  static constexpr int kMaxAge = 128;
  static constexpr int kMargin = 3;

  // threads: how many share the last pass over the pairs (the same list for any count);
  // profile: where its phases' wall times go (none: not timed).
  explicit QuietPairs(int threads = 1, PhaseProfile* profile = nullptr)
      : threads_(threads), profile_(profile), split_skip_(threads) {
    if (profile_ == nullptr) return;
    phase_classify_ = profile_->phase("quiet pairs: classify", PhaseProfile::Kind::kParallel);
    phase_relist_ =
        profile_->phase("quiet pairs: kept over a rebuild", PhaseProfile::Kind::kParallel);
  }

  // The listed pairs to test (increasing pair-list indices), for the pass about to run.
  std::span<const std::uint32_t> tested() const { return {tested_.data(), tested_count_}; }
  // Whether the classification still holds for the next pass.
  bool fresh() const { return age_ < kMaxAge; }
  // Whether the trusted grains are still quiet: none was pushed since they were classified.
  bool trust_holds() const { return trust_holds_; }
  // The list classified is gone (a rebuild that keeps nothing, or grains replaced).
  void expire() {
    age_ = kMaxAge;
    trust_holds_ = false;
    tested_count_ = 0;
  }

  // A rebuild's reordering of the grains, applied to their marks while the trust holds: grain k
  // becomes grain order[k] (Particles::gather), or the moves of Particles::compaction leave `kept`
  // grains followed by `arrived` ones from other ranks, which are not trusted here.
  void gather(std::span<const std::uint32_t> order, int threads = 1) {
    if (trust_holds_) Particles<D>::gather_one(trusted_, order, threads);
  }
  void compact(const typename Particles<D>::Moves& moves, std::size_t kept, std::size_t arrived) {
    if (!trust_holds_) return;
    Particles<D>::compact_one(trusted_, moves, kept, arrived);
    trusted_.resize(kept + arrived, 0);
  }

  // Classifies the pairs of `pairs` (rows pair_row) at the start of a pass. force_before: each
  // grain's force at the last pass (a grain with none moves this pass as if it coasted, whatever
  // its forced bits say); reach(i, j): the sum of the radii; step: the time step (a coasting
  // grain moves by step times its velocity); owned: over MPI ranks, the grains held here that
  // are not ghosts, the only ones trusted (a ghost's partners beyond the halo are not listed
  // here, so no margin around it can be known; empty: every grain may be). The threads share
  // every sweep; the pairs to test come out the same for any thread count whenever a majority
  // velocity exists (and are always the pairs that can touch).
  template <class Space, class Reach>
  void classify(const Particles<D>& p, std::span<const Vec<D>> force_before, const PairList& pairs,
                std::span<const std::uint32_t> pair_row, const Space& space, double step,
                Reach&& reach, std::span<const std::uint8_t> owned = {}) {
    const auto n = static_cast<std::int64_t>(p.size());
    const auto listed = static_cast<std::int64_t>(pairs.size());
    const Vec<D>* x = p.position().data();
    const Vec<D>* v = p.velocity().data();
    const GrainKind* kind = p.kind().data();
    const Vec<D>* f = force_before.data();
    const std::uint32_t* row = pair_row.data();
    const std::uint32_t* partner = pairs.partner.data();
    const PhaseProfile::Timer timing(profile_, phase_classify_);
    begin_listing(listed);
    trust_holds_ = true;
    trusted_.resize(n);
    next_.resize(n);
    // Per thread: its range's majority candidate and how many grains of its range have each
    // thread's candidate.
    std::vector<Vec<D>> candidate(threads_, Vec<D>::Zero());
    std::vector<std::int64_t> tally(threads_ * threads_, 0);
    Vec<D>& shared = shared_;
    shared.setZero();
    double largest = 0.0;    // max |x| over the grains
    std::int64_t quiet = 0;  // trusted grains before the margin
    // firstprivate: each thread's own copies of the pointers stay in registers; shared ones
    // would be read again after every byte store, which may alias anything.
#pragma omp parallel num_threads(threads_) if (threads_ > 1) \
    firstprivate(x, v, kind, f, row, partner)
    {
      const int t = team_index(), team = team_size();
      const std::int64_t first = n * t / team, last = n * (t + 1) / team;
      const auto coasts = [&](std::int64_t i) {
        return kind[i] == GrainKind::kFree && f[i].isZero(0.0);
      };
      // The shared velocity: the one most grains without a force have, if more than half of
      // them have one. A majority of all is one of some range, which Boyer and Moore's vote
      // finds there; the candidate with the most grains overall wins (the lowest range on a
      // tie). Another choice only skips fewer pairs.
      std::int64_t votes = 0;
      for (std::int64_t i = first; i < last; ++i) {
        if (!coasts(i)) continue;
        if (votes == 0) candidate[t] = v[i];
        votes += v[i] == candidate[t] ? 1 : -1;
      }
#pragma omp barrier
      if (team > 1) {                             // alone, the one candidate wins
        std::vector<std::int64_t> mine(team, 0);  // a local: the threads' rows share cache lines
        for (std::int64_t i = first; i < last; ++i)
          if (coasts(i))
            for (int s = 0; s < team; ++s) mine[s] += v[i] == candidate[s];
        std::copy(mine.begin(), mine.end(), tally.begin() + t * team);
      }
#pragma omp barrier
#pragma omp single
      {
        std::int64_t best = -1;
        for (int s = 0; s < team; ++s) {
          std::int64_t total = 0;
          for (int u = 0; u < team; ++u) total += tally[u * team + s];
          if (total > best) {
            best = total;
            shared = candidate[s];
          }
        }
      }
#pragma omp for schedule(static) reduction(+ : quiet) reduction(max : largest)
      for (std::int64_t i = 0; i < n; ++i) {
        trusted_[i] = coasts(i) && v[i] == shared && (owned.empty() || owned[i] != 0);
        quiet += trusted_[i];
        largest = std::max(largest, x[i].cwiseAbs().maxCoeff());
      }
      if (!skips(quiet, n)) {
        test_every(listed);
      } else {
        for (int layer = 0; layer < kMargin; ++layer) {
          // A grain stays trusted while all its partners are: the stores only clear, so the
          // threads may share the pairs (relaxed byte stores, in any order).
          const std::uint8_t* now = trusted_.data();  // raw: a byte store may alias anything
          std::uint8_t* next = next_.data();
#pragma omp for schedule(static)
          for (std::int64_t i = 0; i < n; ++i) next[i] = now[i];
          // Without a branch (untrusted grains come in no order a predictor learns): the zero
          // goes to the grain or, when its partner is trusted, to a byte of the thread's own.
          std::uint8_t ignored = 0;
#pragma omp for schedule(static)
          for (std::int64_t k = 0; k < listed; ++k) {
            const std::uint32_t i = row[k], j = partner[k];
            std::atomic_ref<std::uint8_t>(now[j] != 0 ? ignored : next[i])
                .store(0, std::memory_order_relaxed);
            std::atomic_ref<std::uint8_t>(now[i] != 0 ? ignored : next[j])
                .store(0, std::memory_order_relaxed);
          }
#pragma omp single
          trusted_.swap(next_);
        }
        list_share(listed, row, partner, x, space, drift(largest, step), reach);
      }
    }
    end_listing(skips(quiet, n), phase_classify_);
  }

  // After a rebuild that kept the trusted grains (trust_holds, gather, compact): the pairs of
  // the new list (rows pair_row) to test, from the positions of now, for the next kMaxAge passes
  // at most. owned: over MPI ranks, the grains held here that are not ghosts (a kept grain may
  // have become a ghost here); empty: every grain may be.
  template <class Space, class Reach>
  void relist(const Particles<D>& p, const PairList& pairs, std::span<const std::uint32_t> pair_row,
              const Space& space, double step, Reach&& reach,
              std::span<const std::uint8_t> owned = {}) {
    const auto n = static_cast<std::int64_t>(p.size());
    const auto listed = static_cast<std::int64_t>(pairs.size());
    if (!trust_holds_ || trusted_.size() != p.size())
      throw std::logic_error(
          "QuietPairs::relist: the trusted grains were not kept over the rebuild");
    const Vec<D>* x = p.position().data();
    const std::uint32_t* row = pair_row.data();
    const std::uint32_t* partner = pairs.partner.data();
    const PhaseProfile::Timer timing(profile_, phase_relist_);
    begin_listing(listed);
    std::uint8_t* trusted = trusted_.data();
    double largest = 0.0;
    std::int64_t trusted_count = 0;
#pragma omp parallel num_threads(threads_) if (threads_ > 1) firstprivate(x, row, partner, trusted)
    {
#pragma omp for schedule(static) reduction(+ : trusted_count) reduction(max : largest)
      for (std::int64_t i = 0; i < n; ++i) {
        if (!owned.empty()) trusted[i] &= owned[i];
        trusted_count += trusted[i];
        largest = std::max(largest, x[i].cwiseAbs().maxCoeff());
      }
      if (!skips(trusted_count, n))
        test_every(listed);
      else
        list_share(listed, row, partner, x, space, drift(largest, step), reach);
    }
    end_listing(skips(trusted_count, n), phase_relist_);
  }

  // After the pass's forces are summed (forced bit 0: pushed at this pass): whether a trusted
  // grain of [begin, end) was pushed. The threads look at ranges of their own; after_pass
  // takes whether any was.
  bool trusted_pushed(std::span<const std::uint8_t> forced, std::size_t begin,
                      std::size_t end) const {
    std::uint8_t pushed = 0;
    for (std::size_t i = begin; i < end; ++i) pushed |= trusted_[i] & forced[i];
    return (pushed & 1) != 0;
  }
  // The classification ends if a trusted grain was pushed, and ages by a pass otherwise.
  void after_pass(bool trusted_pushed) {
    age_ = trusted_pushed ? kMaxAge : age_ + 1;
    trust_holds_ = trust_holds_ && !trusted_pushed;
  }

 private:
  // Too few trusted grains to skip much (a gas: only the vote's winner): every pair is tested.
  static bool skips(std::int64_t trusted, std::int64_t grains) { return 8 * trusted >= grains; }

  // A fresh list of `listed` pairs, for kMaxAge passes.
  void begin_listing(std::int64_t listed) {
    age_ = 0;
    // Only grown: shrinking to the kept count and growing back would fill the tail anew, on one
    // thread, at every classification.
    if (tested_.size() < static_cast<std::size_t>(listed)) tested_.resize(listed);
    tested_count_ = listed;
    kept_.resize(threads_);
    kept_count_.assign(threads_ + 1, 0);
  }
  void end_listing(bool skipped, int phase) {
    if (!skipped) return;
    split_skip_.rebalance(profile_, phase);
    std::size_t total = 0;
    for (std::size_t count : kept_count_) total += count;
    tested_count_ = total;
  }

  // Inside the team's parallel region: every pair is tested.
  void test_every(std::int64_t listed) {
#pragma omp for schedule(static)
    for (std::int64_t k = 0; k < listed; ++k) tested_[k] = static_cast<std::uint32_t>(k);
  }

  // The drift of a separation over kMaxAge steps, with the coordinates (largest: max |x| over the
  // grains) grown by as many steps (twice over: the increment is rounded too), and room for the
  // rounding of the contact test itself.
  double drift(double largest, double step) const {
    const double reach_of_x = largest + 2.0 * kMaxAge * step * shared_.cwiseAbs().maxCoeff();
    return 2.0 * kMaxAge * std::sqrt(double{D}) * 0x1p-52 * reach_of_x;
  }

  // Inside the team's parallel region: the pairs to test, all but those of two trusted grains
  // apart by more than their reach and the drift. Each thread lists the kept pairs of its
  // stretch, then copies them to their place in the joined list; the first thread's place is
  // the list's start, where it lists them. The stretches are cut by the last listing's times:
  // the skip test costs little where a partner is untrusted, a distance where both are trusted.
  template <class Space, class Reach>
  void list_share(std::int64_t listed, const std::uint32_t* row, const std::uint32_t* partner,
                  const Vec<D>* x, const Space& space, double drift, Reach&& reach) {
    const int t = team_index(), team = team_size();
    const auto start = std::chrono::steady_clock::now();
    const auto [begin, end] = split_skip_.share(t, team, listed);
    std::vector<std::uint32_t>& scratch = kept_[t];
    if (t > 0) scratch.resize(end - begin);
    std::uint32_t* kept = t > 0 ? scratch.data() : tested_.data();
    std::size_t count = 0;
    const std::uint8_t* trusted = trusted_.data();
    for (std::int64_t k = begin; k < end; ++k) {
      const std::uint32_t i = row[k], j = partner[k];
      const double apart = reach(i, j) * (1.0 + 0x1p-40) + drift;
      const bool skip = (trusted[i] & trusted[j]) != 0 &&
                        space.separation(x[i], x[j]).squaredNorm() > apart * apart;
      kept[count] = static_cast<std::uint32_t>(k);
      count += !skip;
    }
    kept_count_[t + 1] = count;
    split_skip_.record(t, seconds_since(start));
#pragma omp barrier
    std::size_t at = 0;
    for (int s = 0; s <= t; ++s) at += kept_count_[s];
    if (t > 0) std::copy(kept, kept + count, tested_.begin() + at);
  }

  int threads_;
  PhaseProfile* profile_;
  int phase_classify_ = 0, phase_relist_ = 0;
  int age_ = kMaxAge;
  bool trust_holds_ = false;                  // no trusted grain pushed since the classification
  Vec<D> shared_ = Vec<D>::Zero();            // the velocity the quiet grains share
  std::vector<std::uint8_t> trusted_, next_;  // per grain: its pairs with trusted grains skip
  std::vector<std::uint32_t> tested_;         // the first tested_count_ are the pairs to test
  std::size_t tested_count_ = 0;
  // The listing's scratch: each thread's kept pairs, and their counts (from slot 1).
  std::vector<std::vector<std::uint32_t>> kept_;
  std::vector<std::size_t> kept_count_;
  BalancedSplit split_skip_;  // how the skip test is shared out
};

}  // namespace granjet::dem
