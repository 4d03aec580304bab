// The soft-sphere DEM backend: the force pass over a half neighbour list
// (soft_dem/force_pass.hpp), Adams-Bashforth-2 or velocity Verlet (soft_dem/integrators.hpp),
// the tethered or fixed target grains or the flat plate (soft_dem/plate.hpp), and removal of
// grains that leave the region; run.threads shares the pass out with bit-identical results.
// Law is the contact law (soft_dem/linear_spring_dashpot.hpp says what a law provides): its
// traits decide whether contact history is kept and whether grains turn, so a frictionless
// scene compiles without both. Grains all of one size go without radius lookups (kMono); the
// periodic gas scenes use minimum-image separations (Space = PeriodicBox), all others none.
// Given a team of several MPI ranks, the grains of an open-space scene are spread over them by
// space (soft_dem/domain.hpp) with the results of one rank; what looks at all grains is then
// collective, every rank calling it in the same order. energy() and stats() are the same on
// every rank; particles() and the samples, which only the output reads, are whole on rank 0
// and empty elsewhere; a frame comes to rank 0 one block of grain ids at a time, and a
// checkpoint one rank's share at a time.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "core/errors.hpp"
#include "core/id_index.hpp"
#include "core/neighbour_list.hpp"
#include "core/rank_team.hpp"
#include "core/scene.hpp"
#include "core/simulator.hpp"
#include "core/space.hpp"
#include "soft_dem/contact_geometry.hpp"
#include "soft_dem/domain.hpp"
#include "soft_dem/force_pass.hpp"
#include "soft_dem/integrators.hpp"
#include "soft_dem/plate.hpp"
#include "soft_dem/quiet_pairs.hpp"
#include "soft_dem/tethered_wall.hpp"
#include "soft_dem/work_balance.hpp"

namespace granjet::dem {

template <int D, class Law, bool kMono = false, class Space = OpenSpace<D>>
class DemSimulator final : public Simulator<D> {
 public:
  // initial: the scene's grains in id order; over several ranks, this rank's share of them
  // (build_initial_state's GrainShare: a part of the jet and the whole target).
  DemSimulator(const Scene& scene, Particles<D> initial, Space space = {}, RankTeam ranks = {});

  std::string_view backend() const override { return "soft_dem"; }
  // Steps until time() >= t: the state moves on whole steps of dt.
  void advance_to(double t) override;
  double time() const override { return static_cast<double>(step_) * dt_; }
  const Particles<D>& particles() const override;
  std::size_t grain_count() const override;
  const Particles<D>& particles_in(const SampleRegion& region) const override;
  double travel() const override { return travelled_ + travel_; }
  void collect_transfers(std::vector<PairImpulse<D>>& out) override;
  void collect_transfers_in(std::vector<PairImpulse<D>>& out, const SampleRegion& region) override;
  void sample_own(const SampleRegion& region, double elapsed, OwnSampler<D>& sampler) override;
  void join_samples(OwnSampler<D>& sampler) override;
  SimStats stats() const override;
  bool has_contact_forces() const override { return true; }
  void sample_forces(ForceSample<D>& out) const override;
  EnergyBalance energy() const override;
  void frame(const FrameAsk& ask, FrameSink<D>& sink) const override;
  void checkpoint(StateArchive& out) override;
  void restore(const StateArchive& in) override;

  double dt() const { return dt_; }

 private:
  static constexpr bool kRotation = Law::kNeedsRotation;
  using Pass = ForcePass<D, Law, kMono, Space>;
  using History = typename Pass::History::ByIds;
  using WallLaw = typename Law::Wall;

  // The simulator's own phases in the profile (the pass's and the quiet pairs' register theirs).
  struct Phases {
    int rebuild_ids, rebuild_sort, rebuild_moves, rebuild_pairs, rebuild_rows, tethers, plate,
        predictor, ghosts, agree;
  };
  static Phases register_phases(PhaseProfile& profile);
  PhaseProfile::Timer timer(int phase) { return {&this->profile(), phase}; }

