#include "event_driven/ed_simulator.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/collision_rules.hpp"
#include "core/errors.hpp"
#include "core/initial_state.hpp"
#include "core/jet_geometry.hpp"
#include "event_driven/scene_support.hpp"

namespace granjet::ed {
namespace {

// Events per free grain between two moves of the time origin: rare enough to cost nothing,
// often enough that event times stay within a few collision times of zero.
constexpr std::int64_t kShiftEventsPerGrain = 32;
// A pair that collided last with each other and still touches within this fraction of sigma^2
// is separating: an approach seen there is round-off (an echo of the collision), not a new one.
constexpr double kEchoTolerance = 1e-9;
// Verification: collisions at contact and no overlaps, within this fraction of sigma.
constexpr double kContactTolerance = 1e-9;
// The time of a runner-up prediction that is not known.
constexpr double kUnknown = -kNever;

template <int D>
double largest_diameter(const Particles<D>& p) {
  double r = 0.0;
  for (double x : p.radius()) r = std::max(r, x);
  return 2.0 * r;
}

// Neighbour lists with shells (event_driven/neighbour_shells.hpp) serve dense 3D periodic gases,
// the cells with crossings the rest: lists scan fewer grains per prediction, but a dilute gas
// renews them so often (each renewal a scan of 27 wide cells) that the cells win below
// kListedPhi, the crossover measured with BM_EdGas3d (N = 10,976, one core).
constexpr double kListedPhi = 0.4;

template <int D>
bool listed(const Scene& scene, const Particles<D>& p, NeighbourSearch search) {
  return search == NeighbourSearch::kByDensity && D == 3 && scene.periodic() &&
         scene.gas.phi >= kListedPhi &&
         NeighbourShells<D>::fits(gas_lattice<D>(scene.gas).box, largest_diameter(p));
}

// Periodic scenes tile their box; open scenes cover the grains' bounding box, for the jets also
// the removal region, with two cells to spare so that a grain leaving the region still crosses
// a cell face (the moment it is removed).
template <int D>
CellList<D> make_cells(const Scene& scene, const Particles<D>& p) {
  const double d = largest_diameter(p);
  const Vec<D> box = gas_lattice<D>(scene.gas).box;
  if (scene.periodic()) return CellList<D>::periodic(box, d, p.size());
  Vec<D> lo = Vec<D>::Zero(), hi = Vec<D>::Zero();
  if (!p.empty()) lo = hi = p.position()[0];
  for (const Vec<D>& x : p.position()) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  if (scene.has_wall()) {
    for (int a = 0; a < D; ++a) {
      if (a == kJetAxis<D>) {
        lo[a] = std::min(lo[a], -scene.region.below);
      } else {
        lo[a] = std::min(lo[a], -scene.region.radius);
        hi[a] = std::max(hi[a], scene.region.radius);
      }
    }
  }
  const Vec<D> margin = Vec<D>::Constant(2.5 * d);
  return CellList<D>::open(lo - margin, hi + margin, d, p.size());
}

}  // namespace

template <int D>
EdSimulator<D>::EdSimulator(const Scene& scene, Particles<D> grains, Verification verify,
                            NeighbourSearch search)
    : scene_(scene),
      grains_(std::move(grains)),
      verify_(verify),
      restitution_(scene),
      plate_partner_(static_cast<std::uint32_t>(grains_.size())),
      cells_(make_cells<D>(scene, grains_)),
      calendar_(grains_.size()),
      collapse_(grains_.size()) {
  const std::size_t n = grains_.size();
  if (scene.has_plate()) plate_.emplace(scene.wall.diameter);
  if (listed(scene, grains_, search))
    shells_.emplace(std::vector<double>(grains_.radius().begin(), grains_.radius().end()),
                    gas_lattice<D>(scene.gas).box);
  flight_.resize(n);
  std::int64_t free_grains = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    Flight<D>& f = flight_[i];
    f.x = grains_.position()[i];
    f.v = fixed(i) ? Vec<D>::Zero() : grains_.velocity()[i];
    f.radius = grains_.radius()[i];
    free_grains += !fixed(i);
  }
  last_partner_.resize(n);
  for (std::uint32_t i = 0; i < n; ++i) last_partner_[i] = i;
  last_collision_.assign(n, -kNever);
  alive_.assign(n, 1);
  shift_every_ = kShiftEventsPerGrain * std::max<std::int64_t>(1, free_grains);
  predict_anew();
  initial_energy_ = energy().total() + removed_energy_;  // removed at the start counts
  if (verify_ == Verification::kOn) check_no_overlaps();
}

