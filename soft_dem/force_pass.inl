// Part of soft_dem/dem_simulator.cpp (included there, inside namespace granjet::dem, before the
// explicit instantiations): the force pass, serial or shared among run.threads.
#pragma once

// Four phases, each a flat loop without unpredictable branches in its body:
//  1. find_contacts: the listed pairs that touch (a distance test per pair, kept branch-free:
//     only ~5% of the pairs of a touching lattice overlap, and a branch per pair or per row
//     of varying length mispredicts);
//  2. evaluate_contacts: each contact's force and torques from its geometry and history, in
//     blocks of contacts held as columns (contacts_), two vectorised loops per block;
//  3. ContactSums: every grain sums its contacts in list order (the rows k < i
//     that list it, then its own row), one fixed order whatever the thread count, so the
//     same roundings and the same bits;
//  4. the plate, then after_row(i, forced) with grain i's total force; forced_ says which grains
//     had a force at this pass or the last (contacts, plate, tether): the others fly free.
//     The two kinds are listed apart first, and each list is updated in its own loop.
// Phases 1, 2 and 4 are shared among threads; 3 is a short serial sweep over the contacts
// (with one thread it runs inside 2, block by block, in the same order).
// force_ and torque_ must be zero on entry.
template <int D, bool kFriction, bool kMono, class Space>
template <class AfterRow>
[[gnu::flatten]]  // inline the contact law and the grain update into their loops
double DemSimulator<D, kFriction, kMono, Space>::force_pass(AfterRow&& after_row) {
  if (tethered_)
    wall_.add_forces(p_, [this](GrainId id) { return index_of(id); }, std::span<Vec<D>>(force_));
  for (std::uint8_t& bits : forced_) bits = static_cast<std::uint8_t>((bits & 1) << 1);
  find_contacts();
  const std::size_t first_blown = evaluate_contacts();
  if (threads_ > 1) {  // a single thread summed them as it went
    const ContactSums sums = contact_sums();
    for (std::size_t c = 0; c < contact_pair_.size(); ++c) sums.add(c);
  }
  stats_.contacts = static_cast<std::int64_t>(contact_pair_.size());

  const auto n = static_cast<std::int64_t>(p_.size());
  std::uint8_t* forced = forced_.data();
  std::int64_t first_blown_on_plate = n;
  if (plate_) {  // after the contacts: the same sum order for any thread count
#pragma omp parallel for num_threads(threads_) reduction(min : first_blown_on_plate) if (threads_ > 1)
    for (std::int64_t i = 0; i < n; ++i) {
      const PlateTouch touch = add_plate_force(i, force_[i], torque_[i]);
      if (touch != PlateTouch::kApart) forced[i] |= 1;
      if (touch == PlateTouch::kTooDeep) first_blown_on_plate = std::min(first_blown_on_plate, i);
    }
  }
  // The grains with a force at this pass or the last and the coasting ones, two lists in index
  // order built without a branch: whether a grain in a jet touches another is as good as random,
  // and one branch per grain on it mispredicts.
  const GrainKind* kind = p_.kind().data();
  const unsigned tethered = tethered_;  // the wall grains feel their springs
  forced_grains_.resize(n);
  coasting_grains_.resize(n);
  std::int64_t forced_count = 0, coasting_count = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    const bool pushed = (forced[i] | (tethered & (kind[i] == GrainKind::kWall))) != 0;
    forced_grains_[forced_count] = static_cast<std::uint32_t>(i);
    coasting_grains_[coasting_count] = static_cast<std::uint32_t>(i);
    forced_count += pushed;
    coasting_count += !pushed;
  }
  const std::uint32_t* pushed = forced_grains_.data();
  const std::uint32_t* coasting = coasting_grains_.data();
  std::vector<double> thread_largest(threads_, 0.0);
