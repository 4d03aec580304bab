// DemSimulator's members and its factory, instantiated per dimension by
// dem_simulator_2d.cpp and dem_simulator_3d.cpp (two units that compile side by side).
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numeric>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include "core/errors.hpp"
#include "core/exact_sum.hpp"
#include "core/initial_state.hpp"
#include "core/jet_geometry.hpp"
#include "soft_dem/contact_coefficients.hpp"
#include "soft_dem/contact_laws.hpp"
#include "soft_dem/dem_simulator.hpp"
#include "soft_dem/dem_simulator_ranks.hpp"
#include "soft_dem/jet_cuts.hpp"
#include "soft_dem/scene_support.hpp"

namespace granjet::dem {

template <int D, class Law, bool kMono, class Space>
DemSimulator<D, Law, kMono, Space>::DemSimulator(const Scene& scene, Particles<D> initial,
                                                 Space space, RankTeam ranks)
    : scene_(scene),
      space_(std::move(space)),
      p_(std::move(initial)),
      law_(scene.contact, scene.dt()),
      dt_(scene.dt()),
      overlap_limit_(scene.run.max_overlap),
      tethered_(scene.has_tethered_wall()),
      threads_(scene.run.threads),
      phase_(register_phases(this->profile())),
      quiet_(scene.run.threads, &this->profile()),
      pass_(scene.run.threads, scene.run.max_overlap, &this->profile()) {
  if (scene.has_plate()) plate_.emplace(scene.wall.diameter, law_.against_wall(), p_.size());
  // Lattice neighbours lie within spacing + 2 jitter; the scene checks keep next-nearest sites
  // beyond that. The tethers' dashpots are wall.damping_ratio times the eta_n of [3.5] whatever
  // the contact law (model §4 gives them in the linear law's terms).
  if (tethered_)
    wall_ = TetheredWall<D>(p_, scene.wall.spring,
                            scene.wall.damping_ratio * contact_coefficients(scene.contact).eta_n,
                            (scene.wall.spacing + 2.0 * scene.wall.jitter) * (1.0 + 1e-6));
  const std::size_t n = p_.size();
  force_.assign(n, Vec<D>::Zero());
  force_prev_.assign(n, Vec<D>::Zero());
  torque_.assign(n, Dim<D>::zero_spin());
  torque_prev_.assign(n, Dim<D>::zero_spin());
  inv_inertia_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double r = p_.radius()[i];
    inv_inertia_[i] = p_.inverse_mass()[i] / (Dim<D>::kInertiaFactor * r * r);
  }
  GrainId max_id = 0;
  for (GrainId id : p_.id()) max_id = std::max(max_id, id);
  if (!ranks.alone())  // ids below 2^53: exact as doubles
    max_id =
        static_cast<GrainId>(over_all_ranks(ranks, static_cast<double>(max_id), &RankTeam::max));
  id_limit_ = max_id + 1;
  index_of_id_.assign(p_.id());
  if (!ranks.alone()) {
    check_over_ranks(scene, ranks.size());
    double max_radius = 0.0;
    for (double r : p_.radius()) max_radius = std::max(max_radius, r);
    max_radius = over_all_ranks(ranks, max_radius, &RankTeam::max);  // of all ranks' shares
    double reach = 2.0 * max_radius + scene.run.skin;
    if (tethered_) reach = std::max(reach, wall_.longest_bond() + scene.run.skin);
    domain_.emplace(ranks, reach, jet_cuts<D>(scene, reach));
    // Each rank holds the whole target (for its springs) and hands on only its share of it.
    const GrainShare share{ranks.rank(), ranks.size()};
    const auto walls =
        static_cast<std::int64_t>(std::count(p_.kind().begin(), p_.kind().end(), GrainKind::kWall));
    std::vector<std::uint8_t> mine(n, 1);
    std::vector<std::uint64_t> whole_index(n);
    std::int64_t wall = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (p_.kind()[i] == GrainKind::kWall) mine[i] = share.holds(wall++, walls);
      whole_index[i] = static_cast<std::uint64_t>(p_.id()[i]);  // id order, as built
    }
    own_share(std::move(mine), std::move(whole_index));
  }
  rebuild();
  if (scene.run.integrator == IntegratorKind::kVelocityVerlet) {
    force_pass(  // F(t0) into force_prev_, for the predictor
        [](std::size_t) { return 0.0; },
        [](const std::uint8_t*, std::int64_t, std::int64_t) { return 0.0; });
    if (over_ranks()) {
      update_ghosts();
      agree(0.0);
    }
  }
  // What the scene started with: grains the first rebuild removed (outside the region) count.
  initial_energy_ = energy().total() + removed_energy_;
}

template <int D, class Law, bool kMono, class Space>
auto DemSimulator<D, Law, kMono, Space>::register_phases(PhaseProfile& profile) -> Phases {
  using Kind = PhaseProfile::Kind;
  return {profile.phase("rebuild: histories by grain ids", Kind::kParallel),
          profile.phase("rebuild: checks, removal, cell sort", Kind::kParallel),
          profile.phase("ranks: grains to their owners", Kind::kSerial),
          profile.phase("rebuild: pair list", Kind::kParallel),
          profile.phase("rebuild: histories onto the new list", Kind::kParallel),
          profile.phase("tethered target", Kind::kParallel),
          profile.phase("plate", Kind::kParallel),
          profile.phase("Verlet predictor", Kind::kParallel),
          profile.phase("ranks: ghost states", Kind::kSerial),
          profile.phase("ranks: agreement (waits for the slowest)", Kind::kSerial)};
}

template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::advance_to(double t) {
  // The first step at or after t (a relative 1e-9 absorbs round-off in t / dt).
  const auto target = static_cast<std::int64_t>(std::ceil(t / dt_ - 1e-9));
  if (step_ >= target) return;
  whole_fresh_ = false;
  // Over ranks a stop asked of any rank stops all at the same step.
  const auto stopping = [&] { return over_ranks() ? stop_agreed_ : this->stop_requested(); };
  while (step_ < target && !stopping()) step();
  // Over ranks, a blow-up in the last pass of velocity Verlet is not yet agreed on.
  if (over_ranks() && domain_->team().any(error_.has_value())) raise_together(error_);
  // Never hand back a blown-up state: the rebuild's check comes only at the next step.
  check_finite();
  check_energy();
}