template <int D>
void EdSimulator<D>::predict_anew() {
  const std::size_t n = flight_.size();
  cells_ = make_cells<D>(scene_, grains_);
  if (shells_) {
    // Every grain is at the clock here: its position in the box becomes its centre.
    std::vector<Vec<D>> x(n);
    for (std::uint32_t i = 0; i < n; ++i) x[i] = flight_[i].x = cells_.wrap(flight_[i].x);
    shells_->build(x, alive_);
  } else {
    for (std::uint32_t i = 0; i < n; ++i)
      if (alive_[i]) cells_.insert(i, flight_[i].x);
  }
  calendar_ = Calendar(n);
  collapse_ = CollapseDetector(n);
  collapse_.set_flight_time(flight_time());
  next_collision_.assign(n, Prediction{});
  runner_up_.assign(n, Prediction{});
  next_exit_.assign(n, Crossing{});
  events_of_.assign(n + 1, 0);
  for (std::uint32_t i = 0; i < n; ++i) {
    if (fixed(i) || !alive_[i]) continue;
    predict_all(i);
    predict_exit(i);
    schedule(i);
  }
}

// Every grain streamed to the checkpoint's time, which becomes the clock's zero, then every
// event predicted anew: a simulator of the same scene that takes the flights does the same.
template <int D>
void EdSimulator<D>::checkpoint(StateArchive& a) {
  clock_ = time_ - origin_;  // no event lies between the last one and time_
  shift_time_origin();
  predict_anew();
  std::vector<Vec<D>> x, v;
  for (const Flight<D>& f : flight_) {
    x.push_back(f.x);
    v.push_back(f.v);
  }
  a.put_rows<Vec<D>>("ed/x", x);
  a.put_rows<Vec<D>>("ed/v", v);
  a.put_values<std::uint8_t>("ed/alive", alive_);
  a.put_values<std::uint32_t>("ed/last_partner", last_partner_);
  a.put_rows<double>("ed/last_collision", last_collision_);  // the tc_model's clocks
  a.put("ed/origin", origin_);
  a.put("ed/initial_energy", initial_energy_);
  a.put("ed/removed_energy", removed_energy_);
  put_stats(a, "ed/stats", stats_);
  std::vector<GrainId> pair;
  std::vector<Vec<D>> at_i, at_j, impulse;
  for (const PairImpulse<D>& t : transfers_) {
    pair.insert(pair.end(), {t.i, t.j});
    at_i.push_back(t.position_i);
    at_j.push_back(t.position_j);
    impulse.push_back(t.impulse);
  }
  a.put_values<GrainId>("ed/transfers/pair", pair);
  a.put_rows<Vec<D>>("ed/transfers/position_i", at_i);
  a.put_rows<Vec<D>>("ed/transfers/position_j", at_j);
  a.put_rows<Vec<D>>("ed/transfers/impulse", impulse);
}

