// The pair part of the soft DEM's force pass, serial or shared among run.threads, and the
// update of the grains that ends it, in this order and in one parallel region (pass):
//  1. find_share: the listed pairs that touch (a distance test per pair, kept branch-free:
//     only ~5% of the pairs of a touching lattice overlap, and a branch per pair or per row
//     of varying length mispredicts), each with its grains and its history carried over
//     (ContactHistory);
//  2. evaluate_share: each contact's force and torques from its geometry and history, in
//     blocks of contacts held as columns (ContactTable), two vectorised loops per block;
//  3. ContactSums: every grain sums its contacts in list order (the rows k < i that list it,
//     then its own row), one fixed order whatever the thread count, so the same roundings and
//     the same bits. One thread runs it inside 2, block by block; a team runs it after 2, each
//     thread for the grains of its own rows (sum_share), so no two threads write one grain;
//  4. the simulator adds the plate's forces, then update_share moves the grains: those with a
//     force at this pass or the last (contacts, plate, tether; `forced` flags) are listed and
//     advanced one by one with their total force; the others fly free, in one straight loop
//     over all the grains that leaves the pushed ones as they are, and the forced bits age.
// Phases 1 to 4 are shared among threads, with nothing over all grains or contacts left to one;
// each shared loop is cut where the last pass's times say its threads finish together
// (core/balanced_split.hpp), since contacts and pushed grains crowd into the impact region.
// docs/performance.md says why the loops look as they do (plain LaneVec columns, no Eigen in them,
// selects instead of branches).
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "core/balanced_split.hpp"
#include "core/dim.hpp"
#include "core/neighbour_list.hpp"
#include "core/omp_team.hpp"
#include "core/particles.hpp"
#include "core/phase_profile.hpp"
#include "soft_dem/contact_geometry.hpp"
#include "soft_dem/contact_history.hpp"
#include "soft_dem/contact_table.hpp"
#include "soft_dem/integrators.hpp"
#include "soft_dem/lane_vec.hpp"

namespace granjet::dem {

// kMono: every grain has the radius of the first (no radius lookups); Space: how separations
// are taken (core/space.hpp).
template <int D, class Law, bool kMono, class Space>
class ForcePass {
 public:
  using History = ContactHistory<D, Law::kNeedsHistory>;
  using Table = ContactTable<D, Law::kNeedsRotation, rolls<Law>>;

  // Where the contacts' forces go, per grain: raw pointers (see ContactSums). Bit 0 of forced
  // is set for a grain that gets a force.
  struct Sums {
    Vec<D>* force;
    Spin<D>* torque;
    std::uint8_t* forced;
  };

  // profile: where its phases' wall times go (none: not timed).
  ForcePass(int threads, double overlap_limit, PhaseProfile* profile = nullptr)
      : threads_(threads),
        overlap_limit_(overlap_limit),
        profile_(profile),
        split_test_(threads),
        split_join_(threads),
        split_contacts_(threads),
        split_coast_(threads),
        split_advance_(threads) {
    if (profile_ == nullptr) return;
    using Kind = PhaseProfile::Kind;
    phase_.test = profile_->phase("contacts: distance test, history carry-over", Kind::kParallel);
    phase_.forces = profile_->phase("contacts: forces and sums", Kind::kParallel);
    phase_.update = profile_->phase("grains: update", Kind::kParallel);
  }

  // What the passes' loops over listed items took since the last take (each loop's threads'
  // times summed): the pairs tested (phase 1's distance test), the contacts (phase 1's join and
  // carry-over, 2 and 3) and the pushed grains (phase 4's advance); the loop over all grains is
  // not among them. Over MPI ranks they weigh each grain's share of a rank's pass
  // (DemSimulator::grain_weights).
  struct LoopSeconds {
    double pairs = 0.0, contacts = 0.0, pushed = 0.0;
  };
  LoopSeconds take_loop_seconds() { return std::exchange(loop_seconds_, {}); }

  // Whether each grain was pushed at the last pass (a force at it or at the one before, or a
  // tethered wall grain): the others coasted.
  std::span<const std::uint8_t> pushed() const { return pushed_; }

  // The listed pairs in contact at the last evaluation and their history.
  History& history() { return history_; }
  const History& history() const { return history_; }

  // What a pass found: the first contact (in list order) whose overlap is beyond the limit of
  // the smaller radius (the number of contacts if none), and the largest value that advance or
  // coast returned.
  struct Outcome {
    std::size_t first_too_deep;
    double largest;
  };