// Every contact of a scene with e < 1 dissipates, so the kinetic energy can never exceed the
// initial total: more is the integrator's doing, a step too long for the contacts (dt = 0.5 t_c
// turns a binary e = 0.75 into 1.59) [model §3]. Kinetic only, because the elastic energy of a
// contact carries the integrator's phase error while it lasts (a contact that starts inside a
// step already stores 2% of E_0 at dt = 0.1 t_c, though the collision ends with e = 0.736);
// the kinetic bound holds at every instant, so how often the caller looks does not matter.
// 1% of E_0 leaves room for the integration error. With adhesion the bound is kinetic less the
// pull's work on the contacts of the moment.
template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::check_energy() const {
  if (scene_.contact.restitution >= 1.0) return;
  const auto mine = [&](std::size_t i) { return !over_ranks() || owned_[i]; };
  ExactSum kinetic_sum;  // the same bits on any count of ranks (core/exact_sum.hpp)
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (p_.inverse_mass()[i] == 0.0 || !mine(i)) continue;
    kinetic_sum.add(0.5 * p_.mass()[i] * p_.velocity()[i].squaredNorm());
    if constexpr (kRotation)
      kinetic_sum.add(0.5 * Dim<D>::spin_dot(p_.spin()[i], p_.spin()[i]) / inv_inertia_[i]);
  }
  // The pull of adhesion is conservative: what it has given to the grains now touching is its
  // work F_a delta over them (adhesion.hpp), which the kinetic energy may hold on top.
  if (scene_.contact.adhesion > 0.0) {
    for_each_contact(
        [&](std::size_t i, std::size_t, std::uint32_t, const ContactGeometry<D>& g, const Vec<D>&) {
          if (mine(i)) kinetic_sum.add(adhesion_energy(g.overlap, scene_.contact.adhesion));
        },
        [](std::uint32_t) {});
    for_each_plate_contact([&](std::size_t i, const ContactGeometry<D>& g, const Vec<D>&) {
      if (mine(i)) kinetic_sum.add(adhesion_energy(g.overlap, scene_.contact.adhesion));
    });
  }
  std::size_t fastest = 0;
  double fastest_speed2 = -1.0;
  for (std::size_t i = 0; i < p_.size(); ++i)
    if (mine(i) && p_.velocity()[i].squaredNorm() > fastest_speed2) {
      fastest = i;
      fastest_speed2 = p_.velocity()[i].squaredNorm();
    }
  GrainId fastest_id = p_.empty() ? 0 : p_.id()[fastest];
  if (over_ranks()) {
    const RankTeam& team = domain_->team();
    team.sum(kinetic_sum.words());
    struct Fastest {
      double speed2;
      GrainId id;
    };
    const std::vector<Fastest> each =
        team.all_gather<Fastest>(std::vector<Fastest>{{fastest_speed2, fastest_id}});
    fastest_id = std::max_element(each.begin(), each.end(), [](const Fastest& a, const Fastest& b) {
                   return a.speed2 < b.speed2;
                 })->id;
  }
  const double kinetic = kinetic_sum.value();
  const double rise = kinetic + removed_energy_ - initial_energy_;
  if (!(rise > 0.01 * initial_energy_)) return;
  throw BlowUpError("the kinetic energy rose " + std::to_string(100.0 * rise / initial_energy_) +
                        "% above the initial total (counting what removed grains carried off) "
                        "although every contact dissipates (e < 1); "
                        "only the integration adds energy: run.dt = " +
                        std::to_string(dt_) + " (" +
                        std::to_string(dt_ / scene_.contact.contact_time) +
                        " t_c) is too long for the contacts (the study uses 0.02 t_c); "
                        "the fastest grain is listed",
                    step_, time(), {fastest_id});
}

// One step from t to t + dt. Adams-Bashforth-2 needs no force after the position update, so
// the force pass integrates each grain as its last phase (see force_pass.hpp); velocity Verlet
// needs the forces at t + dt before its corrector, so it takes a predictor pass first.
// The neighbour list is rebuilt once the fastest grains may have moved skin/2: travel_ adds up
// dt times the largest speed of each step, a bound on every displacement that costs no extra
// pass over stored positions.
template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::step() {
  if (scene_.run.integrator == IntegratorKind::kAdamsBashforth2) {
    if (needs_rebuild_) rebuild();
    const Ab2Step<D, kRotation> ab2 = ab2_step();
    const auto coast = [&](const std::uint8_t* pushed, std::int64_t begin, std::int64_t end) {
      return ab2.coast(pushed, begin, end);
    };
    if (!over_ranks()) {
      add_travel(force_pass([&](std::size_t i) { return ab2.advance(i); }, coast));
    } else {  // a pushed ghost's move is its owner's, sent after the pass (update_ghosts)
      const std::uint8_t* owned = owned_.data();
      double own = 0.0;
      // A classification comes after a rebuild or a trusted pair's push, not at every step: the
      // cut that balances the per-step passes leaves it out, as it leaves out the rebuilds.
      classify_quiet_pairs();
      {
        const WorkBalance::Pass work(balance_);
        own = force_pass([&](std::size_t i) { return owned[i] ? ab2.advance(i) : ab2.leave(i); },
                         coast);
      }
      update_ghosts();
      add_travel(agree(own));
    }
    first_step_ = false;
    ++step_;
  } else {
    const VerletStep<D, kRotation> predictor = verlet_step();
    const auto n = static_cast<std::int64_t>(p_.size());
    std::vector<double> thread_speed2(threads_, 0.0);
    const std::uint8_t* owned = over_ranks() ? owned_.data() : nullptr;
    {
      const PhaseProfile::Timer predicting = timer(phase_.predictor);
      const WorkBalance::Pass work(balance_);
#pragma omp parallel num_threads(threads_) if (threads_ > 1)
      {
        double speed2 = 0.0;  // a local, stored once: the threads' slots share a cache line
#pragma omp for schedule(static) nowait
        for (std::int64_t i = 0; i < n; ++i) {
          const double own = predictor.predict(i);
          if (owned == nullptr || owned[i]) speed2 = sticky_max(speed2, own);
        }
        thread_speed2[team_index()] = speed2;
      }
    }
    double speed2 = 0.0;
    for (double s : thread_speed2) speed2 = sticky_max(speed2, s);
    ++step_;
    add_travel(over_ranks() ? agree(speed2) : speed2);
    if (needs_rebuild_) rebuild();  // before the forces at t + dt
    const VerletStep<D, kRotation> corrector = verlet_step();
    classify_quiet_pairs();  // not balanced work, as for Adams-Bashforth-2
    {
      const WorkBalance::Pass work(balance_);
      force_pass(
          [&](std::size_t i) {
            corrector.correct(i);
            return 0.0;
          },
          // F(t) = F(t + dt) = 0: nothing to correct
          [](const std::uint8_t*, std::int64_t, std::int64_t) { return 0.0; });
    }
    if (over_ranks()) update_ghosts();
  }
  stats_.steps = step_;
  stats_.particle_steps += free_grains_;
}