template <int D>
void EdSimulator<D>::restore(const StateArchive& a) {
  const std::size_t n = flight_.size();
  const auto x = a.rows<Vec<D>>("ed/x");
  const auto v = a.rows<Vec<D>>("ed/v");
  const auto alive = a.values<std::uint8_t>("ed/alive");
  const auto last_partner = a.values<std::uint32_t>("ed/last_partner");
  const auto last_collision = a.rows<double>("ed/last_collision");
  if (x.size() != n || v.size() != n || alive.size() != n || last_partner.size() != n ||
      last_collision.size() != n)
    throw std::runtime_error("checkpoint holds " + std::to_string(x.size()) +
                             " event-driven grains; this scene builds " + std::to_string(n));
  for (std::size_t i = 0; i < n; ++i) {
    flight_[i].x = x[i];
    flight_[i].v = v[i];
    flight_[i].t = 0.0;
  }
  alive_ = alive;
  last_partner_ = last_partner;
  last_collision_ = last_collision;
  origin_ = time_ = a.real("ed/origin");
  clock_ = 0.0;
  events_since_shift_ = 0;
  initial_energy_ = a.real("ed/initial_energy");
  removed_energy_ = a.real("ed/removed_energy");
  stats_ = get_stats(a, "ed/stats");
  const auto pair = a.values<GrainId>("ed/transfers/pair");
  const auto at_i = a.rows<Vec<D>>("ed/transfers/position_i");
  const auto at_j = a.rows<Vec<D>>("ed/transfers/position_j");
  const auto impulse = a.rows<Vec<D>>("ed/transfers/impulse");
  transfers_.clear();
  for (std::size_t k = 0; k < impulse.size(); ++k)
    transfers_.push_back({pair.at(2 * k), pair.at(2 * k + 1), at_i.at(k), at_j.at(k), impulse[k]});
  predict_anew();
  snapshot_removed_ = -1;  // other grains than the constructor's snapshot
  snapshot_current_ = false;
}

template <int D>
void EdSimulator<D>::advance_to(double t) {
  bool stopped = false;
  while (!calendar_.empty()) {
    const CalendarEntry next = calendar_.top();
    if (next.time > t - origin_) break;
    if ((stopped = this->stop_requested())) break;
    clock_ = next.time;
    process(next.grain);
    if (++events_since_shift_ >= shift_every_) shift_time_origin();
  }
  time_ = std::max(time_, stopped ? origin_ + clock_ : t);
  snapshot_current_ = false;
  if (verify_ == Verification::kOn) check_no_overlaps();
}

template <int D>
void EdSimulator<D>::process(std::uint32_t i) {
  ++stats_.events;
  if (next_exit_[i].time <= next_collision_[i].time) {
    if (shells_)
      renew_shell(i);
    else
      cross_cell(i);
  } else if (still_valid(next_collision_[i])) {
    if (next_collision_[i].partner == plate_partner_)
      hit_plate(i);
    else
      collide(i, next_collision_[i].partner);
  } else {
    // Stale: the partner collided with someone else since the prediction. The runner-up, if
    // still valid, is the earliest of the others (the stale partner has scanned i itself).
    if (runner_up_[i].time != kUnknown && still_valid(runner_up_[i])) {
      next_collision_[i] = runner_up_[i];
      runner_up_[i].time = kUnknown;
    } else {
      predict_all(i);
    }
    schedule(i);
  }
}

// Collision [2.1]-[2.2] through the core rule, at the restitution of the scene's law.
template <int D>
void EdSimulator<D>::collide(std::uint32_t i, std::uint32_t j) {
  Flight<D>& fi = flight_[i];
  Flight<D>& fj = flight_[j];
  const bool j_moves = !fixed(j);
  if (shells_) {
    // Both grains scan their lists below: their partners' flights are fetched meanwhile.
    for (std::uint32_t k : shells_->of(i)) __builtin_prefetch(&flight_[k]);
    for (std::uint32_t k : shells_->of(j)) __builtin_prefetch(&flight_[k]);
  }
  fi.stream_to(clock_);
  if (j_moves) fj.stream_to(clock_);
  const Vec<D> dr = cells_.minimum_image(fj.x - fi.x);
  const double distance = dr.norm();
  const Vec<D> n = dr / distance;
  const double v_n = n.dot(fi.v - fj.v);
  // Marked even when nothing happens below, so that the rescans see the pair as separating.
  last_partner_[i] = j;
  if (j_moves) last_partner_[j] = i;
  // v_n <= 0: a grazing touch that round-off predicted as an approach; no impulse.
  if (v_n > 0.0) {
    if (verify_ == Verification::kOn) check_contact(i, j, distance);
    const double e = restitution_(v_n, clock_ - last_collision_[i],
                                  j_moves ? clock_ - last_collision_[j] : kNever);
    const auto inv_m = grains_.inverse_mass();
    const Vec<D> impulse = granjet::collide(n, fi.v, fj.v, inv_m[i], inv_m[j], e);
    if (recording_)
      transfers_.push_back({grains_.id()[i], grains_.id()[j], fi.x, fi.x + dr, impulse});
    ++stats_.collisions;
    ++events_of_[i];
    last_collision_[i] = clock_;
    bool collapsing = collapse_.collided(i, clock_);
    if (j_moves) {
      ++events_of_[j];
      last_collision_[j] = clock_;
      collapsing = collapse_.collided(j, clock_) || collapsing;
    }
    if (collapsing) report_collapse(i, j);
  }
  predict_all(i);
  predict_exit(i);
  schedule(i);
  if (j_moves) {
    predict_all(j);
    predict_exit(j);
    schedule(j);
  }
}

