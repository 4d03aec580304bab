// DemSimulator's parts that spread one run over MPI ranks (soft_dem/domain.hpp says how and
// why the results stay those of one rank): the grains' moves at a rebuild, the per-step sync,
// and the sums over all grains in the order one rank makes them. Included by
// dem_simulator_impl.hpp with the rest of its members.
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/merge_runs.hpp"
#include "soft_dem/dem_simulator.hpp"
#include "soft_dem/loop_weights.hpp"

namespace granjet::dem {

// Each grain's share of this rank's passes since the last look (soft_dem/loop_weights.hpp):
// the distance tests over the tested pairs, the contacts' join and evaluation over the contacts
// (a pair counts half to each of its grains), the advance over the pushed grains, the tethers
// over the target's grains, as the last pass listed them; the rest (the loop over all grains,
// Verlet's predictor, the plate) evenly. Ghosts share in the counts (their pairs are this
// rank's work) and are weighed 0 by distribute().
template <int D, class Law, bool kMono, class Space>
std::vector<double> DemSimulator<D, Law, kMono, Space>::grain_weights() {
  const typename Pass::LoopSeconds loops = pass_.take_loop_seconds();
  const double tethers = std::exchange(tether_seconds_, 0.0);
  const std::size_t n = p_.size();
  if (n == 0 || pairs_.first.size() != n + 1) return std::vector<double>(n, 1.0);  // no list yet
  std::vector<double> pairs(n, 0.0), contacts(n, 0.0), pushed(n, 0.0), wall(n, 0.0);
  for (std::uint32_t k : quiet_.tested()) {
    pairs[pair_row_[k]] += 0.5;
    pairs[pairs_.partner[k]] += 0.5;
  }
  for (std::uint32_t k : pass_.history().pairs()) {
    contacts[pair_row_[k]] += 0.5;
    contacts[pairs_.partner[k]] += 0.5;
  }
  const auto kind = p_.kind();
  for (std::size_t i = 0; i < n; ++i) {
    wall[i] = tethered_ && kind[i] == GrainKind::kWall;
    pushed[i] = (forced_[i] & 3) != 0 || wall[i] > 0.0;  // as ForcePass::update_share lists them
  }
  const std::vector<TimedLoop> timed{
      {loops.pairs, pairs}, {loops.contacts, contacts}, {loops.pushed, pushed}, {tethers, wall}};
  return spread_loop_times(threads_ * balance_.work(), n, timed);
}

template <int D, class Law, bool kMono, class Space>
std::int64_t DemSimulator<D, Law, kMono, Space>::own_contacts() const {
  std::int64_t contacts = 0;
  for (std::uint32_t k : pass_.history().pairs()) contacts += owned_[pair_row_[k]];
  return contacts;
}

template <int D, class Law, bool kMono, class Space>
GrainRecord<D> DemSimulator<D, Law, kMono, Space>::record_of(std::size_t i) const {
  GrainRecord<D> g{};
  g.id = p_.id()[i];
  g.kind = p_.kind()[i];
  put<D>(g.x, p_.position()[i]);
  put<D>(g.v, p_.velocity()[i]);
  put<D>(g.w, p_.spin()[i]);
  g.radius = p_.radius()[i];
  g.mass = p_.mass()[i];
  put<D>(g.force_prev, force_prev_[i]);
  put<D>(g.torque_prev, torque_prev_[i]);
  if (plate_ && plate_->keeps_shear()) put<D>(g.plate_shear, plate_->shear()[i]);
  return g;
}

template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::distribute(std::vector<History>& history,
                                                    std::vector<double> weight,
                                                    bool partners_elsewhere) {
  Domain<D>& domain = *domain_;
  const RankTeam& team = domain.team();
  const std::size_t n = p_.size();
  const auto x = p_.position();

  // Cut anew where the work grew uneven: each grain weighted by its share of the pass, scaled
  // so that a rank's own grains weigh its measured work (its ghosts nothing).
  const auto start = std::chrono::steady_clock::now();
  const std::optional<double> work = balance_.at_rebuild(team);
  if (work) {
    double mine = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      if (owned_[i]) mine += weight[i];
    const double scale = mine > 0.0 ? *work / mine : 1.0;
    for (std::size_t i = 0; i < n; ++i) weight[i] = owned_[i] ? scale * weight[i] : 0.0;
    domain.partition(x, weight, owned_);
  }

  // Each owned grain that leaves goes to its owner and, as a ghost, to the other ranks within
  // reach. It stays here, in place, when it stays owned or becomes a ghost here. The ghosts
  // held until now are dropped: their owners send them anew.
  const int me = domain.rank();
  std::vector<std::vector<GrainRecord<D>>> to(domain.ranks());
  std::vector<int> owner(n, -1);
  std::vector<std::uint32_t> keep;
  std::vector<std::uint8_t> keep_owned;
  keep.reserve(n);
  keep_owned.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!owned_[i]) continue;
    std::optional<GrainRecord<D>> record;
    const auto send = [&](int r, bool ghost) {
      if (!record) record = record_of(i);
      record->ghost = ghost;
      to[r].push_back(*record);
    };
    bool ghost_here = false;
    owner[i] = domain.owner_and_ghost_ranks(x[i], [&](int r) {
      if (r == me)
        ghost_here = true;
      else
        send(r, true);
    });
    if (owner[i] != me) send(owner[i], false);
    if (owner[i] != me && !ghost_here) continue;
    keep.push_back(static_cast<std::uint32_t>(i));
    keep_owned.push_back(owner[i] == me);
  }
  // A contact's history goes to the owners of its grains, from the owner of its first.
  const auto record_of_history = [](const History& h) {
    HistoryRecord<D> record{h.a, h.b, {}};
    put<D>(record.shear, h.shear);
    return record;
  };
  const auto history_of_record = [](const HistoryRecord<D>& r) -> History {
    return {r.a, r.b, get<D, Vec<D>>(r.shear)};
  };
  std::vector<std::vector<HistoryRecord<D>>> history_to(domain.ranks()), partner_unseen_to;
  if (partners_elsewhere) partner_unseen_to.resize(domain.ranks());
  std::vector<History> kept_history, partner_unseen;
  kept_history.reserve(history.size());
  for (const History& h : history) {
    const std::uint32_t a = index_of_id_[h.a], b = index_of_id_[h.b];
    if (a == kRemoved || !owned_[a]) continue;
    if (b == kRemoved) {
      if (!partners_elsewhere) continue;
      if (owner[a] == me)
        partner_unseen.push_back(h);
      else
        partner_unseen_to[owner[a]].push_back(record_of_history(h));
      continue;
    }
    const int owner_a = owner[a], owner_b = owned_[b] ? owner[b] : domain.owner_of(x[b]);
    const auto send = [&](int r) {
      if (r == me)
        kept_history.push_back(h);
      else
        history_to[r].push_back(record_of_history(h));
    };
    send(owner_a);
    if (owner_b != owner_a) send(owner_b);
  }
  const std::vector<GrainRecord<D>> arrived = domain.move(to);
  history = std::move(kept_history);
  for (const HistoryRecord<D>& r : domain.move(history_to)) history.push_back(history_of_record(r));
  if (partners_elsewhere)
    for (const HistoryRecord<D>& r : domain.move(partner_unseen_to))
      partner_unseen.push_back(history_of_record(r));

  // The kept grains stay in place or fill a dropped grain's (the rebuild's cell sort orders
  // them after), and the arrivals follow them.
  for (std::size_t k = 0; k < keep.size(); ++k) owned_[keep[k]] = keep_owned[k];
  const typename Particles<D>::Moves moves = Particles<D>::compaction(keep);
  const std::size_t kept = keep.size(), room = arrived.size();
  p_.compact(moves, kept, room);
  Particles<D>::compact_one(force_prev_, moves, kept, room);
  Particles<D>::compact_one(torque_prev_, moves, kept, room);
  Particles<D>::compact_one(inv_inertia_, moves, kept, room);
  Particles<D>::compact_one(owned_, moves, kept, room);
  if (plate_) plate_->compact(moves, kept, room);
  quiet_.compact(moves, kept, room);
  std::vector<Vec<D>>* shear = plate_ && plate_->keeps_shear() ? &plate_->shear() : nullptr;
  for (const GrainRecord<D>& g : arrived) {
    p_.add(g.id, g.kind, get<D, Vec<D>>(g.x), get<D, Vec<D>>(g.v), g.radius, g.mass);
    p_.spin().back() = get<D, Spin<D>>(g.w);
    force_prev_.push_back(get<D, Vec<D>>(g.force_prev));
    torque_prev_.push_back(get<D, Spin<D>>(g.torque_prev));
    inv_inertia_.push_back(p_.inverse_mass().back() /
                           (Dim<D>::kInertiaFactor * g.radius * g.radius));
    owned_.push_back(!g.ghost);
    if (shear) shear->push_back(get<D, Vec<D>>(g.plate_shear));
  }
  whole_fresh_ = false;
  if (work)
    balance_.recut_took(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  if (!partners_elsewhere) return;
  // The first grain of each history whose partner was not here is now owned here, and the
  // partner, within the contact's reach of it, is held here too (owned, or a ghost): the
  // history goes on to the partner's owner. A partner held nowhere was removed, as above.
  index_of_id_.assign(p_.id(), threads_);
  std::vector<std::vector<HistoryRecord<D>>> to_partner(domain.ranks());
  for (const History& h : partner_unseen) {
    const std::uint32_t b = index_of_id_[h.b];
    if (b == kRemoved) continue;
    history.push_back(h);
    if (!owned_[b]) to_partner[domain.owner_of(p_.position()[b])].push_back(record_of_history(h));
  }
  for (const HistoryRecord<D>& r : domain.move(to_partner)) history.push_back(history_of_record(r));
}