template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::add_travel(double largest_speed2) {
  travel_ += dt_ * std::sqrt(largest_speed2);
  // Written so that a NaN speed also triggers the rebuild, which reports it.
  needs_rebuild_ = !(travel_ <= 0.5 * scene_.run.skin);
}

// Adams-Bashforth-2, with F(t - dt) = F(t) on the first step [model §3].
template <int D, class Law, bool kMono, class Space>
auto DemSimulator<D, Law, kMono, Space>::ab2_step() -> Ab2Step<D, kRotation> {
  return {p_.position().data(),
          p_.velocity().data(),
          p_.spin().data(),
          force_.data(),
          first_step_ ? force_.data() : force_prev_.data(),
          force_prev_.data(),
          torque_.data(),
          first_step_ ? torque_.data() : torque_prev_.data(),
          torque_prev_.data(),
          p_.inverse_mass().data(),
          inv_inertia_.data(),
          0.5 * dt_};
}

template <int D, class Law, bool kMono, class Space>
auto DemSimulator<D, Law, kMono, Space>::verlet_step() -> VerletStep<D, kRotation> {
  return {p_.position().data(), p_.velocity().data(),
          p_.spin().data(),     force_.data(),
          force_prev_.data(),   torque_.data(),
          torque_prev_.data(),  p_.inverse_mass().data(),
          inv_inertia_.data(),  dt_};
}

template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::classify_quiet_pairs() {
  if (quiet_.fresh()) return;
  quiet_.classify(
      p_, force_prev_, pairs_, pair_row_, space_, dt_, pair_reach(),
      over_ranks() ? std::span<const std::uint8_t>(owned_) : std::span<const std::uint8_t>());
}

// The whole pass (the phases of force_pass.hpp): the quiet pairs' classification where due,
// then in one parallel region the tethers, the pairs, the plate and each grain's update.
// force_ and torque_ must be zero on entry.
template <int D, class Law, bool kMono, class Space>
template <class Advance, class Coast>
[[gnu::flatten]]  // inline the contact law and the grain update into their loops
double
DemSimulator<D, Law, kMono, Space>::force_pass(Advance&& advance, Coast&& coast) {
  classify_quiet_pairs();
  const auto tether_forces = [&] {
    const auto start = std::chrono::steady_clock::now();
    {
      std::optional<PhaseProfile::Timer> tethering;
      if (team_index() == 0) tethering.emplace(&this->profile(), phase_.tethers);
      wall_.add_forces_share(p_, std::span<Vec<D>>(force_));
    }
    const double seconds = seconds_since(start);  // summed over the team, as the loops' are
#pragma omp atomic
    tether_seconds_ += seconds;
  };
  const auto n = static_cast<std::int64_t>(p_.size());
  // The plate's forces, after the contacts': the same sum order for any thread count. Each
  // thread keeps the first grain too deep in its share.
  std::vector<std::int64_t> first_blown_on_plate(threads_, n);
  const auto plate_forces = [&] {
    if (!plate_) return;
    using Touch = typename Plate<D, WallLaw>::Touch;
    const auto x = p_.position();
    const auto v = p_.velocity();
    const auto w = p_.spin();
    const auto radius = p_.radius();
    std::uint8_t* forced = forced_.data();
    std::optional<PhaseProfile::Timer> plating;
    if (team_index() == 0) plating.emplace(&this->profile(), phase_.plate);
    std::int64_t first_blown = n;
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) {
      const Touch touch = plate_->add_force(i, x[i], radius_of(radius, i), v[i], w[i],
                                            overlap_limit_, force_[i], torque_[i]);
      if (touch != Touch::kApart) forced[i] |= 1;
      if (touch == Touch::kTooDeep) first_blown = std::min(first_blown, i);
    }  // (a barrier: every grain has its plate force)
    first_blown_on_plate[team_index()] = first_blown;
  };
  std::atomic<bool> trusted_pushed = false;
  const typename Pass::Outcome outcome =
      pass_.pass(law_, p_, pairs_, pair_row_, quiet_.tested(), space_,
                 {force_.data(), torque_.data(), forced_.data()}, tether_forces, plate_forces,
                 p_.kind(), tethered_, advance, coast, [&](std::size_t begin, std::size_t end) {
                   if (quiet_.trusted_pushed(forced_, begin, end))
                     trusted_pushed.store(true, std::memory_order_relaxed);
                 });
  const std::vector<std::uint32_t>& contact_pair = pass_.history().pairs();
  stats_.contacts = static_cast<std::int64_t>(contact_pair.size());
  if (!over_ranks()) {
    quiet_.after_pass(trusted_pushed.load(std::memory_order_relaxed));
  } else {  // the ranks agree on it in agree(); the contacts are counted when asked for
    trusted_pushed_ = trusted_pushed.load(std::memory_order_relaxed);
    pass_pending_ = true;
    contacts_pending_ = true;
  }
  const std::size_t first_blown = outcome.first_too_deep;
  const std::int64_t plate_blown =
      *std::min_element(first_blown_on_plate.begin(), first_blown_on_plate.end());
  // A blown step is reported in row order (row i's pairs, then grain i on the plate, then
  // row i + 1); the state it integrated is lost anyway.
  std::optional<BlowUpError> blown;
  if (first_blown < contact_pair.size()) {
    const std::uint32_t k = contact_pair[first_blown];
    if (pair_row_[k] <= plate_blown) blown = overlap_error(pair_row_[k], pairs_.partner[k]);
  }
  if (!blown && plate_blown < n) blown = overlap_error(plate_blown, plate_blown);
  if (blown && !over_ranks()) throw *blown;
  if (blown && !error_) error_ = blown;  // raised on every rank by agree()
  // advance zeroed force_prev_ as it went: now F(t) becomes F(t-dt) and the zeros the next F.
  force_.swap(force_prev_);
  if constexpr (kRotation) torque_.swap(torque_prev_);
  return outcome.largest;
}