  // Phases 1 to 4 in one parallel region. With a tethered wall every thread of the team runs
  // before() at its start, ahead of the contacts' sums (the tether forces), and it runs between()
  // once every grain has its contacts' forces, before the update (the plate's forces); each
  // hook may hold worksharing loops, each ending in a barrier. Phase 4: the grains with a force at
  // this pass or the last (target.forced bits, or a tethered wall grain, which feels its springs)
  // are pushed: advance(i) for each; coast(pushed, begin, end) moves the others of [begin, end)
  // (pushed[i] == 0). Each thread calls look(begin, end) on its range of grains, the last look
  // at this pass's forced bits, before they age for the next pass: bit 0 (a force at this
  // pass) becomes bit 1.
  template <class Before, class Between, class Advance, class Coast, class Look>
  [[gnu::flatten]]  // the contact law, the geometry and the grain update inlined into the loops
  Outcome
  pass(const Law& law, const Particles<D>& p, const PairList& pairs,
       const std::vector<std::uint32_t>& pair_row, std::span<const std::uint32_t> tested,
       const Space& space, const Sums& target, Before&& before, Between&& between,
       std::span<const GrainKind> kinds, bool tethered_wall, Advance&& advance, Coast&& coast,
       Look&& look) {
    found_.resize(threads_);
    span_.assign(threads_, 0);
    pushed_.resize(kinds.size());
    pushed_grains_.resize(threads_);
    // count[t + 1]: stretch t's contacts, then where the stretch after it starts
    std::vector<std::size_t> count(threads_ + 1, 0);
    std::vector<std::int64_t> pushed_count(threads_, 0);
    std::vector<double> thread_largest(threads_, 0.0);
    bool any_too_deep = false;  // the first such contact is looked for only then
    // (With a tethered wall the hook times itself from the fork on.)
    std::optional<PhaseProfile::Timer> timing;
    if (!tethered_wall) timing.emplace(profile_, phase_.test);
    std::atomic<int> sized = 0;  // find_share's threads that have counted their contacts
#pragma omp parallel num_threads(threads_) reduction(| : any_too_deep) if (threads_ > 1)
    {
      const int t = team_index();
      if (tethered_wall) {
        before();
        if (t == 0) timing.emplace(profile_, phase_.test);
      }
      find_share(p, pairs, pair_row, tested, space, count, sized);
#pragma omp barrier  // the join and carry-over are complete
      const auto contacts = static_cast<std::int64_t>(count[team_size()]);
      const std::int64_t span = *std::max_element(span_.begin(), span_.end());  // largest j - i
      if (t == 0) timing.emplace(profile_, phase_.forces);
      any_too_deep |= evaluate_share(law, p, space, contact_sums(target), contacts, span);
#pragma omp barrier  // every grain has its contacts' forces
      if (t == 0) timing.reset();
      between();
      if (t == 0) timing.emplace(profile_, phase_.update);
      thread_largest[t] =
          update_share(target.forced, kinds, tethered_wall, pushed_count, advance, coast, look);
    }
    timing.reset();
    history_.finish_carry(found_pair_);
    loop_seconds_.pairs += split_test_.seconds();
    loop_seconds_.contacts += split_join_.seconds() + split_contacts_.seconds();
    loop_seconds_.pushed += split_advance_.seconds();
    split_test_.rebalance(profile_, phase_.test);
    split_join_.rebalance(profile_, phase_.test);
    split_contacts_.rebalance(profile_, phase_.forces);
    split_coast_.rebalance(profile_, phase_.update);
    split_advance_.rebalance(profile_, phase_.update);
    Outcome outcome{history_.size(), 0.0};
    for (double value : thread_largest) outcome.largest = sticky_max(outcome.largest, value);
    if (any_too_deep)
      for (std::size_t c = 0; c < history_.size(); ++c) {
        const double radius_i = radius_of(p.radius(), contact_i_[c]);
        const double radius_j = radius_of(p.radius(), contact_j_[c]);
        if (contacts_.overlap(c) > overlap_limit_ * std::min(radius_i, radius_j)) {
          outcome.first_too_deep = c;
          break;
        }
      }
    return outcome;
  }

 private:
  static double radius_of(std::span<const double> radius, std::size_t i) {
    if constexpr (kMono) return radius[0];
    return radius[i];
  }