template <int D, class Law, bool kMono, class Space>
auto DemSimulator<D, Law, kMono, Space>::whole_frame(double cut) const ->
    typename CellGrid<D>::Frame {
  const RankTeam& team = domain_->team();
  std::vector<double> low(D, INFINITY), high(D, -INFINITY);
  std::int64_t grains = 0;
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (!owned_[i]) continue;
    ++grains;
    for (int d = 0; d < D; ++d) {
      low[d] = std::min(low[d], p_.position()[i][d]);
      high[d] = std::max(high[d], p_.position()[i][d]);
    }
  }
  team.min(low);
  team.max(high);
  grains = team.sum(grains);
  Vec<D> lo = Vec<D>::Zero(), hi = Vec<D>::Zero();
  if (grains > 0)
    for (int d = 0; d < D; ++d) {
      lo[d] = low[d];
      hi[d] = high[d];
    }
  return CellGrid<D>::frame_of(lo, hi, cut, static_cast<std::size_t>(grains));
}

// A ghost's state as its owner sends it after a step that pushed it: x, v, w, the forced bits
// and F(t - dt) (QuietPairs' coasting test reads it), and for velocity Verlet also M(t - dt),
// which its predictor needs; the pass here left it alone (Adams-Bashforth-2) or corrected it
// with only this rank's share of its forces (Verlet). A ghost that its owner did not push
// coasted here as there, bit for bit, from the same state with no force: its owner sends
// nothing. Where it is pushed here, a contact with a grain owned here, the plate or a tether,
// its owner pushed it too: the owner holds that grain as a ghost and lists their pair.
template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::update_ghosts() {
  const PhaseProfile::Timer timing = timer(phase_.ghosts);
  constexpr std::size_t S = kSpinWidth<D>, kForced = 3 * D + S, kTorque = kForced + 1;
  const bool torque = scene_.run.integrator == IntegratorKind::kVelocityVerlet;
  domain_->update_ghosts(
      kTorque + (torque ? S : 0), [&](std::uint32_t i) { return pass_.pushed()[i] != 0; },
      [&](std::uint32_t i, double* row) {
        put<D>(row, p_.position()[i]);
        put<D>(row + D, p_.velocity()[i]);
        put<D>(row + 2 * D, force_prev_[i]);
        put<D>(row + 3 * D, p_.spin()[i]);
        row[kForced] = forced_[i];
        if (torque) put<D>(row + kTorque, torque_prev_[i]);
      },
      [&](std::uint32_t i, const double* row) {
        p_.position()[i] = get<D, Vec<D>>(row);
        p_.velocity()[i] = get<D, Vec<D>>(row + D);
        force_prev_[i] = get<D, Vec<D>>(row + 2 * D);
        p_.spin()[i] = get<D, Spin<D>>(row + 3 * D);
        forced_[i] = static_cast<std::uint8_t>(row[kForced]);
        if (torque) torque_prev_[i] = get<D, Spin<D>>(row + kTorque);
      });
}