// [2.1]-[2.2] against the plate: an infinite-mass partner at rest, normal k towards the face
// point nearest the grain (on the face, or a 2D end point).
template <int D>
void EdSimulator<D>::hit_plate(std::uint32_t i) {
  Flight<D>& f = flight_[i];
  f.stream_to(clock_);
  const Vec<D> k = plate_->inward(f.x);
  const double v_n = k.dot(f.v);  // > 0: predicted only for a grain closing on the plate
  if (verify_ == Verification::kOn) check_plate_contact(i);
  const double e = restitution_(v_n, clock_ - last_collision_[i], kNever);
  Vec<D> plate_v = Vec<D>::Zero();
  const Vec<D> impulse = granjet::collide(k, f.v, plate_v, grains_.inverse_mass()[i], 0.0, e);
  if (recording_)
    transfers_.push_back({grains_.id()[i], kPlateId, f.x, plate_->mirror(f.x), impulse});
  ++stats_.collisions;
  ++events_of_[i];
  last_partner_[i] = plate_partner_;
  last_collision_[i] = clock_;
  if (collapse_.collided(i, clock_)) report_collapse(i, i);
  predict_all(i);
  predict_exit(i);
  schedule(i);
}

template <int D>
void EdSimulator<D>::cross_cell(std::uint32_t i) {
  ++stats_.cell_crossings;
  Flight<D>& f = flight_[i];
  f.stream_to(clock_);
  const Crossing moved = next_exit_[i];
  f.x += cells_.move(i, moved.axis, moved.direction);
  if (scene_.has_wall() && grains_.kind()[i] == GrainKind::kFree &&
      outside_region<D>(scene_.region, f.x)) {
    remove(i);
    return;
  }
  // The kept prediction is the earliest over the cells scanned before; only the new layer
  // can add an earlier one, unless the kept one went stale.
  if (still_valid(next_collision_[i]))
    predict_new_layer(i, moved);
  else
    predict_all(i);
  predict_exit(i);
  schedule(i);
}

// The grain has left the shell of its list: its position, back in the box, is the new centre;
// the new list may hold an earlier collision than the old one, so it is scanned in full.
template <int D>
void EdSimulator<D>::renew_shell(std::uint32_t i) {
  ++stats_.neighbour_rebuilds;
  Flight<D>& f = flight_[i];
  f.stream_to(clock_);
  f.x = cells_.wrap(f.x);
  shells_->renew(i, f.x);
  predict_all(i);
  predict_exit(i);
  schedule(i);
}

template <int D>
void EdSimulator<D>::remove(std::uint32_t i) {
  const Flight<D>& f = flight_[i];
  removed_energy_ += 0.5 * grains_.mass()[i] * f.v.squaredNorm();
  const double r = grains_.radius()[i];
  removed_energy_ += 0.5 * Dim<D>::kInertiaFactor * grains_.mass()[i] * r * r *
                     Dim<D>::spin_dot(grains_.spin()[i], grains_.spin()[i]);
  cells_.remove(i);
  calendar_.cancel(i);
  alive_[i] = 0;
  ++events_of_[i];  // predictions with i as partner go stale
  ++stats_.removed;
}

template <int D>
void EdSimulator<D>::predict_all(std::uint32_t i) {
  if (shells_) {
    // Periodic, no plate. Listed grains drift up to a shell beyond the box: nearest images.
    const std::span<const std::uint32_t> list = shells_->of(i);
    const PeriodicBox<D>& space = cells_.space();
    merge(i, list.data(), list.size(),
          NearestImage<D>{flight_[i].position_at(clock_), space.box, space.inv_box}, Prediction{},
          Prediction{});
    return;
  }
  cells_.gather(i, hood_);
  Prediction plate;
  if (plate_) {
    const Flight<D>& f = flight_[i];
    plate.time = clock_ + plate_->contact_delay(f.position_at(clock_), f.v, f.radius);
    plate.partner = plate_partner_;
  }
  merge_hood(i, plate, Prediction{});
}