template <int D, class Law, bool kMono, class Space>
template <class OnContact, class OnApart>
void DemSimulator<D, Law, kMono, Space>::for_each_contact_of(std::size_t i, OnContact&& on_contact,
                                                             OnApart&& on_apart) const {
  const auto x = p_.position();
  const auto radius = p_.radius();
  const Vec<D> x_i = x[i];
  const double radius_i = radius_of(radius, i);
  for (std::uint32_t k = pairs_.first[i]; k < pairs_.first[i + 1]; ++k) {
    const std::uint32_t j = pairs_.partner[k];
    const Vec<D> r_ij = space_.separation(x_i, x[j]);
    const double radius_j = kMono ? radius_i : radius[j];
    const double reach = radius_i + radius_j;
    const double d2 = r_ij.squaredNorm();
    if (d2 >= reach * reach) {
      on_apart(k);
      continue;
    }
    const ContactGeometry<D> g = contact_geometry(r_ij, std::sqrt(d2), radius_i, radius_j);
    on_contact(j, k, g, relative_velocity(i, j, g));
  }
}

template <int D, class Law, bool kMono, class Space>
Vec<D> DemSimulator<D, Law, kMono, Space>::relative_velocity(std::size_t i, std::size_t j,
                                                             const ContactGeometry<D>& g) const {
  const auto v = p_.velocity();
  const auto w = p_.spin();
  return dem::relative_velocity<kRotation>(v[i], v[j], w[i], w[j], g);
}

template <int D, class Law, bool kMono, class Space>
template <class OnContact, class OnApart>
void DemSimulator<D, Law, kMono, Space>::for_each_contact(OnContact&& on_contact,
                                                          OnApart&& on_apart) const {
  for (std::size_t i = 0; i < p_.size(); ++i)
    for_each_contact_of(
        i,
        [&](std::size_t j, std::uint32_t k, const ContactGeometry<D>& g, const Vec<D>& v_rel) {
          on_contact(i, j, k, g, v_rel);
        },
        on_apart);
}

template <int D, class Law, bool kMono, class Space>
template <class OnContact>
void DemSimulator<D, Law, kMono, Space>::for_each_plate_contact(OnContact&& on_contact) const {
  if (!plate_) return;
  const auto x = p_.position();
  const auto v = p_.velocity();
  const auto w = p_.spin();
  const auto radius = p_.radius();
  for (std::size_t i = 0; i < p_.size(); ++i)
    plate_->contact(
        x[i], radius_of(radius, i), v[i], w[i],
        [&](const ContactGeometry<D>& g, const Vec<D>& v_rel) { on_contact(i, g, v_rel); }, [] {});
}

// Grain i overlapping grain j, or the plate when j == i.
template <int D, class Law, bool kMono, class Space>
BlowUpError DemSimulator<D, Law, kMono, Space>::overlap_error(std::size_t i, std::size_t j) const {
  std::vector<GrainId> ids{p_.id()[i]};
  if (j != i) ids.push_back(p_.id()[j]);
  return BlowUpError("overlap beyond run.max_overlap = " + std::to_string(overlap_limit_) +
                         " of the smaller radius" + (j == i ? " against the plate" : ""),
                     step_, time(), ids);
}

template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::check_finite() const {
  const auto n = static_cast<std::int64_t>(p_.size());
  const auto x = p_.position();
  const auto v = p_.velocity();
  bool any = false;
#pragma omp parallel for num_threads(threads_) reduction(| : any) if (threads_ > 1)
  for (std::int64_t i = 0; i < n; ++i) any |= !x[i].allFinite() || !v[i].allFinite();
  const auto finite = [&](std::size_t i) { return x[i].allFinite() && v[i].allFinite(); };
  std::vector<GrainId> bad;
  if (over_ranks()) {  // the first ten in the order one rank holds them
    if (!domain_->team().any(any)) return;
    bad = in_whole_order<GrainId>([&](std::size_t i, auto emit) {
      if (!finite(i)) emit(p_.id()[i]);
    });
    bad.resize(std::min<std::size_t>(bad.size(), 10));
  } else {
    if (!any) return;
    for (std::size_t i = 0; i < p_.size() && bad.size() < 10; ++i)
      if (!finite(i)) bad.push_back(p_.id()[i]);
  }
  if (!bad.empty()) throw BlowUpError("non-finite position or velocity", step_, time(), bad);
}