  // Geometry and relative velocity of contacts [begin, end) into contacts_; whether any
  // overlaps beyond the limit. A plain loop inside the OpenMP loop over blocks: GCC vectorises
  // gathers there, not in an OpenMP loop itself. The grains' vectors are read as plain doubles
  // (see LaneVec::at).
  bool gather_contacts(const Particles<D>& p, const Space& space, std::int64_t begin,
                       std::int64_t end) {
    constexpr int kSpinWidth = Table::kSpinWidth;
    static_assert(sizeof(Vec<D>) == D * sizeof(double) &&
                  sizeof(Spin<D>) == kSpinWidth * sizeof(double));
    using Lane = LaneVec<D>;
    const auto spin_at = [](const double* base, std::int64_t k) {
      if constexpr (kSpinWidth == 1)
        return base[k];  // 2D: a scalar
      else
        return LaneVec<kSpinWidth>::at(base, k);
    };
    const double* x = p.position().data()->data();
    const double* v = p.velocity().data()->data();
    const double* w = reinterpret_cast<const double*>(p.spin().data());
    const double* radius = p.radius().data();
    const std::int64_t* grain_i = contact_i_.data();
    const std::int64_t* grain_j = contact_j_.data();
    // An or as wide as a double, which the vectoriser keeps in lanes (a bool or a first index
    // stops it).
    std::int64_t too_deep = 0;
#pragma GCC ivdep
    for (std::int64_t c = begin; c < end; ++c) {
      const std::int64_t i = grain_i[c], j = grain_j[c];
      const Lane r_ij = space.separation(Lane::at(x, i), Lane::at(x, j));
      const double radius_i = kMono ? radius[0] : radius[i];
      const double radius_j = kMono ? radius[0] : radius[j];
      const ContactGeometryOf<Lane> g =
          contact_geometry(r_ij, std::sqrt(r_ij.squaredNorm()), radius_i, radius_j);
      contacts_.set(c, g,
                    dem::relative_velocity<Law::kNeedsRotation>(Lane::at(v, i), Lane::at(v, j),
                                                                spin_at(w, i), spin_at(w, j), g));
      if constexpr (rolls<Law>) contacts_.set_relative_spin(c, spin_at(w, i) - spin_at(w, j));
      too_deep |= std::int64_t{g.overlap > overlap_limit_ * std::min(radius_i, radius_j)};
    }
    return too_deep != 0;
  }

  // Adds contact c's force and torques to its two grains and flags them. Raw pointers: Eigen
  // stores through may-alias vector types, after which a pointer read from a member would have
  // to be read again.
  struct ContactSums {
    const std::int64_t* grain_i;
    const std::int64_t* grain_j;
    ColumnsView<D> contact_force;
    ColumnsView<Table::kSpinWidth> contact_torque_i, contact_torque_j;
    Vec<D>* force;
    Spin<D>* torque;
    std::uint8_t* forced;

    void add(std::size_t c) const {
      add_i(c);
      add_j(c);
    }
    // Its part for grain i only, or j only.
    void add_i(std::size_t c) const {
      const std::int64_t i = grain_i[c];
      forced[i] |= 1;
      force[i] += contact_force.template get<Vec<D>>(c);
      if constexpr (Law::kNeedsRotation) torque[i] -= contact_torque_i.template get<Spin<D>>(c);
    }
    void add_j(std::size_t c) const {
      const std::int64_t j = grain_j[c];
      forced[j] |= 1;
      force[j] -= contact_force.template get<Vec<D>>(c);
      if constexpr (Law::kNeedsRotation) torque[j] -= contact_torque_j.template get<Spin<D>>(c);
    }
  };
  ContactSums contact_sums(const Sums& target) const {
    return {contact_i_.data(),     contact_j_.data(), contacts_.forces(), contacts_.torques_i(),
            contacts_.torques_j(), target.force,      target.torque,      target.forced};
  }