  void step();
  void add_travel(double largest_speed2);
  // The integrators over the current arrays (rebuilds reorder them: take these after one).
  Ab2Step<D, kRotation> ab2_step();
  VerletStep<D, kRotation> verlet_step();
  // Evaluates all forces at the current state, then moves the grains (see force_pass.hpp):
  // advance(i) for each grain with a force at this pass or the last, coast(pushed, begin, end)
  // for the others; returns the largest value either returned.
  template <class Advance, class Coast>
  double force_pass(Advance&& advance, Coast&& coast);
  // The quiet pairs' classification (soft_dem/quiet_pairs.hpp), where due: once a trusted grain
  // was pushed, after a rebuild that could not keep the trusted grains, or kMaxAge passes after
  // the last listing. force_pass does it first; over ranks step() does it before, outside the
  // work the cut balances.
  void classify_quiet_pairs();
  // The tangential history of the touching pairs, by grain ids (indices change in rebuilds).
  std::vector<History> histories() const;
  void rebuild();
  // partners_elsewhere: a restore over ranks, whose histories may name a partner grain that
  // another rank read (see distribute).
  void rebuild(std::vector<History> history, bool partners_elsewhere = false);
  // Over ranks: the grains `region` holds (all for none) into whole_ on rank 0. Collective.
  void gather_whole(const SampleRegion* region) const;
  // Over ranks: the cell frame of all grains (CellGrid::Frame) for pairs of reach `cut`, and a
  // value combined over the ranks.
  typename CellGrid<D>::Frame whole_frame(double cut) const;
  static double over_all_ranks(const RankTeam& team, double value,
                               void (RankTeam::*combine)(std::span<double>) const) {
    (team.*combine)(std::span<double>(&value, 1));
    return value;
  }
  // weight: per grain held, compacted alike (empty: none).
  void remove_escaped(std::vector<double>& weight);
  BlowUpError overlap_error(std::size_t i, std::size_t j) const;
  // Over MPI ranks (soft_dem/dem_simulator_ranks.hpp). distribute: at a rebuild, moves the
  // grains to their owners and the ghosts to the ranks that need them, with the histories of
  // their contacts (those for the grains held here come back in `history`). weight: each grain's
  // share of this rank's pass, for a re-cut of the parts (grain_weights(), when the balance looks
  // at this rebuild). partners_elsewhere: a history whose second grain is not here goes to the
  // owner of its first, which then holds the second as a ghost and hands it on to its owner.
  void distribute(std::vector<History>& history, std::vector<double> weight,
                  bool partners_elsewhere = false);
  std::vector<double> grain_weights();
  GrainRecord<D> record_of(std::size_t i) const;
  // The contacts of the last pass in this rank's own rows.
  std::int64_t own_contacts() const;
  // The ghosts' state from their owners: after each pass (the moves of Adams-Bashforth-2, the
  // corrector of velocity Verlet; Verlet's predictor moves a ghost as its owner does).
  void update_ghosts();
  // What every rank must agree on after each step's moves: the largest squared speed of all
  // grains (returned), whether a trusted quiet grain was pushed, any blow-up a rank found
  // (raised on every rank) and a stop asked of any rank.
  double agree(double own_largest_speed2);
  void raise_together(const std::optional<BlowUpError>& mine) const;
  // Per-grain values of this rank's own grains, joined over all ranks in the order one rank
  // holds the grains (by the cell of the last rebuild, then id): on every rank, or only on rank
  // 0 (empty elsewhere) for what only the run's output reads.
  // for_each_in_whole_order hands them to visit(value) one by one, with no list of them built.
  // Only the grains whose cells lie in [cells_from, cells_to) when those are given.
  enum class Joined : std::uint8_t { kOnEveryRank, kOnRank0 };
  template <class Value, class Of, class Visit>
  void for_each_in_whole_order(Of&& value_of, Visit&& visit, Joined where,
                               std::uint64_t cells_from = 0,
                               std::uint64_t cells_to = UINT64_MAX) const;
  // The same on rank 0 for what only the run's output reads, in stretches of the cells that
  // hold at most `limit` values over all ranks (or a single cell): visit(value) for each value
  // of a stretch, then stretch_done() on every rank. Rank 0 holds one stretch at a time.
  template <class Value, class Of, class Visit, class Done>
  void for_each_stretch_in_whole_order(Of&& value_of, Visit&& visit, Done&& stretch_done,
                                       std::size_t limit) const;
  template <class Value, class Of>
  std::vector<Value> in_whole_order(Of&& value_of, Joined where = Joined::kOnEveryRank) const {
    std::vector<Value> out;
    for_each_in_whole_order<Value>(
        std::forward<Of>(value_of), [&](const Value& v) { out.push_back(v); }, where);
    return out;
  }
  template <class Value, class Of>
  std::vector<Value> in_whole_order_on_rank0(Of&& value_of) const {
    return in_whole_order<Value>(std::forward<Of>(value_of), Joined::kOnRank0);
  }
  // At the start or a resume: the first cut of the parts, over the ranks, from the grains each
  // rank starts with (mine: those it is to hand to their owners, each grain on one rank;
  // whole_index: each grain's place in the order one rank would hold them). The first rebuild
  // moves them to their owners.
  void own_share(std::vector<std::uint8_t> mine, std::vector<std::uint64_t> whole_index);
  void checkpoint_over_ranks(StateArchive& a);
  // The tail of a checkpoint, on one rank or over ranks: the histories by grain ids, the
  // tethers, the clocks and counters.
  void put_histories_and_counters(StateArchive& a, const std::vector<GrainId>& pair,
                                  const std::vector<Vec<D>>& shear, const SimStats& stats) const;
  // Those `region` holds (all for none).
  void collect_transfers_over_ranks(std::vector<PairImpulse<D>>& out, double elapsed,
                                    const SampleRegion* region) const;
  // The transfers over `elapsed` of grain i's contacts that `region` holds (all for none), each
  // contact under the one grain that lists it in the whole order (for_each_contact_of), then of
  // its contact with the plate: emit(PairImpulse) for each.
  template <class Emit>
  void contact_transfers_of(std::size_t i, double elapsed, const SampleRegion* region,
                            Emit&& emit) const;
  template <class Emit>
  void plate_transfer_of(std::size_t i, double elapsed, const SampleRegion* region,
                         Emit&& emit) const;
  void sample_forces_over_ranks(ForceSample<D>& out) const;
  std::vector<Vec<D>> force_totals_here() const;
  // join(value_of) for the contacts' rows (value_of(i, emit): grain i's contacts as rows of
  // numbers), the pairs' and then the plate's: each joins them over the ranks its own way.
  template <class Join>
  void join_contacts(Join&& join) const;
  void contacts_on_rank0(std::vector<typename ForceSample<D>::Contact>& out) const;
  // A frame's grains over ranks, one block of ids at a time, and its contacts one stretch of
  // cells at a time.
  void frame_grains(const FrameAsk& ask, FrameSink<D>& sink) const;
  void frame_contacts(const FrameAsk& ask, FrameSink<D>& sink) const;
  bool over_ranks() const { return domain_.has_value(); }
  void check_finite() const;
  void check_energy() const;
  std::size_t index_of(GrainId id) const { return index_of_id_[id]; }
  // Grain i's radius; one constant when all grains have the size of the first.
  double radius_of(std::span<const double> radius, std::size_t i) const {
    if constexpr (kMono) return radius[0];
    return radius[i];
  }
  // The sum of two grains' radii, as QuietPairs asks for it.
  auto pair_reach() const {
    return [this, radius = p_.radius()](std::uint32_t i, std::uint32_t j) {
      return radius_of(radius, i) + radius_of(radius, j);
    };
  }
  // Calls on_contact(i, j, k, geometry, v_rel) for listed pairs in contact, on_apart(k) for the
  // others (k indexes the pair list).
  template <class OnContact, class OnApart>
  void for_each_contact(OnContact&& on_contact, OnApart&& on_apart) const;
  // The same for the pairs of row i of the half list: on_contact(j, k, geometry, v_rel).
  template <class OnContact, class OnApart>
  void for_each_contact_of(std::size_t i, OnContact&& on_contact, OnApart&& on_apart) const;
  // Calls on_contact(i, geometry, v_rel) for the grains touching the plate.
  template <class OnContact>
  void for_each_plate_contact(OnContact&& on_contact) const;
  // The velocity of i's surface relative to j's at their contact point.
  Vec<D> relative_velocity(std::size_t i, std::size_t j, const ContactGeometry<D>& g) const;