template <int D, class Law, bool kMono, class Space>
double DemSimulator<D, Law, kMono, Space>::agree(double own_largest_speed2) {
  const PhaseProfile::Timer timing = timer(phase_.agree);
  const Domain<D>& domain = *domain_;
  // A trusted grain pushed on any rank ends every rank's classification (ghosts are never
  // trusted: their owners watch them).
  const bool pushed = trusted_pushed_;
  // A NaN speed becomes infinite: a maximum over ranks keeps it, and the rebuild reports it.
  std::vector<double> agreed{std::isnan(own_largest_speed2) ? INFINITY : own_largest_speed2,
                             pushed ? 1.0 : 0.0, error_ ? 1.0 : 0.0,
                             this->stop_requested() ? 1.0 : 0.0};
  domain.team().max(agreed);
  if (agreed[2] > 0.0) raise_together(error_);
  if (pass_pending_) quiet_.after_pass(agreed[1] > 0.0);
  pass_pending_ = false;
  trusted_pushed_ = false;
  stop_agreed_ = agreed[3] > 0.0;
  return agreed[0];
}

// Every rank throws the blow-up of the lowest rank that found one, so that all leave together
// with the same report.
template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::raise_together(
    const std::optional<BlowUpError>& mine) const {
  const RankTeam& team = domain_->team();
  struct Head {
    std::int64_t step;
    double time;
    std::uint64_t reason, ids;
    std::uint8_t found;
  };
  Head head{};
  std::string reason;
  std::vector<GrainId> ids;
  if (mine) {
    head = {mine->step(), mine->time(), mine->reason().size(), mine->grain_ids().size(), 1};
    reason = mine->reason();
    ids = mine->grain_ids();
  }
  const std::vector<Head> heads = team.all_gather<Head>(std::vector<Head>{head});
  const std::vector<char> reasons =
      team.all_gather<char>(std::vector<char>(reason.begin(), reason.end()));
  const std::vector<GrainId> all_ids = team.all_gather<GrainId>(ids);
  std::size_t at_reason = 0, at_ids = 0;
  for (const Head& h : heads) {
    if (h.found)
      throw BlowUpError(
          std::string(reasons.begin() + at_reason, reasons.begin() + at_reason + h.reason), h.step,
          h.time, std::vector<GrainId>(all_ids.begin() + at_ids, all_ids.begin() + at_ids + h.ids));
    at_reason += h.reason;
    at_ids += h.ids;
  }
}

