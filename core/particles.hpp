// Structure-of-arrays grain store with stable ids. Backends may reorder grains (spatial sort,
// removal); ids never change, so output and contact history are independent of the order.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "core/dim.hpp"

namespace granjet {

using GrainId = std::int64_t;

enum class GrainKind : std::uint8_t {
  kFree,  // integrated by the backend
  kWall,  // target grain: tethered (finite mass) or fixed (infinite mass)
};

template <int D>
class Particles {
 public:
  using VecT = Vec<D>;
  using SpinT = Spin<D>;

  // Appends a grain; mass = +inf makes it immovable (inverse mass 0).
  void add(GrainId id, GrainKind kind, const VecT& position, const VecT& velocity, double radius,
           double mass) {
    id_.push_back(id);
    kind_.push_back(kind);
    pos_.push_back(position);
    vel_.push_back(velocity);
    omega_.push_back(Dim<D>::zero_spin());
    radius_.push_back(radius);
    mass_.push_back(mass);
    inv_mass_.push_back(mass == std::numeric_limits<double>::infinity() ? 0.0 : 1.0 / mass);
  }

  // Drops every grain but keeps the arrays' memory: a store filled again and again (the whole
  // a domain decomposition gathers at each sample) then appends without reallocating.
  void clear() {
    id_.clear();
    kind_.clear();
    pos_.clear();
    vel_.clear();
    omega_.clear();
    radius_.clear();
    mass_.clear();
    inv_mass_.clear();
  }

  std::size_t size() const { return id_.size(); }
  bool empty() const { return id_.empty(); }

  std::span<const GrainId> id() const { return id_; }
  std::span<const GrainKind> kind() const { return kind_; }
  std::span<const VecT> position() const { return pos_; }
  std::span<const VecT> velocity() const { return vel_; }
  std::span<const SpinT> spin() const { return omega_; }
  std::span<const double> radius() const { return radius_; }
  std::span<const double> mass() const { return mass_; }
  std::span<const double> inverse_mass() const { return inv_mass_; }

  std::span<VecT> position() { return pos_; }
  std::span<VecT> velocity() { return vel_; }
  std::span<SpinT> spin() { return omega_; }

  // Reorders every array so that new index k holds old index order[k]; `order` may be shorter
  // than size() (the grains left out are dropped).
  // `threads` share the copying (the result is the same for any count).
  void gather(std::span<const std::uint32_t> order, int threads = 1) {
    gather_one(id_, order, threads);
    gather_one(kind_, order, threads);
    gather_one(pos_, order, threads);
    gather_one(vel_, order, threads);
    gather_one(omega_, order, threads);
    gather_one(radius_, order, threads);
    gather_one(mass_, order, threads);
    gather_one(inv_mass_, order, threads);
  }

  // Keeping only the grains `keep` (increasing indices) without reordering them all: each kept
  // grain beyond the first keep.size() places fills a dropped grain's place there, so a store
  // that drops few grains moves few (a domain decomposition's rebuild, whose cell sort orders
  // them after). compaction() lists the moves (from, to); compact() applies them and leaves room
  // for `room` grains about to be added, so that adding them copies no array.
  using Moves = std::vector<std::pair<std::uint32_t, std::uint32_t>>;
  static Moves compaction(std::span<const std::uint32_t> keep) {
    const auto kept = static_cast<std::uint32_t>(keep.size());
    const auto in_place =
        static_cast<std::size_t>(std::lower_bound(keep.begin(), keep.end(), kept) - keep.begin());
    Moves moves;
    moves.reserve(kept - in_place);
    std::size_t k = 0, source = in_place;
    for (std::uint32_t place = 0; source < kept; ++place) {
      if (k < in_place && keep[k] == place) {
        ++k;
        continue;
      }
      moves.emplace_back(keep[source++], place);
    }
    return moves;
  }
  void compact(const Moves& moves, std::size_t kept, std::size_t room) {
    compact_one(id_, moves, kept, room);
    compact_one(kind_, moves, kept, room);
    compact_one(pos_, moves, kept, room);
    compact_one(vel_, moves, kept, room);
    compact_one(omega_, moves, kept, room);
    compact_one(radius_, moves, kept, room);
    compact_one(mass_, moves, kept, room);
    compact_one(inv_mass_, moves, kept, room);
  }
  // Room for `size` values, and an eighth more when it must grow: counts that wander from
  // rebuild to rebuild (ghosts, arrivals) then seldom reallocate.
  template <class T>
  static void with_room(std::vector<T>& values, std::size_t size) {
    if (values.capacity() < size) values.reserve(size + size / 8);
  }
  template <class T>
  static void compact_one(std::vector<T>& values, const Moves& moves, std::size_t kept,
                          std::size_t room) {
    for (const auto& [from, to] : moves) values[to] = values[from];
    values.resize(kept);
    with_room(values, kept + room);
  }

  // The gathered values go to the array the last gather of this type replaced, kept for it, so
  // that a neighbour rebuild allocates no memory: fresh pages cost a fault and zeroing each,
  // about 19 MB of them at every rebuild of a 1e6-grain jet on one process, where the kept
  // arrays took the rebuild's cell sort from 0.8-1.0 s to 0.5 s over 10 rebuilds
  // (docs/performance.md). A type's last replaced array stays held.
  template <class T>
  static void gather_one(std::vector<T>& values, std::span<const std::uint32_t> order,
                         int threads = 1) {
    static thread_local std::vector<T> kept;
    with_room(kept, order.size());
    kept.resize(order.size());
    T* out = kept.data();  // the calling thread's: each thread of the team has its own `kept`
    const auto n = static_cast<std::int64_t>(order.size());
#pragma omp parallel for num_threads(threads) schedule(static) if (threads > 1)
    for (std::int64_t k = 0; k < n; ++k) out[k] = values[order[k]];
    values.swap(kept);
  }

 private:
  std::vector<GrainId> id_;
  std::vector<GrainKind> kind_;
  std::vector<VecT> pos_;
  std::vector<VecT> vel_;
  std::vector<SpinT> omega_;
  std::vector<double> radius_;
  std::vector<double> mass_;
  std::vector<double> inv_mass_;
};

// Total momentum of the movable grains (immovable ones, inverse mass 0, carry none).
template <int D>
Vec<D> total_momentum(const Particles<D>& p) {
  Vec<D> sum = Vec<D>::Zero();
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.inverse_mass()[i] > 0.0) sum += p.mass()[i] * p.velocity()[i];
  return sum;
}

}  // namespace granjet