// Jet grains farther than region.radius from the axis or region.below behind the target plane
// are removed; their energy is booked so the balance still closes.
template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::remove_escaped(std::vector<double>& weight) {
  if (!scene_.has_wall()) return;
  const auto n = static_cast<std::int64_t>(p_.size());
  const auto kind = p_.kind();
  const auto x = p_.position();
  // Over ranks each removes its own grains (the ghosts are chosen anew after).
  const auto escaped = [&](std::size_t i) {
    return kind[i] == GrainKind::kFree && outside_region<D>(scene_.region, x[i]) &&
           (!over_ranks() || owned_[i]);
  };
  bool any = false;  // most rebuilds remove none: a shared look first
#pragma omp parallel for num_threads(threads_) reduction(| : any) if (threads_ > 1)
  for (std::int64_t i = 0; i < n; ++i) any |= escaped(i);
  if (over_ranks()) any = domain_->team().any(any);
  if (!any) return;
  struct Carried {
    double kinetic, rotational;
  };
  const auto carried = [&](std::size_t i) -> Carried {
    double rotational = 0.0;
    if constexpr (kRotation)
      rotational = 0.5 * Dim<D>::spin_dot(p_.spin()[i], p_.spin()[i]) / inv_inertia_[i];
    return {0.5 * p_.mass()[i] * p_.velocity()[i].squaredNorm(), rotational};
  };
  // The energy they carry off, summed in the order one rank holds them.
  std::vector<Carried> removed;
  if (over_ranks())
    removed = in_whole_order<Carried>([&](std::size_t i, auto emit) {
      if (escaped(i)) emit(carried(i));
    });
  std::vector<std::uint32_t> keep;
  keep.reserve(p_.size());
  for (std::uint32_t i = 0; i < p_.size(); ++i) {
    if (!escaped(i)) {
      keep.push_back(i);
      continue;
    }
    if (!over_ranks()) removed.push_back(carried(i));
  }
  for (const Carried& c : removed) {
    ++stats_.removed;
    removed_energy_ += c.kinetic;
    if constexpr (kRotation) removed_energy_ += c.rotational;
  }
  p_.gather(keep, threads_);
  Particles<D>::gather_one(force_prev_, keep, threads_);
  Particles<D>::gather_one(torque_prev_, keep, threads_);
  Particles<D>::gather_one(inv_inertia_, keep, threads_);
  if (over_ranks()) {
    Particles<D>::gather_one(owned_, keep, threads_);
    Particles<D>::gather_one(whole_cell_, keep, threads_);
  }
  if (!weight.empty()) Particles<D>::gather_one(weight, keep, threads_);
  if (plate_) plate_->gather(keep);
  quiet_.gather(keep, threads_);
  index_of_id_.assign(p_.id(), threads_);
}

template <int D, class Law, bool kMono, class Space>
auto DemSimulator<D, Law, kMono, Space>::histories() const -> std::vector<History> {
  return pass_.history().by_ids(p_.id(), pair_row_, pairs_.partner, threads_);
}

template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::rebuild() {
  std::vector<History> history;
  {
    const PhaseProfile::Timer timing = timer(phase_.rebuild_ids);
    history = histories();
  }
  rebuild(std::move(history));
}

// Rebuilds the neighbour list, re-sorting grains by cell for memory locality and carrying the
// tangential history over by grain-id pair.
template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::rebuild(std::vector<History> history,
                                                 bool partners_elsewhere) {
  std::optional<PhaseProfile::Timer> timing(std::in_place, &this->profile(), phase_.rebuild_sort);
  if (contacts_pending_) {  // before the list they index changes
    stats_.contacts = own_contacts();
    contacts_pending_ = false;
  }
  // Read off the list about to go, for a re-cut of the parts.
  std::vector<double> weight;
  if (over_ranks() && balance_.looks_at_next_rebuild()) weight = grain_weights();
  check_finite();
  remove_escaped(weight);
  if (over_ranks()) {
    timing.emplace(&this->profile(), phase_.rebuild_moves);
    distribute(history, std::move(weight), partners_elsewhere);
    timing.emplace(&this->profile(), phase_.rebuild_sort);
  }
  const auto radius = p_.radius();
  double max_radius = radius.empty() ? 0.0 : radius[0];
  if constexpr (!kMono) {
    const auto grains = static_cast<std::int64_t>(radius.size());
#pragma omp parallel for num_threads(threads_) reduction(max : max_radius) if (threads_ > 1)
    for (std::int64_t i = 0; i < grains; ++i) max_radius = std::max(max_radius, radius[i]);
  }
  if (over_ranks()) max_radius = over_all_ranks(domain_->team(), max_radius, &RankTeam::max);
  const double cut = 2.0 * max_radius + scene_.run.skin;
  if constexpr (Space::kPeriodic) {
    for (Vec<D>& x : p_.position()) space_.wrap(x);
    grid_.build_periodic(p_.position(), space_.box, cut, threads_, p_.id());
  } else if (!over_ranks()) {
    grid_.build(p_.position(), cut, threads_, p_.id());
  } else {  // the frame of all grains, this rank's window of it
    grid_.build_in(whole_frame(cut), p_.position(), threads_, p_.id());
  }
  const auto order = grid_.order();
  p_.gather(order, threads_);
  Particles<D>::gather_one(force_prev_, order, threads_);
  Particles<D>::gather_one(torque_prev_, order, threads_);
  Particles<D>::gather_one(inv_inertia_, order, threads_);
  if (plate_) plate_->gather(order);
  quiet_.gather(order, threads_);
  if (over_ranks()) {
    Particles<D>::gather_one(owned_, order, threads_);
    whole_cell_.resize(order.size());
    for (std::size_t k = 0; k < order.size(); ++k)
      whole_cell_[k] = grid_.frame_cell(grid_.cell_of(order[k]));
  }
  const auto n = static_cast<std::int64_t>(p_.size());
  force_.resize(n);
  forced_.resize(n);
  torque_.resize(n);
  const auto id = p_.id();
#pragma omp parallel for num_threads(threads_) schedule(static) if (threads_ > 1)
  for (std::int64_t i = 0; i < n; ++i) {
    force_[i].setZero();  // rebuilds come between force passes
    forced_[i] = 2;       // unknown after the reordering: assume a force at the last pass
    torque_[i] = Dim<D>::zero_spin();
  }
  index_of_id_.assign(id, threads_);
  if (tethered_) wall_.locate([this](GrainId id) { return index_of(id); }, p_.size());

  const auto kind = p_.kind();
  timing.emplace(&this->profile(), phase_.rebuild_pairs);
  // Two grains that share a bit are never a pair: two wall grains never interact, and two
  // ghosts are their owners' pair. One byte a grain keeps the candidates' test to one load.
  enum : std::uint8_t { kWallGrain = 1, kGhostGrain = 2 };
  std::vector<std::uint8_t> pair_class(n);
  for (std::int64_t i = 0; i < n; ++i)
    pair_class[i] = static_cast<std::uint8_t>((kind[i] == GrainKind::kWall ? kWallGrain : 0) |
                                              (over_ranks() && !owned_[i] ? kGhostGrain : 0));
  build_half_pairs<D, kMono>(
      grid_, p_.position(), p_.radius(), scene_.run.skin,
      [c = pair_class.data()](std::uint32_t i, std::uint32_t j) { return (c[i] & c[j]) != 0; },
      pairs_, space_, threads_);
  if (over_ranks()) domain_->list_halo(p_.position(), p_.id(), owned_);
  timing.emplace(&this->profile(), phase_.rebuild_rows);
  pair_row_.resize(pairs_.size());
#pragma omp parallel for num_threads(threads_) schedule(static) if (threads_ > 1)
  for (std::int64_t i = 0; i < n; ++i)
    std::fill(pair_row_.begin() + pairs_.first[i], pair_row_.begin() + pairs_.first[i + 1],
              static_cast<std::uint32_t>(i));
  pass_.history().restore(
      history,
      [this](GrainId id) -> std::optional<std::uint32_t> {
        const std::uint32_t i = index_of_id_[id];
        if (i == kRemoved) return std::nullopt;
        return i;
      },
      pairs_, threads_);
  // A pass whose look at the trusted grains the ranks have not yet agreed on (velocity Verlet's
  // last, before a checkpoint) may have pushed one here.
  if (quiet_.trust_holds() && !pass_pending_)
    quiet_.relist(
        p_, pairs_, pair_row_, space_, dt_, pair_reach(),
        over_ranks() ? std::span<const std::uint8_t>(owned_) : std::span<const std::uint8_t>());
  else
    quiet_.expire();
  travelled_ += travel_;
  travel_ = 0.0;
  needs_rebuild_ = false;
  std::int64_t free = 0;
  const std::uint8_t* owned = over_ranks() ? owned_.data() : nullptr;
#pragma omp parallel for num_threads(threads_) reduction(+ : free) if (threads_ > 1)
  for (std::int64_t i = 0; i < n; ++i)
    free += kind[i] == GrainKind::kFree && (owned == nullptr || owned[i]);
  free_grains_ = free;
  ++stats_.neighbour_rebuilds;
}

