// Structure-of-arrays grain store with stable ids. Backends may reorder grains (spatial sort,
// removal); ids never change, so output and contact history are independent of the order.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
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
  // `threads` share the copying (the result is the same for any count). room: how many grains
  // are about to be added, whose place is reserved (a domain decomposition's arrivals: added
  // to arrays gathered to their exact size, they would copy every array to one twice as long).
  void gather(std::span<const std::uint32_t> order, int threads = 1, std::size_t room = 0) {
    gather_one(id_, order, threads, room);
    gather_one(kind_, order, threads, room);
    gather_one(pos_, order, threads, room);
    gather_one(vel_, order, threads, room);
    gather_one(omega_, order, threads, room);
    gather_one(radius_, order, threads, room);
    gather_one(mass_, order, threads, room);
    gather_one(inv_mass_, order, threads, room);
  }

  template <class T>
  static void gather_one(std::vector<T>& values, std::span<const std::uint32_t> order,
                         int threads = 1, std::size_t room = 0) {
    std::vector<T> out;
    out.reserve(order.size() + room);
    out.resize(order.size());
    const auto n = static_cast<std::int64_t>(order.size());
    // Each thread writes (and so first touches) the stretch of the new order it will own.
#pragma omp parallel for num_threads(threads) schedule(static) if (threads > 1)
    for (std::int64_t k = 0; k < n; ++k) out[k] = values[order[k]];
    values.swap(out);
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