  Scene scene_;
  Space space_;
  Particles<D> p_;
  Law law_;
  double dt_;
  double overlap_limit_;
  bool tethered_;
  TetheredWall<D> wall_;
  int threads_ = 1;
  Phases phase_;

  std::vector<Vec<D>> force_, force_prev_;  // F being accumulated (zero between passes), F(t-dt)
  std::vector<Spin<D>> torque_, torque_prev_;
  std::vector<double> inv_inertia_;
  // Per grain, bit 0: it had a force at this pass, bit 1: at the last one (see
  // ForcePass::pass).
  std::vector<std::uint8_t> forced_;
  static constexpr std::uint32_t kRemoved = IdIndex::kAbsent;
  // The grains held here (kRemoved for the others, and once removed), assigned anew after
  // every reordering of the grains.
  IdIndex index_of_id_;
  GrainId id_limit_ = 0;  // one past the scene's largest id

  CellGrid<D> grid_;
  PairList pairs_;
  std::vector<std::uint32_t> pair_row_;  // the row i of each listed pair
  QuietPairs<D> quiet_;                  // which listed pairs the pass tests
  Pass pass_;
  std::optional<Plate<D, WallLaw>> plate_;  // wall.kind = plate

  std::int64_t step_ = 0;
  std::int64_t free_grains_ = 0;
  double travel_ = 0.0;     // bound on any grain's displacement since the last rebuild
  double travelled_ = 0.0;  // travel_ summed over the lists before this one
  bool needs_rebuild_ = false;
  bool first_step_ = true;
  double removed_energy_ = 0.0;
  double initial_energy_ = 0.0;
  double last_collect_time_ = 0.0;
  SimStats stats_;