// A rebuild first: it re-sorts the grains by cell and lists the pairs anew from positions
// alone, so a simulator that takes the stored grains (already in that order) and rebuilds gets
// the same order, list and carried histories, and every later sum runs in the same order.
template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::checkpoint(StateArchive& a) {
  if (over_ranks()) return checkpoint_over_ranks(a);
  rebuild();
  put_particles(a, "dem/grains", p_);
  a.put_rows<Vec<D>>("dem/force_prev", force_prev_);
  a.put_rows<Spin<D>>("dem/torque_prev", torque_prev_);
  a.put_rows<Vec<D>>("dem/plate_shear", plate_ ? plate_->shear() : std::vector<Vec<D>>());
  std::vector<GrainId> pair;
  std::vector<Vec<D>> shear;
  for (const History& h : histories()) {
    pair.insert(pair.end(), {h.a, h.b});
    shear.push_back(h.shear);
  }
  put_histories_and_counters(a, pair, shear, stats_);
}

template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::put_histories_and_counters(
    StateArchive& a, const std::vector<GrainId>& pair, const std::vector<Vec<D>>& shear,
    const SimStats& stats) const {
  a.put_values<GrainId>("dem/history/pair", pair);
  a.put_rows<Vec<D>>("dem/history/shear", shear);
  if (tethered_) wall_.save(a, "dem/tethers");
  a.put("dem/step", step_);
  a.put("dem/first_step", std::int64_t{first_step_});
  a.put("dem/removed_energy", removed_energy_);
  a.put("dem/initial_energy", initial_energy_);
  a.put("dem/last_collect_time", last_collect_time_);
  put_stats(a, "dem/stats", stats);
}

template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::restore(const StateArchive& a) {
  quiet_.expire();  // the grains are replaced
  p_ = get_particles<D>(a, "dem/grains");
  const std::size_t n = p_.size();
  force_prev_ = a.rows<Vec<D>>("dem/force_prev");
  torque_prev_ = a.rows<Spin<D>>("dem/torque_prev");
  std::vector<Vec<D>> plate_shear = a.rows<Vec<D>>("dem/plate_shear");
  const std::size_t plate_rows = plate_ && Law::kNeedsHistory ? n : 0;
  if (force_prev_.size() != n || torque_prev_.size() != n || plate_shear.size() != plate_rows)
    throw std::runtime_error("checkpoint entries under dem/ differ in length");
  if (plate_) plate_->shear() = std::move(plate_shear);
  inv_inertia_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double r = p_.radius()[i];
    inv_inertia_[i] = p_.inverse_mass()[i] / (Dim<D>::kInertiaFactor * r * r);
  }
  for (const GrainId id : p_.id())
    if (id < 0 || id >= id_limit_)
      throw std::runtime_error("checkpoint holds grain " + std::to_string(id) +
                               ", which this scene does not build");
  index_of_id_.assign(p_.id(), threads_);
  const auto pair = a.values<GrainId>("dem/history/pair");
  const auto shear = a.rows<Vec<D>>("dem/history/shear");
  if (pair.size() != 2 * shear.size())
    throw std::runtime_error("checkpoint entries under dem/history differ in length");
  std::vector<History> history;
  for (std::size_t c = 0; c < shear.size(); ++c)
    history.push_back({pair[2 * c], pair[2 * c + 1], shear[c]});
  if (tethered_) wall_.restore(a, "dem/tethers");
  bool partners_elsewhere = false;
  if (over_ranks()) {
    // Each rank read its shares of a checkpoint split over ranks (analysis/checkpoint_file.hpp)
    // and hands on all its grains, or it read a whole one and hands on a run of it.
    const bool read_shares = a.contains("checkpoint/readers");
    if (read_shares && a.integer("checkpoint/readers") != domain_->ranks())
      throw std::logic_error("the checkpoint's shares were read for another count of ranks");
    const GrainShare share{domain_->rank(), domain_->ranks()};
    std::vector<std::uint8_t> mine(n);
    std::vector<std::uint64_t> whole_index(n);
    for (std::size_t i = 0; i < n; ++i) {
      mine[i] =
          read_shares || share.holds(static_cast<std::int64_t>(i), static_cast<std::int64_t>(n));
      // Until the rebuild sorts them: the whole checkpoint's order, or the ids.
      whole_index[i] = read_shares ? static_cast<std::uint64_t>(p_.id()[i]) : i;
    }
    own_share(std::move(mine), std::move(whole_index));
    partners_elsewhere = read_shares;
  }
  rebuild(std::move(history), partners_elsewhere);
  step_ = a.integer("dem/step");
  first_step_ = a.integer("dem/first_step") != 0;
  removed_energy_ = a.real("dem/removed_energy");
  initial_energy_ = a.real("dem/initial_energy");
  last_collect_time_ = a.real("dem/last_collect_time");
  stats_ = get_stats(a, "dem/stats");
  if (over_ranks() && domain_->rank() != 0) stats_.particle_steps = 0;  // summed over ranks
  whole_fresh_ = false;
}