#pragma omp parallel num_threads(threads_) if (threads_ > 1)
  {
    double largest = 0.0;  // a local, stored once: the threads' slots share a cache line
#pragma omp for schedule(static) nowait
    for (std::int64_t k = 0; k < coasting_count; ++k)
      largest = sticky_max(largest, after_row(coasting[k], false));
#pragma omp for schedule(static) nowait
    for (std::int64_t k = 0; k < forced_count; ++k)
      largest = sticky_max(largest, after_row(pushed[k], true));
    thread_largest[thread_index()] = largest;
  }
  // A blown step is reported in row order (row i's pairs, then grain i on the plate, then
  // row i + 1); the state it integrated is lost anyway.
  if (first_blown < contact_pair_.size()) {
    const std::uint32_t k = contact_pair_[first_blown];
    if (pair_row_[k] <= first_blown_on_plate) throw_overlap(pair_row_[k], pairs_.partner[k]);
  }
  if (first_blown_on_plate < n) throw_overlap(first_blown_on_plate, first_blown_on_plate);
  double largest = 0.0;
  for (double value : thread_largest) largest = sticky_max(largest, value);
  // after_row zeroed force_prev_ as it went: now F(t) becomes F(t-dt) and the zeros the next F.
  force_.swap(force_prev_);
  if constexpr (kFriction) torque_.swap(torque_prev_);
  return largest;
}

// Each thread tests a contiguous stretch of the list; the stretches are joined in order. The
// index of every pair is written and the count advances only for a contact: no branch. A
// non-finite separation counts as apart; check_finite reports it at the next rebuild.
template <int D, bool kFriction, bool kMono, class Space>
void DemSimulator<D, kFriction, kMono, Space>::find_contacts() {
  const std::size_t listed = pairs_.size();
  const Vec<D>* x = p_.position().data();
  const double* radius = p_.radius().data();
  const std::uint32_t* row = pair_row_.data();
  const std::uint32_t* partner = pairs_.partner.data();
  found_.resize(threads_);
  std::vector<std::size_t> count(threads_, 0);
#pragma omp parallel for num_threads(threads_) schedule(static, 1) if (threads_ > 1)
  for (int t = 0; t < threads_; ++t) {
    const std::size_t begin = listed * t / threads_, end = listed * (t + 1) / threads_;
    std::vector<std::uint32_t>& out = found_[t];
    if (out.size() < end - begin) out.resize(end - begin);
    std::uint32_t* slot = out.data();
    std::size_t touching = 0;
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t i = row[k], j = partner[k];
      const double reach = kMono ? 2.0 * radius[0] : radius[i] + radius[j];
      const double d2 = space_.separation(x[i], x[j]).squaredNorm();
      slot[touching] = static_cast<std::uint32_t>(k);
      touching += d2 < reach * reach;
    }
    count[t] = touching;
  }
  found_pair_.clear();
  for (int t = 0; t < threads_; ++t)
    found_pair_.insert(found_pair_.end(), found_[t].begin(), found_[t].begin() + count[t]);
  if constexpr (kFriction) {
    // The history goes on while a pair keeps touching and ends when it parts [spec §2]: both
    // lists increase, so one merge finds each new contact's previous u_t.
    found_shear_.resize(found_pair_.size());
    std::size_t before = 0;
    for (std::size_t c = 0; c < found_pair_.size(); ++c) {
      while (before < contact_pair_.size() && contact_pair_[before] < found_pair_[c]) ++before;
      const bool continues =
          before < contact_pair_.size() && contact_pair_[before] == found_pair_[c];
      found_shear_.store(c, continues ? contact_shear_.load(before) : LaneVec<D>::Zero());
    }
    contact_shear_.swap(found_shear_);
  }
  contact_pair_.swap(found_pair_);
}