template <int D, class Law, bool kMono, class Space>
template <class Value, class Of, class Visit>
void DemSimulator<D, Law, kMono, Space>::for_each_in_whole_order(Of&& value_of, Visit&& visit,
                                                                 Joined where,
                                                                 std::uint64_t cells_from,
                                                                 std::uint64_t cells_to) const {
  struct Keyed {
    std::uint64_t cell;
    GrainId id;
    std::uint32_t nth;  // of the grain's values
    Value value;
  };
  // Kept from call to call: a sample's gather of every grain then writes into the memory the
  // last one used, where fresh pages would cost more than the copy itself.
  static thread_local std::vector<Keyed> mine, all;
  mine.clear();
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (!owned_[i] || whole_cell_[i] < cells_from || whole_cell_[i] >= cells_to) continue;
    std::uint32_t nth = 0;
    value_of(i, [&](const Value& v) { mine.push_back({whole_cell_[i], p_.id()[i], nth++, v}); });
  }
  // Each rank's values come in the whole order: merging its run with the others' sorts them.
  const RankTeam& team = domain_->team();
  if (where == Joined::kOnEveryRank)
    team.template all_gather_into<Keyed>(mine, all);
  else
    team.template gather_into<Keyed>(mine, all);
  for (std::uint32_t k : merged_run_order(all.size(), [&](std::size_t a, std::size_t b) {
         return std::tie(all[a].cell, all[a].id, all[a].nth) <
                std::tie(all[b].cell, all[b].id, all[b].nth);
       }))
    visit(all[k].value);
}

