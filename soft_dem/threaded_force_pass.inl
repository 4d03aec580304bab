// Part of soft_dem/dem_simulator.cpp (included there, inside namespace granjet::dem, before the
// explicit instantiations): the force pass for run.threads > 1.
#pragma once

// Pass 1 evaluates every listed pair (rows shared out among threads; each pair and its history
// belong to one row). Pass 2 gives every grain its total in exactly the serial pass's order:
// first the rows k < i that list it (force_[i] -= f, by increasing k), then its own row
// (+= f); the same roundings, so the same bits for any thread count. The price is storing the
// pair forces once.
template <int D, bool kFriction, bool kMono, class Space>
template <class AfterRow>
[[gnu::flatten]]
double DemSimulator<D, kFriction, kMono, Space>::threaded_force_pass(AfterRow&& after_row) {
  if (tethered_)
    wall_.add_forces(p_, [this](GrainId id) { return index_of(id); }, std::span<Vec<D>>(force_));
  const auto radius = p_.radius();
  const auto n = static_cast<std::int64_t>(p_.size());
  std::int64_t contacts = 0;
  // The serial pass reports the first pair, or grain on the plate, in its order.
  std::uint32_t first_blown = UINT32_MAX;
  std::int64_t first_blown_on_plate = n;
  std::vector<double> thread_largest(threads_, 0.0);
  // One parallel region per step: waking the threads costs more than the barriers inside.
#pragma omp parallel num_threads(threads_) reduction(+ : contacts) reduction(min : first_blown) \
    reduction(min : first_blown_on_plate)
  {
    Vec<D> no_history = Vec<D>::Zero();
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < n; ++i)
      for_each_contact_of(
          i,
          [&](std::size_t j, std::uint32_t k, const ContactGeometry<D>& g, const Vec<D>& v_rel) {
            ++contacts;
            if (g.overlap > overlap_limit_ * std::min(radius_of(radius, i), radius_of(radius, j)))
              first_blown = std::min(first_blown, k);
            in_contact_[k] = 1;
            if constexpr (kFriction) touching_[k] = 1;
            Vec<D>& shear = kFriction ? shear_[k] : no_history;
            const Vec<D> f = law_.force(g, v_rel, shear);
            pair_force_[k] = f;
            if constexpr (kFriction) {
              const Spin<D> t = Dim<D>::cross(g.n, f);
              pair_torque_i_[k] = g.lever_i * t;
              pair_torque_j_[k] = g.lever_j * t;
            }
          },
          [this](std::uint32_t k) {
            in_contact_[k] = 0;
            if constexpr (kFriction) {
              if (touching_[k]) {
                shear_[k].setZero();
                touching_[k] = 0;
              }
            }
          });
    // (the implicit barrier: every pair force is in place)
    double largest = 0.0;  // a local, stored once: the threads' slots share a cache line
#pragma omp for schedule(static) nowait
    for (std::int64_t i = 0; i < n; ++i) {
      Vec<D> force_i = force_[i];
      Spin<D> torque_i = torque_[i];
      for (std::uint32_t e = incoming_first_[i]; e < incoming_first_[i + 1]; ++e) {
        const std::uint32_t k = incoming_[e];
        if (!in_contact_[k]) continue;
        force_i -= pair_force_[k];
        if constexpr (kFriction) torque_i -= pair_torque_j_[k];
      }
      for (std::uint32_t k = pairs_.first[i]; k < pairs_.first[i + 1]; ++k) {
        if (!in_contact_[k]) continue;
        force_i += pair_force_[k];
        if constexpr (kFriction) torque_i -= pair_torque_i_[k];
      }
      if (plate_ && add_plate_force(i, force_i, torque_i))
        first_blown_on_plate = std::min(first_blown_on_plate, i);
      force_[i] = force_i;
      torque_[i] = torque_i;
      largest = sticky_max(largest, after_row(i));
    }
    thread_largest[thread_index()] = largest;
  }
  stats_.contacts = contacts;
  // A blown step is reported as the serial pass does (row i's pairs, then grain i on the
  // plate, then row i + 1); the state it integrated is lost anyway.
  if (first_blown != UINT32_MAX) {
    const auto row = std::upper_bound(pairs_.first.begin(), pairs_.first.end(), first_blown);
    const auto i = static_cast<std::int64_t>(row - pairs_.first.begin() - 1);
    if (i <= first_blown_on_plate) throw_overlap(i, pairs_.partner[first_blown]);
  }
  if (first_blown_on_plate < n) throw_overlap(first_blown_on_plate, first_blown_on_plate);
  double largest = 0.0;
  for (double value : thread_largest) largest = sticky_max(largest, value);
  force_.swap(force_prev_);
  if constexpr (kFriction) torque_.swap(torque_prev_);
  return largest;
}

// For pass 2 of the threaded force pass: the pairs that list each grain as partner, by row.
template <int D, bool kFriction, bool kMono, class Space>
void DemSimulator<D, kFriction, kMono, Space>::index_incoming_pairs() {
  const std::size_t n = p_.size();
  incoming_first_.assign(n + 1, 0);
  for (std::uint32_t j : pairs_.partner) ++incoming_first_[j + 1];
  for (std::size_t i = 0; i < n; ++i) incoming_first_[i + 1] += incoming_first_[i];
  incoming_.resize(pairs_.size());
  std::vector<std::uint32_t> fill(incoming_first_.begin(), incoming_first_.end() - 1);
  for (std::uint32_t k = 0; k < pairs_.size(); ++k) incoming_[fill[pairs_.partner[k]]++] = k;
  in_contact_.assign(pairs_.size(), 0);
  pair_force_.resize(pairs_.size());
  if constexpr (kFriction) {
    pair_torque_i_.resize(pairs_.size());
    pair_torque_j_.resize(pairs_.size());
  }
}