template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::collect_transfers(std::vector<PairImpulse<D>>& out) {
  const double elapsed = time() - last_collect_time_;
  last_collect_time_ = time();
  if (over_ranks()) return collect_transfers_over_ranks(out, elapsed, nullptr);
  const auto x = p_.position();
  const auto id = p_.id();
  // Runs of rows with as many listed pairs each, taken by the threads as they come free (the
  // contacts, which cost most, crowd into a few runs); the runs' transfers are joined in row
  // order, as one thread would list them.
  const int runs = threads_ == 1 ? 1 : 16 * threads_;
  std::vector<std::vector<PairImpulse<D>>> found(runs);
  const auto n = static_cast<std::int64_t>(p_.size());
  const std::vector<std::uint32_t>& first = pairs_.first;
  const auto row_at = [&](int r) {  // the first row of run r
    const std::size_t pair = pairs_.size() * r / runs;
    return r == runs ? n : std::lower_bound(first.begin(), first.begin() + n, pair) - first.begin();
  };
#pragma omp parallel for num_threads(threads_) schedule(dynamic, 1) if (threads_ > 1)
  for (int r = 0; r < runs; ++r) {
    std::vector<PairImpulse<D>>& mine = found[r];
    for (std::int64_t i = row_at(r); i < row_at(r + 1); ++i)
      for_each_contact_of(
          i,
          [&](std::size_t j, std::uint32_t k, const ContactGeometry<D>& g, const Vec<D>& v_rel) {
            Vec<D> shear = pass_.history().of(k);  // a copy: sampling must not advance it
            const Vec<D> f = law_.force(g, v_rel, shear);
            // The partner's nearest image: position_i - position_j is the separation.
            mine.push_back({id[i], id[j], x[i], x[i] - space_.separation(x[i], x[j]), elapsed * f});
          },
          [](std::uint32_t) {});
  }
  for (const std::vector<PairImpulse<D>>& run : found)
    out.insert(out.end(), run.begin(), run.end());
  for_each_plate_contact([&](std::size_t i, const ContactGeometry<D>& g, const Vec<D>& v_rel) {
    const Vec<D> f = plate_->force(i, g, v_rel);
    out.push_back({id[i], kPlateId, x[i], plate_->mirror(x[i]), elapsed * f});
  });
}

// One rank lists them all: no gather to save.
template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::collect_transfers_in(std::vector<PairImpulse<D>>& out,
                                                              const SampleRegion& region) {
  if (!over_ranks()) return collect_transfers(out);
  const double elapsed = time() - last_collect_time_;
  last_collect_time_ = time();
  collect_transfers_over_ranks(out, elapsed, &region);
}

template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::sample_forces(ForceSample<D>& out) const {
  const auto id = p_.id();
  out.contacts.clear();
  if (over_ranks()) return sample_forces_over_ranks(out);
  out.total.assign(p_.size(), Vec<D>::Zero());
  const auto add = [&](std::size_t i, GrainId j, const ContactGeometry<D>& g, const Vec<D>& f) {
    // A law that turns no grain has no tangential force: projecting would only add rounding.
    const Vec<D> normal = kRotation ? Vec<D>(f.dot(g.n) * g.n) : f;
    out.contacts.push_back({id[i], j, normal, f - normal, g.overlap});
    out.total[i] += f;
  };
  for_each_contact(
      [&](std::size_t i, std::size_t j, std::uint32_t k, const ContactGeometry<D>& g,
          const Vec<D>& v_rel) {
        Vec<D> shear = pass_.history().of(k);  // a copy: sampling must not advance the history
        const Vec<D> f = law_.force(g, v_rel, shear);
        add(i, id[j], g, f);
        out.total[j] -= f;
      },
      [](std::uint32_t) {});
  for_each_plate_contact([&](std::size_t i, const ContactGeometry<D>& g, const Vec<D>& v_rel) {
    add(i, kPlateId, g, plate_->force(i, g, v_rel));
  });
  if (tethered_) wall_.add_forces(p_, std::span<Vec<D>>(out.total));
}

template <int D, class Law, bool kMono, class Space>
const Particles<D>& DemSimulator<D, Law, kMono, Space>::particles() const {
  if (!over_ranks()) return p_;
  if (!whole_fresh_) {
    gather_whole(nullptr);
    whole_fresh_ = true;
  }
  return whole_;
}

// Over ranks whole_ then holds only those grains (not the whole: whole_fresh_ stays false).
template <int D, class Law, bool kMono, class Space>
const Particles<D>& DemSimulator<D, Law, kMono, Space>::particles_in(
    const SampleRegion& region) const {
  if (!over_ranks() || whole_fresh_) return particles();
  gather_whole(&region);
  return whole_;
}

// The grains `region` holds (all for none) into whole_ on rank 0, in the order one rank holds
// them.
template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::gather_whole(const SampleRegion* region) const {
  struct Grain {  // what Particles holds of a grain
    GrainId id;
    GrainKind kind;
    double x[D], v[D], w[kSpinWidth<D>], radius, mass;
  };
  whole_.clear();  // its memory stays: each sample refills it
  for_each_in_whole_order<Grain>(
      [&](std::size_t i, auto emit) {
        if (region != nullptr &&
            !region->holds_grain<D>(p_.position()[i], p_.radius()[i], p_.kind()[i]))
          return;
        Grain g{p_.id()[i], p_.kind()[i], {}, {}, {}, p_.radius()[i], p_.mass()[i]};
        put<D>(g.x, p_.position()[i]);
        put<D>(g.v, p_.velocity()[i]);
        put<D>(g.w, p_.spin()[i]);
        emit(g);
      },
      [&](const Grain& g) {
        whole_.add(g.id, g.kind, get<D, Vec<D>>(g.x), get<D, Vec<D>>(g.v), g.radius, g.mass);
        whole_.spin().back() = get<D, Spin<D>>(g.w);
      },
      Joined::kOnRank0);
}