// The stretches are found by counting: each rank counts its values in 4,096 equal runs of the
// cells, the counts are summed over the ranks, and runs follow each other into a stretch while
// the stretch holds no more than `limit`; a run that alone holds more is counted again in
// finer runs, down to a single cell. An all-reduce per counting and a gather per stretch.
template <int D, class Law, bool kMono, class Space>
template <class Value, class Of, class Visit, class Done>
void DemSimulator<D, Law, kMono, Space>::for_each_stretch_in_whole_order(Of&& value_of,
                                                                         Visit&& visit,
                                                                         Done&& stretch_done,
                                                                         std::size_t limit) const {
  constexpr std::uint64_t kRuns = 4096;
  const RankTeam& team = domain_->team();
  std::vector<std::int64_t> values(p_.size(), 0);  // per own grain
  std::vector<double> cells{0.0};                  // exact: cells are far fewer than 2^53
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (!owned_[i]) continue;
    value_of(i, [&](const Value&) { ++values[i]; });
    cells[0] = std::max(cells[0], static_cast<double>(whole_cell_[i] + 1));
  }
  team.max(cells);
  const auto limit_values = static_cast<std::int64_t>(std::max<std::size_t>(limit, 1));
  const auto stretch = [&](std::uint64_t from, std::uint64_t to) {
    for_each_in_whole_order<Value>(value_of, visit, Joined::kOnRank0, from, to);
    stretch_done();
  };
  // Run k of [from, to) covers [from + ceil(k w / runs), from + ceil((k + 1) w / runs)).
  const std::function<void(std::uint64_t, std::uint64_t)> cover = [&](std::uint64_t from,
                                                                      std::uint64_t to) {
    const std::uint64_t width = to - from, runs = std::min(kRuns, width);
    const auto run_start = [&](std::uint64_t k) { return from + (k * width + runs - 1) / runs; };
    std::vector<std::int64_t> count(runs, 0);
    for (std::size_t i = 0; i < p_.size(); ++i)
      if (values[i] > 0 && whole_cell_[i] >= from && whole_cell_[i] < to)
        count[(whole_cell_[i] - from) * runs / width] += values[i];
    team.sum(count);
    for (std::uint64_t k = 0; k < runs;) {
      if (count[k] > limit_values && run_start(k + 1) - run_start(k) > 1) {
        cover(run_start(k), run_start(k + 1));
        ++k;
        continue;
      }
      std::uint64_t end = k + 1;
      std::int64_t held = count[k];
      while (end < runs && held + count[end] <= limit_values) held += count[end++];
      if (held > 0) stretch(run_start(k), run_start(end));
      k = end;
    }
  };
  if (cells[0] > 0.0) cover(0, static_cast<std::uint64_t>(cells[0]));
}

template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::own_share(std::vector<std::uint8_t> mine,
                                                   std::vector<std::uint64_t> whole_index) {
  owned_ = std::move(mine);
  whole_cell_ = std::move(whole_index);
  domain_->partition(p_.position(), std::vector<double>(p_.size(), 1.0), owned_);
}

// Vectors as plain rows of doubles for the sums in whole order (ids too: exact below 2^53).
template <int N>
using Row = std::array<double, N>;
template <int D, int N>
void put_row(Row<N>& row, int at, const Vec<D>& v) {
  for (int d = 0; d < D; ++d) row[at + d] = v[d];
}
template <int D, int N>
Vec<D> get_row(const Row<N>& row, int at) {
  Vec<D> v;
  for (int d = 0; d < D; ++d) v[d] = row[at + d];
  return v;
}

// This rank's archive, split over the ranks (StateArchive::split_over): what all ranks hold
// alike, and as its share its own grains with their per-grain state, in its order, and the
// contacts whose first grain it owns. Rank 0 stores the shares one rank at a time, so no rank
// gathers the whole run; a resume on any count of ranks joins them, and its rebuild puts the
// grains in the order of one rank (CellGrid orders by position and id alone).
template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::checkpoint_over_ranks(StateArchive& a) {
  rebuild();
  a.split_over(domain_->ranks(), {"dem/grains/", "dem/force_prev", "dem/torque_prev",
                                  "dem/plate_shear", "dem/history/"});
  std::vector<std::uint32_t> own;
  for (std::size_t i = 0; i < p_.size(); ++i)
    if (owned_[i]) own.push_back(static_cast<std::uint32_t>(i));
  const auto only_own = [&](auto values) {
    Particles<D>::gather_one(values, own);
    return values;
  };
  Particles<D> grains = p_;
  grains.gather(own);
  put_particles(a, "dem/grains", grains);
  a.put_rows<Vec<D>>("dem/force_prev", only_own(force_prev_));
  a.put_rows<Spin<D>>("dem/torque_prev", only_own(torque_prev_));
  a.put_rows<Vec<D>>("dem/plate_shear", plate_ && plate_->keeps_shear() ? only_own(plate_->shear())
                                                                        : std::vector<Vec<D>>());
  std::vector<GrainId> pair;
  std::vector<Vec<D>> shear;
  for (const History& h : histories()) {
    if (!owned_[index_of_id_[h.a]]) continue;
    pair.insert(pair.end(), {h.a, h.b});
    shear.push_back(h.shear);
  }
  put_histories_and_counters(a, pair, shear, stats());
}