template <int D>
void EdSimulator<D>::predict_new_layer(std::uint32_t i, const Crossing& moved) {
  cells_.gather_new_layer(i, moved.axis, moved.direction, hood_);
  merge_hood(i, next_collision_[i], runner_up_[i]);
}

template <int D>
void EdSimulator<D>::merge_hood(std::uint32_t i, Prediction best, Prediction second) {
  const Vec<D> x_i = flight_[i].position_at(clock_);
  // Most stencils do not wrap around the box: their scans skip the shifts, as good as zero.
  if (hood_.shifted)
    merge(i, hood_.grain.data(), hood_.size,
          ShiftedImage<D>{x_i, hood_.shift.data(), hood_.image.data()}, best, second);
  else
    merge(i, hood_.grain.data(), hood_.size, SameImage<D>{x_i}, best, second);
}

// The earliest two of the scan (event_driven/contact_scan.hpp, vector code), merged as if each
// grain were merged in turn, in the order of the list: an unknown runner-up (kUnknown) stays
// unknown unless a new earliest displaces the old.
template <int D>
template <class Separation>
void EdSimulator<D>::merge(std::uint32_t i, const std::uint32_t* grain, std::size_t n,
                           const Separation& separation, Prediction best, Prediction second) {
  // The pair that collided last with each other (neither has changed velocity since, or the
  // partner is fixed) and still touches is separating, whatever the rounded dr.dv says.
  const std::uint32_t last = last_partner_[i];
  const bool mutual =
      last < flight_.size() && last != i && (fixed(last) || last_partner_[last] == i);
  const Scanner<D> self{clock_, flight_[i].v, flight_[i].radius,
                        mutual ? static_cast<std::int32_t>(last) : -1, kEchoTolerance};
  const Earliest e = earliest_contacts(self, flight_.data(), grain, n, separation);
  for (const auto& [when, m] : {std::pair{e.first, e.first_at}, std::pair{e.second, e.second_at}}) {
    if (when >= best.time && when >= second.time) continue;
    const std::uint32_t k = grain[m];
    const Prediction found{when, k, events_of_[k]};
    if (when < best.time) {
      second = best;
      best = found;
    } else {
      second = found;
    }
  }
  next_collision_[i] = best;
  runner_up_[i] = second;
}

template <int D>
void EdSimulator<D>::predict_exit(std::uint32_t i) {
  const Flight<D>& f = flight_[i];
  if (shells_) {
    next_exit_[i] = {std::max(clock_, f.t + shells_->exit_delay(i, f.x, f.v)), 0, 0};
    return;
  }
  const typename CellList<D>::Exit exit = cells_.next_exit(i, f.x, f.v);
  next_exit_[i] = {std::max(clock_, f.t + exit.delay), exit.axis, exit.direction};
}

template <int D>
void EdSimulator<D>::schedule(std::uint32_t i) {
  const double when = std::min(next_collision_[i].time, next_exit_[i].time);
  if (when == kNever)
    calendar_.cancel(i);
  else
    calendar_.schedule(i, when);
}

// Streams every grain to the clock and makes the clock zero; the event order is unchanged.
template <int D>
void EdSimulator<D>::shift_time_origin() {
  const double dt = clock_;
  for (std::uint32_t i = 0; i < flight_.size(); ++i) {
    if (alive_[i] && !fixed(i)) {
      flight_[i].stream_to(clock_);
      flight_[i].t = 0.0;
    }
    next_collision_[i].time -= dt;
    runner_up_[i].time -= dt;
    next_exit_[i].time -= dt;
    last_collision_[i] -= dt;
  }
  calendar_.shift(dt);
  collapse_.shift(dt);
  collapse_.set_flight_time(flight_time());
  origin_ += dt;
  clock_ = 0.0;
  events_since_shift_ = 0;
}