  std::optional<Domain<D>> domain_;  // none on one rank
  std::vector<std::uint8_t> owned_;  // per grain held: owned here (1) or a ghost (0)
  // Per grain held: its cell in the frame of the last rebuild, its index in the initial state
  // before the first; with the id, where one rank holds it.
  std::vector<std::uint64_t> whole_cell_;
  std::optional<BlowUpError> error_;  // a blow-up found here, to be raised on every rank
  bool trusted_pushed_ = false;       // found by this rank's pass, for agree()
  bool pass_pending_ = false;         // a pass ran since the last agree()
  bool contacts_pending_ = false;     // a pass ran whose contacts stats_ does not count yet
  bool stop_agreed_ = false;          // some rank was asked to stop
  WorkBalance balance_;
  double tether_seconds_ = 0.0;  // the tethers' part of the passes since the last look
  mutable Particles<D> whole_;   // particles() over ranks: all grains on rank 0, none elsewhere
  Particles<D> own_sample_;      // sample_own over ranks: this rank's grains of the look
  mutable bool whole_fresh_ = false;
};

// The factory's single point where run-time scene choices (dimension, contact.model, friction,
// monodisperse grains, periodic space) become template instantiations. `ranks`: the MPI ranks
// that share the run (collective: each of them calls it).
template <int D>
std::unique_ptr<Simulator<D>> make_dem_simulator(const Scene& scene, const RankTeam& ranks = {});

// Why the scene's contact.model cannot run in its dimension, or empty (scene_support.hpp).
std::string contact_law_refusal(const Scene& scene);

// The scene's contact law's peak_overlap (linear_spring_dashpot.hpp says what a law provides).
double peak_overlap(const Scene& scene, double speed);

extern template std::unique_ptr<Simulator<2>> make_dem_simulator<2>(const Scene&, const RankTeam&);
extern template std::unique_ptr<Simulator<3>> make_dem_simulator<3>(const Scene&, const RankTeam&);

}  // namespace granjet::dem