template <int D, class Law, bool kMono, class Space>
template <class Emit>
void DemSimulator<D, Law, kMono, Space>::contact_transfers_of(std::size_t i, double elapsed,
                                                              const SampleRegion* region,
                                                              Emit&& emit) const {
  const auto x = p_.position();
  const auto id = p_.id();
  for_each_contact_of(
      i,
      [&](std::size_t j, std::uint32_t k, const ContactGeometry<D>& g, const Vec<D>& v_rel) {
        const Vec<D> at_j = x[i] - space_.separation(x[i], x[j]);
        if (region != nullptr && !region->holds_transfer<D>(x[i], at_j)) return;
        Vec<D> shear = pass_.history().of(k);  // a copy: sampling must not advance it
        const Vec<D> f = law_.force(g, v_rel, shear);
        emit(PairImpulse<D>{id[i], id[j], x[i], at_j, elapsed * f});
      },
      [](std::uint32_t) {});
}

template <int D, class Law, bool kMono, class Space>
template <class Emit>
void DemSimulator<D, Law, kMono, Space>::plate_transfer_of(std::size_t i, double elapsed,
                                                           const SampleRegion* region,
                                                           Emit&& emit) const {
  const auto x = p_.position();
  plate_->contact(
      x[i], radius_of(p_.radius(), i), p_.velocity()[i], p_.spin()[i],
      [&](const ContactGeometry<D>& g, const Vec<D>& v_rel) {
        const Vec<D> image = plate_->mirror(x[i]);
        if (region != nullptr && !region->holds_transfer<D>(x[i], image)) return;
        const Vec<D> f = plate_->force(i, g, v_rel);
        emit(PairImpulse<D>{p_.id()[i], kPlateId, x[i], image, elapsed * f});
      },
      [] {});
}

template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::collect_transfers_over_ranks(
    std::vector<PairImpulse<D>>& out, double elapsed, const SampleRegion* region) const {
  constexpr int N = 2 + 3 * D;
  const auto row_of = [](const PairImpulse<D>& t) {
    Row<N> row{static_cast<double>(t.i), static_cast<double>(t.j)};
    put_row<D, N>(row, 2, t.position_i);
    put_row<D, N>(row, 2 + D, t.position_j);
    put_row<D, N>(row, 2 + 2 * D, t.impulse);
    return row;
  };
  const auto take = [&](const Row<N>& r) {
    out.push_back({static_cast<GrainId>(r[0]), static_cast<GrainId>(r[1]), get_row<D, N>(r, 2),
                   get_row<D, N>(r, 2 + D), get_row<D, N>(r, 2 + 2 * D)});
  };
  for_each_in_whole_order<Row<N>>(
      [&](std::size_t i, auto emit) {
        contact_transfers_of(i, elapsed, region, [&](const PairImpulse<D>& t) { emit(row_of(t)); });
      },
      take, Joined::kOnRank0);
  if (plate_)
    for_each_in_whole_order<Row<N>>(
        [&](std::size_t i, auto emit) {
          plate_transfer_of(i, elapsed, region, [&](const PairImpulse<D>& t) { emit(row_of(t)); });
        },
        take, Joined::kOnRank0);
}

// Over ranks each rank hands its sampler the grains it owns that `region` holds, every target
// grain it holds (the sampler tells target grains by id, and a contact with one may be listed
// on any rank that holds it), and the transfers it lists: each contact on one rank, as the
// gather of collect_transfers_in would list it, so the sampler's sums, joined, are those of
// one process.
template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::sample_own(const SampleRegion& region, double elapsed,
                                                    OwnSampler<D>& sampler) {
  if (!over_ranks()) return Simulator<D>::sample_own(region, elapsed, sampler);
  own_sample_.clear();
  const auto kind = p_.kind();
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (!(owned_[i] || kind[i] == GrainKind::kWall) ||
        !region.holds_grain<D>(p_.position()[i], p_.radius()[i], kind[i]))
      continue;
    own_sample_.add(p_.id()[i], kind[i], p_.position()[i], p_.velocity()[i], p_.radius()[i],
                    p_.mass()[i]);
    own_sample_.spin().back() = p_.spin()[i];
  }
  std::vector<PairImpulse<D>> own_transfers;
  const double covered = time() - last_collect_time_;
  last_collect_time_ = time();
  const auto take = [&](const PairImpulse<D>& t) { own_transfers.push_back(t); };
  for (std::size_t i = 0; i < p_.size(); ++i)
    if (owned_[i]) contact_transfers_of(i, covered, &region, take);
  if (plate_)
    for (std::size_t i = 0; i < p_.size(); ++i)
      if (owned_[i]) plate_transfer_of(i, covered, &region, take);
  sampler.sample(own_sample_, own_transfers, elapsed);
}