// Smallest diameter over the rms speed of the moving grains (kNever when nothing moves).
template <int D>
double EdSimulator<D>::flight_time() const {
  double sum_v2 = 0.0, d_min = kNever;
  std::int64_t moving = 0;
  for (std::uint32_t i = 0; i < flight_.size(); ++i) {
    if (!alive_[i] || fixed(i)) continue;
    sum_v2 += flight_[i].v.squaredNorm();
    d_min = std::min(d_min, 2.0 * flight_[i].radius);
    ++moving;
  }
  return sum_v2 > 0.0 ? d_min / std::sqrt(sum_v2 / moving) : kNever;
}

template <int D>
void EdSimulator<D>::report_collapse(std::uint32_t i, std::uint32_t j) const {
  std::vector<GrainId> ids{grains_.id()[i]};
  if (j != i) ids.push_back(grains_.id()[j]);
  for (std::uint32_t g : collapse_.streaking(clock_)) {
    if (ids.size() >= 12) break;
    if (std::find(ids.begin(), ids.end(), grains_.id()[g]) == ids.end())
      ids.push_back(grains_.id()[g]);
  }
  std::ostringstream what;
  what << "inelastic collapse: grain " << grains_.id()[i] << " collided "
       << CollapseDetector::kCollisions << " times while the clock advanced less than "
       << CollapseDetector::kSpan << " free-flight times; ";
  switch (scene_.ed.restitution_law) {
    case RestitutionLaw::kConstant:
      what << "a constant restitution cannot resolve it: use ed.restitution_law = "
              "velocity_dependent or tc_model";
      break;
    case RestitutionLaw::kVelocityDependent:
      what << "raise ed.v0 (slow collisions more elastic) or use ed.restitution_law = tc_model";
      break;
    case RestitutionLaw::kTcModel:
      what << "raise ed.tc or use ed.restitution_law = velocity_dependent";
      break;
  }
  throw BlowUpError(what.str(), stats_.events, origin_ + clock_, ids);
}

template <int D>
void EdSimulator<D>::take_snapshot() const {
  const double now = time_ - origin_;
  snapshot_current_ = true;
  if (snapshot_removed_ == stats_.removed) {
    // The same grains as the last snapshot: only positions and velocities change (hard grains
    // keep their spins), so the store is refreshed in place instead of rebuilt.
    std::size_t k = 0;
    for (std::uint32_t i = 0; i < flight_.size(); ++i) {
      if (!alive_[i]) continue;
      snapshot_.position()[k] = cells_.wrap(flight_[i].position_at(now));
      snapshot_.velocity()[k++] = flight_[i].v;
    }
    return;
  }
  snapshot_removed_ = stats_.removed;
  Particles<D> s;
  for (std::uint32_t i = 0; i < flight_.size(); ++i) {
    if (!alive_[i]) continue;
    const Flight<D>& f = flight_[i];
    s.add(grains_.id()[i], grains_.kind()[i], cells_.wrap(f.position_at(now)), f.v, f.radius,
          grains_.mass()[i]);
    s.spin()[s.size() - 1] = grains_.spin()[i];
  }
  snapshot_ = std::move(s);
}

template <int D>
void EdSimulator<D>::collect_transfers(std::vector<PairImpulse<D>>& out) {
  // An empty `out` (the gas observer's, at each sample: some 10^4 impulses) takes the buffer
  // itself rather than a copy; the buffers then take turns, each keeping its room.
  if (out.empty()) {
    out.swap(transfers_);
  } else {
    out.insert(out.end(), transfers_.begin(), transfers_.end());
  }
  transfers_.clear();
}

template <int D>
void EdSimulator<D>::record_transfers(bool on) {
  recording_ = on;
  if (!on) transfers_.clear();
}

template <int D>
EnergyBalance EdSimulator<D>::energy() const {
  EnergyBalance e;
  for (std::uint32_t i = 0; i < flight_.size(); ++i) {
    if (!alive_[i] || fixed(i)) continue;  // immovable wall grains carry no energy
    const double m = grains_.mass()[i], r = grains_.radius()[i];
    e.kinetic += 0.5 * m * flight_[i].v.squaredNorm();
    // Frictionless hard grains never change their spins.
    e.rotational += 0.5 * Dim<D>::kInertiaFactor * m * r * r *
                    Dim<D>::spin_dot(grains_.spin()[i], grains_.spin()[i]);
  }
  e.removed = removed_energy_;
  e.dissipated = initial_energy_ - e.total() - e.removed;
  return e;
}