  // Phase 1, one thread's part, over the listed pairs `tested` (increasing indices;
  // soft_dem/quiet_pairs.hpp says which others cannot touch). Each thread tests a contiguous
  // stretch of them; then the threads copy the contacts into their place in the joined list and
  // carry their histories over (finish_carry is left to the caller). The index of every pair is
  // written and the count advances only for a contact: no branch. A non-finite separation
  // counts as apart (the simulator's check reports it). count and sized: the team's, zero on
  // entry; the last thread to count sizes the joined list.
  void find_share(const Particles<D>& p, const PairList& pairs,
                  const std::vector<std::uint32_t>& pair_row, std::span<const std::uint32_t> tested,
                  const Space& space, std::vector<std::size_t>& count, std::atomic<int>& sized) {
    const std::size_t listed = tested.size();
    // Every pair, tested[k] == k: read straight through (the loop is unswitched on this).
    const bool every = listed == pairs.size();
    const std::uint32_t* index = tested.data();
    const Vec<D>* x = p.position().data();
    const double* radius = p.radius().data();
    const std::uint32_t* row = pair_row.data();
    const std::uint32_t* partner = pairs.partner.data();
    const int t = team_index(), team = team_size();
    const auto start = std::chrono::steady_clock::now();
    const auto [begin, end] = split_test_.share(t, team, static_cast<std::int64_t>(listed));
    std::vector<std::uint32_t>& out = found_[t];
    const auto length = static_cast<std::size_t>(end - begin);
    if (out.size() < length) out.resize(length);
    std::uint32_t* slot = out.data();
    std::size_t touching = 0;
    for (std::int64_t m = begin; m < end; ++m) {
      const std::uint32_t k = every ? static_cast<std::uint32_t>(m) : index[m];
      const std::uint32_t i = row[k], j = partner[k];
      const double reach = kMono ? 2.0 * radius[0] : radius[i] + radius[j];
      const double d2 = space.separation(x[i], x[j]).squaredNorm();
      slot[touching] = k;
      touching += d2 < reach * reach;
    }
    count[t + 1] = touching;
    split_test_.record(t, seconds_since(start));
    on_last_arrival(sized, [&] {
      for (int s = 0; s < team; ++s) count[s + 1] += count[s];  // where each stretch starts
      const std::size_t total = count[team];
      found_pair_.resize(total);
      history_.prepare_carry(total);
      contact_i_.resize(total);
      contact_j_.resize(total);
      contacts_.resize(total);
    });  // the joined list is sized
    // The join and carry-over are shared anew: the contacts crowd into some stretches.
    const auto joining = std::chrono::steady_clock::now();
    const auto [first, last] = split_join_.share(t, team, static_cast<std::int64_t>(count[team]));
    int s = 0;              // the stretch that found contact c
    std::int64_t span = 0;  // a local, stored once: the threads' slots share a cache line
    for (std::int64_t c = first; c < last; ++c) {
      while (c >= static_cast<std::int64_t>(count[s + 1])) ++s;
      const std::uint32_t k = found_[s][c - count[s]];
      found_pair_[c] = k;
      contact_i_[c] = row[k];
      contact_j_[c] = partner[k];
      span = std::max(span, contact_j_[c] - contact_i_[c]);
    }
    span_[t] = span;
    history_.carry(found_pair_, first, last);
    split_join_.record(t, seconds_since(joining));
  }

  // Phases 2 and 3, one thread's part: the forces and torques of its share of the `contacts`
  // (largest j - i: span), added to their grains through `sums`. Whether any of its contacts
  // overlaps beyond the limit of the smaller radius.
  bool evaluate_share(const Law& law, const Particles<D>& p, const Space& space,
                      const ContactSums& sums, std::int64_t contacts, std::int64_t span) {
    // Blocks of contacts small enough that their columns stay in the first-level cache from the
    // geometry through the law to the sums.
    constexpr std::int64_t kBlock = 32;
    bool too_deep = false;
    const int t = team_index(), team = team_size();
    auto start = std::chrono::steady_clock::now();
    const auto [begin, end] = split_contacts_.share(t, team, contacts, kBlock);
    for (std::int64_t block_begin = begin; block_begin < end; block_begin += kBlock) {
      const std::int64_t block_end = std::min(end, block_begin + kBlock);
      too_deep |= gather_contacts(p, space, block_begin, block_end);
      contacts_.apply(law, history_.shear(), block_begin, block_end);
      // Alone, the thread sums each block as it goes: that is list order.
      if (team == 1)
        for (std::int64_t c = block_begin; c < block_end; ++c) sums.add(c);
    }
    double seconds = seconds_since(start);
    if (team > 1) {
#pragma omp barrier
      start = std::chrono::steady_clock::now();
      sum_share(sums, t, team, static_cast<std::int64_t>(p.size()), contacts, span, kBlock);
      seconds += seconds_since(start);
    }
    split_contacts_.record(t, seconds);
    return too_deep;
  }