template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::join_samples(OwnSampler<D>& sampler) {
  if (over_ranks()) sampler.join(domain_->team());
}

// Each grain's total force from all its contacts here, in list order as on one rank, then the
// plate and the tethers: whole for the grains owned here.
template <int D, class Law, bool kMono, class Space>
std::vector<Vec<D>> DemSimulator<D, Law, kMono, Space>::force_totals_here() const {
  std::vector<Vec<D>> total(p_.size(), Vec<D>::Zero());
  for_each_contact(
      [&](std::size_t i, std::size_t j, std::uint32_t k, const ContactGeometry<D>& g,
          const Vec<D>& v_rel) {
        Vec<D> shear = pass_.history().of(k);
        const Vec<D> f = law_.force(g, v_rel, shear);
        total[i] += f;
        total[j] -= f;
      },
      [](std::uint32_t) {});
  for_each_plate_contact([&](std::size_t i, const ContactGeometry<D>& g, const Vec<D>& v_rel) {
    if (owned_[i]) total[i] += plate_->force(i, g, v_rel);
  });
  if (tethered_) wall_.add_forces(p_, std::span<Vec<D>>(total));
  return total;
}

// A contact as a row of numbers: i, j, the overlap, the normal and tangential forces.
template <int D>
using ContactRow = Row<3 + 2 * D>;
template <int D>
typename ForceSample<D>::Contact contact_of_row(const ContactRow<D>& r) {
  constexpr int N = 3 + 2 * D;
  return {static_cast<GrainId>(r[0]), static_cast<GrainId>(r[1]), get_row<D, N>(r, 3),
          get_row<D, N>(r, 3 + D), r[2]};
}

template <int D, class Law, bool kMono, class Space>
template <class Join>
void DemSimulator<D, Law, kMono, Space>::join_contacts(Join&& join) const {
  constexpr int N = 3 + 2 * D;
  const auto id = p_.id();
  const auto split = [&](GrainId i, GrainId j, const ContactGeometry<D>& g, const Vec<D>& f) {
    // A law that turns no grain has no tangential force: projecting would only add rounding.
    const Vec<D> normal = kRotation ? Vec<D>(f.dot(g.n) * g.n) : f;
    ContactRow<D> row{static_cast<double>(i), static_cast<double>(j), g.overlap};
    put_row<D, N>(row, 3, normal);
    put_row<D, N>(row, 3 + D, f - normal);
    return row;
  };
  join([&](std::size_t i, auto emit) {
    for_each_contact_of(
        i,
        [&](std::size_t j, std::uint32_t k, const ContactGeometry<D>& g, const Vec<D>& v_rel) {
          Vec<D> shear = pass_.history().of(k);
          emit(split(id[i], id[j], g, law_.force(g, v_rel, shear)));
        },
        [](std::uint32_t) {});
  });
  if (!plate_) return;
  join([&](std::size_t i, auto emit) {
    plate_->contact(
        p_.position()[i], radius_of(p_.radius(), i), p_.velocity()[i], p_.spin()[i],
        [&](const ContactGeometry<D>& g, const Vec<D>& v_rel) {
          emit(split(id[i], kPlateId, g, plate_->force(i, g, v_rel)));
        },
        [] {});
  });
}

// The contacts of all ranks on rank 0, in the order of one rank.
template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::contacts_on_rank0(
    std::vector<typename ForceSample<D>::Contact>& out) const {
  join_contacts([&](auto&& value_of) {
    for_each_in_whole_order<ContactRow<D>>(
        value_of, [&](const ContactRow<D>& r) { out.push_back(contact_of_row<D>(r)); },
        Joined::kOnRank0);
  });
}

// A frame's contacts come to rank 0 in stretches of about as many as a block of grains, each
// handed on as one piece, in the order of one rank.
template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::frame_contacts(const FrameAsk& ask,
                                                        FrameSink<D>& sink) const {
  static thread_local std::vector<typename ForceSample<D>::Contact> piece;  // memory kept
  piece.clear();
  const bool writer = domain_->team().rank() == 0;
  join_contacts([&](auto&& value_of) {
    for_each_stretch_in_whole_order<ContactRow<D>>(
        value_of, [&](const ContactRow<D>& r) { piece.push_back(contact_of_row<D>(r)); },
        [&] {
          if (writer) sink.contacts(piece);
          piece.clear();
        },
        ask.block_rows);
  });
}