template <int D>
void EdSimulator<D>::check_contact(std::uint32_t i, std::uint32_t j, double distance) const {
  const double sigma = flight_[i].radius + flight_[j].radius;
  if (std::abs(distance - sigma) > kContactTolerance * sigma)
    throw BlowUpError("collision at distance " + std::to_string(distance) + " instead of " +
                          std::to_string(sigma),
                      stats_.events, origin_ + clock_, {grains_.id()[i], grains_.id()[j]});
}

// At the plate: the grain's surface reaches its nearest face point (closer only when it slid
// in over a 3D edge, through the plane already).
template <int D>
void EdSimulator<D>::check_plate_contact(std::uint32_t i) const {
  const Flight<D>& f = flight_[i];
  const double distance = (f.x - plate_->nearest_point(f.x)).norm();
  if (distance > (1.0 + kContactTolerance) * f.radius)
    throw BlowUpError("plate collision at distance " + std::to_string(distance) + " instead of " +
                          std::to_string(f.radius),
                      stats_.events, origin_ + clock_, {grains_.id()[i]});
}

template <int D>
void EdSimulator<D>::check_no_overlaps() const {
  const double now = time_ - origin_;
  // Listed, the cells hold no grains (the lists bin their centres apart): the grains are binned
  // here where they stand, and each pair is taken at its nearest image.
  std::optional<CellList<D>> binned;
  if (shells_) {
    binned.emplace(make_cells<D>(scene_, grains_));
    for (std::uint32_t i = 0; i < flight_.size(); ++i)
      if (alive_[i]) binned->insert(i, cells_.wrap(flight_[i].position_at(now)));
  }
  const CellList<D>& cells = binned ? *binned : cells_;
  typename CellList<D>::Neighbourhood hood;
  for (std::uint32_t i = 0; i < flight_.size(); ++i) {
    if (!alive_[i] || fixed(i)) continue;
    const Vec<D> x_i = flight_[i].position_at(now);
    // In front of the face, or (2D) beside it, where its end points count; not behind it.
    const bool modelled = plate_ && (plate_->over_face(x_i) ? plate_->height(x_i) >= 0.0 : D == 2);
    if (modelled) {
      const double distance = (x_i - plate_->nearest_point(x_i)).norm();
      if (distance < (1.0 - kContactTolerance) * flight_[i].radius)
        throw BlowUpError("overlap with the plate: distance " + std::to_string(distance),
                          stats_.events, time_, {grains_.id()[i]});
    }
    cells.gather(i, hood);
    for (std::size_t m = 0; m < hood.size; ++m) {
      const std::uint32_t k = hood.grain[m];
      if (k == i) continue;
      const double sigma = flight_[i].radius + flight_[k].radius;
      const Vec<D> x_k = flight_[k].position_at(now);
      const double distance =
          (binned ? cells_.minimum_image(Vec<D>(x_k - x_i))
                  : Vec<D>((hood.shifted ? x_k + hood.shift[hood.image[m]] : x_k) - x_i))
              .norm();
      if (distance < (1.0 - kContactTolerance) * sigma)
        throw BlowUpError(
            "overlap: distance " + std::to_string(distance) + " < " + std::to_string(sigma),
            stats_.events, time_, {grains_.id()[i], grains_.id()[k]});
    }
  }
}

template <int D>
std::unique_ptr<Simulator<D>> make_ed_simulator(const Scene& scene) {
  const Scene hard = hard_scene(scene);
  return std::make_unique<EdSimulator<D>>(hard, build_initial_state<D>(hard));
}

template class EdSimulator<2>;
template class EdSimulator<3>;
template std::unique_ptr<Simulator<2>> make_ed_simulator<2>(const Scene&);
template std::unique_ptr<Simulator<3>> make_ed_simulator<3>(const Scene&);

}  // namespace granjet::ed