template <int D, bool kFriction, bool kMono, class Space>
[[gnu::flatten]]  // the contact law and geometry inlined into the loop
std::size_t DemSimulator<D, kFriction, kMono, Space>::evaluate_contacts() {
  const auto contacts = static_cast<std::int64_t>(contact_pair_.size());
  contacts_.resize(contacts);
  contact_i_.resize(contacts);
  contact_j_.resize(contacts);
  const std::uint32_t* pair = contact_pair_.data();
  const std::uint32_t* row = pair_row_.data();
  const std::uint32_t* partner = pairs_.partner.data();
  std::int64_t* grain_i = contact_i_.data();
  std::int64_t* grain_j = contact_j_.data();
  const bool serial = threads_ == 1;
  const ContactSums sums = contact_sums();
  // Blocks of contacts small enough that their columns stay in the first-level cache from the
  // geometry through the law to a single thread's sums.
  constexpr std::int64_t kBlock = 32;
  const std::int64_t blocks = (contacts + kBlock - 1) / kBlock;
  bool any_too_deep = false;  // the first such contact is looked for only then
#pragma omp parallel num_threads(threads_) reduction(| : any_too_deep) if (threads_ > 1)
  {
#pragma omp for schedule(static)
    for (std::int64_t c = 0; c < contacts; ++c) {
      grain_i[c] = row[pair[c]];
      grain_j[c] = partner[pair[c]];
    }
#pragma omp for schedule(static)
    for (std::int64_t block = 0; block < blocks; ++block) {
      const std::int64_t begin = block * kBlock, end = std::min(contacts, begin + kBlock);
      any_too_deep |= gather_contacts(begin, end);
      contacts_.apply(law_, contact_shear_, begin, end);
      if (serial)  // in list order already: step 3 done on the way
        for (std::int64_t c = begin; c < end; ++c) sums.add(c);
    }
  }
  if (any_too_deep)
    for (std::int64_t c = 0; c < contacts; ++c) {
      const double radius_i = radius_of(p_.radius(), grain_i[c]);
      const double radius_j = radius_of(p_.radius(), grain_j[c]);
      if (contacts_.overlap(c) > overlap_limit_ * std::min(radius_i, radius_j)) return c;
    }
  return contacts;
}

// A plain loop inside the OpenMP loop over blocks: GCC vectorises gathers there, not in an
// OpenMP loop itself. The grains' vectors are read as plain doubles (see LaneVec::at).
template <int D, bool kFriction, bool kMono, class Space>
bool DemSimulator<D, kFriction, kMono, Space>::gather_contacts(std::int64_t begin,
                                                              std::int64_t end) {
  constexpr int kSpinWidth = ContactTable<D, kFriction>::kSpinWidth;
  static_assert(sizeof(Vec<D>) == D * sizeof(double) &&
                sizeof(Spin<D>) == kSpinWidth * sizeof(double));
  using Lane = LaneVec<D>;
  const auto spin_at = [](const double* base, std::int64_t k) {
    if constexpr (kSpinWidth == 1) return base[k];  // 2D: a scalar
    else return LaneVec<kSpinWidth>::at(base, k);
  };
  const double* x = p_.position().data()->data();
  const double* v = p_.velocity().data()->data();
  const double* w = reinterpret_cast<const double*>(p_.spin().data());
  const double* radius = p_.radius().data();
  const std::int64_t* grain_i = contact_i_.data();
  const std::int64_t* grain_j = contact_j_.data();
  // An or as wide as a double, which the vectoriser keeps in lanes (a bool or a first index
  // stops it).
  std::int64_t too_deep = 0;
#pragma GCC ivdep
  for (std::int64_t c = begin; c < end; ++c) {
    const std::int64_t i = grain_i[c], j = grain_j[c];
    const Lane r_ij = space_.separation(Lane::at(x, i), Lane::at(x, j));
    const double radius_i = kMono ? radius[0] : radius[i];
    const double radius_j = kMono ? radius[0] : radius[j];
    const ContactGeometryOf<Lane> g =
        contact_geometry(r_ij, std::sqrt(r_ij.squaredNorm()), radius_i, radius_j);
    contacts_.set(c, g,
                  dem::relative_velocity<kFriction>(Lane::at(v, i), Lane::at(v, j),
                                                    spin_at(w, i), spin_at(w, j), g));
    too_deep |= std::int64_t{g.overlap > overlap_limit_ * std::min(radius_i, radius_j)};
  }
  return too_deep != 0;
}

template <int D, bool kFriction, bool kMono, class Space>
auto DemSimulator<D, kFriction, kMono, Space>::contact_sums() -> ContactSums {
  return {contact_i_.data(),     contact_j_.data(),     contacts_.forces(),
          contacts_.torques_i(), contacts_.torques_j(), force_.data(),
          torque_.data(),        forced_.data()};
}

template <int D, bool kFriction, bool kMono, class Space>
void DemSimulator<D, kFriction, kMono, Space>::ContactSums::add(std::size_t c) const {
  const std::int64_t i = grain_i[c], j = grain_j[c];
  forced[i] |= 1;
  forced[j] |= 1;
  const Vec<D> f = contact_force.template get<Vec<D>>(c);
  force[i] += f;
  force[j] -= f;
  if constexpr (kFriction) {
    torque[i] -= contact_torque_i.template get<Spin<D>>(c);
    torque[j] -= contact_torque_j.template get<Spin<D>>(c);
  }
}