template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::sample_forces_over_ranks(ForceSample<D>& out) const {
  contacts_on_rank0(out.contacts);
  const std::vector<Vec<D>> total = force_totals_here();
  out.total.clear();
  for (const Row<D>&r : in_whole_order_on_rank0<Row<D>>([&](std::size_t i, auto emit) {
         Row<D> row;
         put_row<D, D>(row, 0, total[i]);
         emit(row);
       }))
    out.total.push_back(get_row<D, D>(r, 0));
}

template <int D, class Law, bool kMono, class Space>
std::size_t DemSimulator<D, Law, kMono, Space>::grain_count() const {
  if (!over_ranks()) return p_.size();
  return static_cast<std::size_t>(domain_->team().sum(
      static_cast<std::int64_t>(std::count(owned_.begin(), owned_.end(), std::uint8_t{1}))));
}

// Over ranks each block of ids comes to rank 0 from every rank at once (a gather per block):
// rank 0 holds one block of grains, never the whole run, and writes it as one stretch of rows.
// A grain whose id lies beyond the rows goes with the last block, where the sink refuses it as
// on one rank.
template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::frame(const FrameAsk& ask, FrameSink<D>& sink) const {
  if (!over_ranks()) return Simulator<D>::frame(ask, sink);
  frame_grains(ask, sink);
  if (ask.contacts) frame_contacts(ask, sink);
}

template <int D, class Law, bool kMono, class Space>
void DemSimulator<D, Law, kMono, Space>::frame_grains(const FrameAsk& ask,
                                                      FrameSink<D>& sink) const {
  struct Grain {  // what Particles holds of a grain, and its total force
    GrainId id;
    GrainKind kind;
    double x[D], v[D], w[kSpinWidth<D>], f[D], radius, mass;
  };
  const RankTeam& team = domain_->team();
  const std::vector<Vec<D>> total = ask.force ? force_totals_here() : std::vector<Vec<D>>();
  const std::size_t per_block = std::max<std::size_t>(ask.block_rows, 1);
  const std::size_t blocks = std::max<std::size_t>((ask.rows + per_block - 1) / per_block, 1);
  const auto block_of = [&](GrainId id) {
    return std::min(static_cast<std::size_t>(std::max<GrainId>(id, 0)) / per_block, blocks - 1);
  };
  // This rank's own grains by block (counting sort: each block's grains in the order held).
  std::vector<std::uint32_t> start(blocks + 1, 0), own;
  for (std::size_t i = 0; i < p_.size(); ++i)
    if (owned_[i]) ++start[block_of(p_.id()[i]) + 1];
  for (std::size_t b = 0; b < blocks; ++b) start[b + 1] += start[b];
  own.resize(start[blocks]);
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < p_.size(); ++i)
    if (owned_[i]) own[fill[block_of(p_.id()[i])]++] = static_cast<std::uint32_t>(i);
  // Kept from frame to frame, as in for_each_in_whole_order: fresh pages for a stretch cost
  // more than filling it.
  static thread_local std::vector<Grain> mine, all;
  static thread_local Particles<D> block;
  static thread_local std::vector<Vec<D>> force;
  for (std::size_t b = 0; b < blocks; ++b) {
    mine.clear();
    for (std::uint32_t k = start[b]; k < start[b + 1]; ++k) {
      const std::uint32_t i = own[k];
      Grain g{p_.id()[i], p_.kind()[i], {}, {}, {}, {}, p_.radius()[i], p_.mass()[i]};
      put<D>(g.x, p_.position()[i]);
      put<D>(g.v, p_.velocity()[i]);
      put<D>(g.w, p_.spin()[i]);
      if (ask.force) put<D>(g.f, total[i]);
      mine.push_back(g);
    }
    team.template gather_into<Grain>(mine, all);
    if (team.rank() != 0) continue;
    block.clear();
    force.clear();
    for (const Grain& g : all) {
      block.add(g.id, g.kind, get<D, Vec<D>>(g.x), get<D, Vec<D>>(g.v), g.radius, g.mass);
      block.spin().back() = get<D, Spin<D>>(g.w);
      if (ask.force) force.push_back(get<D, Vec<D>>(g.f));
    }
    const auto first = static_cast<GrainId>(b * per_block);
    const auto end = static_cast<GrainId>(std::min((b + 1) * per_block, ask.rows));
    sink.grains(first, end, block, force);
  }
}

}  // namespace granjet::dem