template <int D, class Law, bool kMono, class Space>
SimStats DemSimulator<D, Law, kMono, Space>::stats() const {
  if (!over_ranks()) return stats_;
  SimStats s = stats_;  // steps, rebuilds and removals are counted alike on every rank
  s.particle_steps = domain_->team().sum(stats_.particle_steps);
  s.contacts = domain_->team().sum(contacts_pending_ ? own_contacts() : stats_.contacts);
  s.ranks = domain_->ranks();
  s.imbalance = balance_.imbalance();
  s.recuts = balance_.recuts();
  const typename Domain<D>::HaloCount& halo = domain_->halo_count();
  std::vector<std::int64_t> rows{halo.rows_sent, halo.rows_held};
  domain_->team().sum(rows);
  if (halo.exchanges > 0)
    s.ghost_states_per_step = static_cast<double>(rows[0]) / static_cast<double>(halo.exchanges);
  if (rows[1] > 0)
    s.ghost_states_share = static_cast<double>(rows[0]) / static_cast<double>(rows[1]);
  return s;
}

// Each sum exact and rounded once (core/exact_sum.hpp): over ranks each rank adds its own grains,
// and the contacts and springs whose first grain it owns, and the ranks' sums join as integers,
// to the bits of one rank.
template <int D, class Law, bool kMono, class Space>
EnergyBalance DemSimulator<D, Law, kMono, Space>::energy() const {
  const auto mine = [&](std::size_t i) { return !over_ranks() || owned_[i]; };
  ExactSum kinetic, rotational, elastic;
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (!mine(i) || p_.inverse_mass()[i] == 0.0) continue;  // immovable grains carry none
    kinetic.add(0.5 * p_.mass()[i] * p_.velocity()[i].squaredNorm());
    if constexpr (kRotation)
      rotational.add(0.5 * Dim<D>::spin_dot(p_.spin()[i], p_.spin()[i]) / inv_inertia_[i]);
  }
  for_each_contact(
      [&](std::size_t i, std::size_t, std::uint32_t k, const ContactGeometry<D>& g, const Vec<D>&) {
        if (mine(i)) elastic.add(law_.elastic_energy(g, pass_.history().of(k)));
      },
      [](std::uint32_t) {});
  for_each_plate_contact([&](std::size_t i, const ContactGeometry<D>& g, const Vec<D>&) {
    if (mine(i)) elastic.add(plate_->elastic_energy(i, g));
  });
  if (tethered_)
    wall_.for_each_energy_term(p_, [&](std::size_t, std::size_t i, double term) {
      if (mine(i)) elastic.add(term);
    });
  if (over_ranks())
    for (ExactSum* sum : {&kinetic, &rotational, &elastic}) domain_->team().sum(sum->words());
  EnergyBalance e;
  e.kinetic = kinetic.value();
  e.rotational = rotational.value();
  e.elastic = elastic.value();
  e.removed = removed_energy_;
  e.dissipated = initial_energy_ - e.total() - e.removed;
  return e;
}

namespace factory {

// The periodic gas scenes' box (gas_lattice's), which must hold three neighbour cells across.
template <int D>
PeriodicBox<D> periodic_box(const Scene& scene) {
  const PeriodicBox<D> box(gas_lattice<D>(scene.gas).box);
  const double cut = 1.0 + scene.run.skin;
  if (box.box.minCoeff() < 3.0 * cut)
    throw InputError("gas.grains", "the periodic box (" + std::to_string(box.box.minCoeff()) +
                                       " d across) must be at least three neighbour cells of "
                                       "1 + run.skin = " +
                                       std::to_string(cut) +
                                       " d wide; use more grains or a lower gas.phi");
  return box;
}

// Open space (jets, binary collisions), mono- or bidisperse.
template <int D, class Law>
std::unique_ptr<Simulator<D>> make_jet_with_law(const Scene& scene, const RankTeam& ranks) {
  Particles<D> initial = build_initial_state<D>(scene, {ranks.rank(), ranks.size()});
  if (scene.monodisperse())
    return std::make_unique<DemSimulator<D, Law, true>>(scene, std::move(initial), OpenSpace<D>{},
                                                        ranks);
  return std::make_unique<DemSimulator<D, Law, false>>(scene, std::move(initial), OpenSpace<D>{},
                                                       ranks);
}

template <int D, class Law>
std::unique_ptr<Simulator<D>> make_with_law(const Scene& scene, const RankTeam& ranks) {
  // The gases' grains are unit grains (Scene::monodisperse), so they need no other instance.
  if (scene.periodic()) {
    const PeriodicBox<D> box = periodic_box<D>(scene);
    return std::make_unique<DemSimulator<D, Law, true, PeriodicBox<D>>>(
        scene, build_initial_state<D>(scene), box, ranks);
  }
  return make_jet_with_law<D, Law>(scene, ranks);
}

}  // namespace factory

template <int D>
std::unique_ptr<Simulator<D>> make_dem_simulator(const Scene& scene, const RankTeam& ranks) {
  return with_contact_law(
      scene.contact.model,
      [&]<template <int, bool> class LawOf>(ContactLaw<LawOf>) -> std::unique_ptr<Simulator<D>> {
        if constexpr (!LawOf<D, false>::kUnsupported.empty()) {
          throw InputError("contact.model", std::string(LawOf<D, false>::kUnsupported));
        } else {
          // The law with its tangential part when the scene needs one, and its rolling part
          // (rolling scenes are frictional and not periodic: scene_support refuses the rest);
          // the law's traits then say what is stored and integrated.
          if (scene.contact.rolling_friction > 0.0 && !scene.periodic())
            return factory::make_jet_with_law<D, Rolling<LawOf<D, true>>>(scene, ranks);
          if (scene.needs_history() || scene.needs_rotation())
            return factory::make_with_law<D, LawOf<D, true>>(scene, ranks);
          return factory::make_with_law<D, LawOf<D, false>>(scene, ranks);
        }
      });
}

}  // namespace granjet::dem