  // Phase 3 among threads, one thread's part: the sums of the grains it owns, those from the
  // first row of its stretch of contacts to the first row of the next (the grains whose own rows
  // it evaluated, so mostly its own contacts' results). Each grain's parts come in list order:
  // the thread walks the contacts that can reach its grains, those of the span rows before
  // them and of their own rows, in order, and takes the part of each grain of its own.
  void sum_share(const ContactSums& sums, int t, int team, std::int64_t n, std::int64_t contacts,
                 std::int64_t span, std::int64_t block) const {
    const std::int64_t* grain_i = contact_i_.data();
    const std::int64_t* grain_j = contact_j_.data();
    const auto first_grain = [&](int s) -> std::int64_t {  // of thread s
      if (s == 0) return 0;
      if (s == team) return n;
      const std::int64_t c = split_contacts_.share(s, team, contacts, block).first;
      return c < contacts ? grain_i[c] : n;
    };
    const std::int64_t own_begin = first_grain(t), own_end = first_grain(t + 1);
    if (own_begin >= own_end) return;
    // Contacts come in row order, and j - i <= span.
    const std::int64_t c_begin =
        std::lower_bound(grain_i, grain_i + contacts, own_begin - span) - grain_i;
    const std::int64_t c_end = std::lower_bound(grain_i, grain_i + contacts, own_end) - grain_i;
    for (std::int64_t c = c_begin; c < c_end; ++c) {
      if (grain_i[c] >= own_begin) sums.add_i(c);
      const std::int64_t j = grain_j[c];
      if (j >= own_begin && j < own_end) sums.add_j(c);
    }
  }

  // Phase 4, one thread's part (see pass): returns the largest value advance or coast returned.
  // Each thread flags and lists the pushed grains of its own range, in index order, without a
  // branch (whether a grain in a jet touches another is as good as random, and one branch per
  // grain on it mispredicts), and moves the coasting ones; then the threads share out all the
  // lists. pushed_count: the team's, one slot per thread.
  template <class Advance, class Coast, class Look>
  double update_share(std::uint8_t* forced, std::span<const GrainKind> kinds, bool tethered_wall,
                      std::vector<std::int64_t>& pushed_count, Advance&& advance, Coast&& coast,
                      Look&& look) {
    const auto n = static_cast<std::int64_t>(kinds.size());
    const GrainKind* kind = kinds.data();
    const unsigned tethered = tethered_wall;
    std::uint8_t* pushed = pushed_.data();
    const int t = team_index(), team = team_size();
    auto start = std::chrono::steady_clock::now();
    const auto [begin, end] = split_coast_.share(t, team, n);
    for (std::int64_t i = begin; i < end; ++i)
      pushed[i] = (forced[i] | (tethered & (kind[i] == GrainKind::kWall))) != 0;
    look(begin, end);
    for (std::int64_t i = begin; i < end; ++i)  // bits 2 and up stay: a grain's lasting marks
      forced[i] = static_cast<std::uint8_t>(((forced[i] & 1) << 1) | (forced[i] & ~3));
    std::vector<std::uint32_t>& listed = pushed_grains_[t];
    listed.resize(end - begin);
    std::int64_t count = 0;
    for (std::int64_t i = begin; i < end; ++i) {
      listed[count] = static_cast<std::uint32_t>(i);
      count += pushed[i];
    }
    pushed_count[t] = count;
    double largest = coast(pushed, begin, end);
    split_coast_.record(t, seconds_since(start));
    // coast stores every grain of its range, the pushed ones unchanged, and the pushed grains
    // cluster in some ranges (the impact region): the threads share out all the lists after.
#pragma omp barrier
    std::int64_t total = 0;
    for (std::int64_t count_of : pushed_count) total += count_of;
    // This thread's share of the joined lists: entry k of list s, onwards.
    start = std::chrono::steady_clock::now();
    const auto [first, last] = split_advance_.share(t, team, total);
    std::int64_t k = first;
    int s = 0;
    for (std::int64_t m = first; m < last; ++m) {
      while (k >= pushed_count[s]) k -= pushed_count[s++];
      largest = sticky_max(largest, advance(pushed_grains_[s][k++]));
    }
    split_advance_.record(t, seconds_since(start));
    return largest;
  }

  int threads_;
  double overlap_limit_;
  PhaseProfile* profile_;
  struct {
    int test = 0, forces = 0, update = 0;
  } phase_;
  History history_;
  Table contacts_;
  std::vector<std::int64_t> contact_i_, contact_j_;  // the grains, 64-bit: vectorised gathers
  // find_share's scratch: each thread's stretch of the list, and their join; the largest
  // j - i of each stretch's contacts.
  std::vector<std::vector<std::uint32_t>> found_;
  std::vector<std::uint32_t> found_pair_;
  std::vector<std::int64_t> span_;
  // update_share's scratch: whether each grain is pushed (a force at this pass or the last), and
  // each thread's list of those that are.
  std::vector<std::uint8_t> pushed_;
  std::vector<std::vector<std::uint32_t>> pushed_grains_;
  // How each shared loop is split among the threads, balanced by the times of the last pass.
  BalancedSplit split_test_, split_join_, split_contacts_, split_coast_, split_advance_;
  LoopSeconds loop_seconds_;
};

}  // namespace granjet::dem
