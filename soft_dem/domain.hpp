// The soft DEM's grains spread over MPI ranks by space (domain decomposition): each rank owns
// the grains of one part of a recursive coordinate bisection (core/recursive_bisection.hpp)
// and holds, as ghosts, copies of the grains of other parts within the reach of a pair (2
// R_max + skin, or a tether bond) of its part. At every neighbour rebuild the grains move to
// their owners and the ghosts are chosen anew; at every step each owner sends its ghosts'
// state. The parts are cut anew, weighted by measured work, when the ranks' busy times grow
// uneven.
//
// Why the results are those of one rank, bit for bit: every rank bins its grains in the cells
// of one frame, that of all grains (CellGrid::Frame), and within a cell orders them by id; so
// its grains come in the order of the whole, its pair list holds the whole's pairs of each
// owned grain in the whole's order, and every owned grain sums its contacts in the same order
// from the same inputs. The ghosts' states are exact copies.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/dim.hpp"
#include "core/particles.hpp"
#include "core/rank_team.hpp"
#include "core/recursive_bisection.hpp"

namespace granjet::dem {

template <int D>
inline constexpr int kSpinWidth = static_cast<int>(sizeof(Spin<D>) / sizeof(double));

// Eigen's vectors as plain doubles (the records must be trivially copyable).
template <int D, class V>
void put(double* to, const V& v) {
  std::memcpy(to, &v, sizeof(V));
}
template <int D, class V>
V get(const double* from) {
  V v;
  std::memcpy(static_cast<void*>(&v), from, sizeof(V));
  return v;
}

// One grain as it moves at a rebuild: all that the simulator keeps of it.
template <int D>
struct GrainRecord {
  GrainId id;
  std::int32_t owner;  // the rank that owns it from this rebuild on
  GrainKind kind;
  std::uint8_t ghost;  // a copy for a rank that does not own it
  double x[D], v[D], w[kSpinWidth<D>];
  double radius, mass;
  double force_prev[D], torque_prev[kSpinWidth<D>];
  double plate_shear[D];
};

// What an owner sends of a ghost at every step.
template <int D>
struct GhostState {
  double x[D], v[D], w[kSpinWidth<D>];
  double force_prev[D], torque_prev[kSpinWidth<D>];
  std::uint8_t forced;
};

// A touching pair's tangential history, by grain ids.
template <int D>
struct HistoryRecord {
  GrainId a, b;
  double shear[D];
};

template <int D>
class Domain {
 public:
  // reach: how far from its part a grain is needed as a ghost.
  Domain(RankTeam team, double reach) : team_(team), reach_(reach) {}

  const RankTeam& team() const { return team_; }
  int rank() const { return team_.rank(); }
  int ranks() const { return team_.size(); }
  double reach() const { return reach_; }

  // Cuts the parts anew from the owned grains of every rank (`owned` flags; all true when every
  // rank holds the same grains, as at the start) with their weights. Collective.
  void partition(std::span<const Vec<D>> x, std::span<const double> weight,
                 std::span<const std::uint8_t> owned, bool everywhere_alike) {
    std::vector<Vec<D>> mine_x;
    std::vector<double> mine_w;
    for (std::size_t i = 0; i < x.size(); ++i)
      if (owned[i]) {
        mine_x.push_back(x[i]);
        mine_w.push_back(weight[i]);
      }
    if (everywhere_alike) {
      parts_.emplace(mine_x, mine_w, ranks());
      return;
    }
    std::vector<double> flat(mine_x.size() * D);
    for (std::size_t i = 0; i < mine_x.size(); ++i) put<D>(&flat[i * D], mine_x[i]);
    const std::vector<double> all_flat = team_.all_gather<double>(flat);
    const std::vector<double> all_w = team_.all_gather<double>(mine_w);
    std::vector<Vec<D>> all_x(all_w.size());
    for (std::size_t i = 0; i < all_x.size(); ++i) all_x[i] = get<D, Vec<D>>(&all_flat[i * D]);
    parts_.emplace(all_x, all_w, ranks());
  }
  bool partitioned() const { return parts_.has_value(); }
  int owner_of(const Vec<D>& x) const { return parts_->part_of(x); }
  // Calls visit(rank) for every rank but `owner` that needs a grain at x as a ghost.
  template <class Visit>
  void for_each_ghost_rank(const Vec<D>& x, int owner, Visit&& visit) const {
    parts_->for_each_part_near(x, reach_, [&](int part) {
      if (part != owner) visit(part);
    });
  }

  // Sends to[r] to rank r; returns every record sent here (this rank's own to[rank()]
  // included). Then lists the halo by id: the ghosts each owner sends here and
  // the ghosts of this rank's own grains, for each rank that holds them, both in id order.
  std::vector<GrainRecord<D>> move_grains(const std::vector<std::vector<GrainRecord<D>>>& to) {
    std::vector<GrainRecord<D>> all;
    for (const std::vector<GrainRecord<D>>& from : team_.exchange(to))
      all.insert(all.end(), from.begin(), from.end());
    send_ids_.assign(ranks(), {});
    recv_ids_.assign(ranks(), {});
    for (const GrainRecord<D>& g : all) {
      if (g.ghost) {
        recv_ids_[g.owner].push_back(g.id);
      } else {
        Vec<D> x;
        for (int d = 0; d < D; ++d) x[d] = g.x[d];
        for_each_ghost_rank(x, rank(), [&](int r) { send_ids_[r].push_back(g.id); });
      }
    }
    partners_.clear();
    for (int r = 0; r < ranks(); ++r) {
      std::sort(send_ids_[r].begin(), send_ids_[r].end());
      std::sort(recv_ids_[r].begin(), recv_ids_[r].end());
      if (!send_ids_[r].empty() || !recv_ids_[r].empty()) partners_.push_back(r);
    }
    return all;
  }

  std::vector<HistoryRecord<D>> move_histories(
      const std::vector<std::vector<HistoryRecord<D>>>& to) const {
    std::vector<HistoryRecord<D>> all;
    for (const std::vector<HistoryRecord<D>>& from : team_.exchange(to))
      all.insert(all.end(), from.begin(), from.end());
    return all;
  }

  // The halo's local indices, once the grains moved by move_grains are in their places.
  template <class IndexOf>
  void index_halo(IndexOf&& index_of) {
    send_index_.assign(ranks(), {});
    recv_index_.assign(ranks(), {});
    for (int r = 0; r < ranks(); ++r) {
      for (GrainId id : send_ids_[r]) send_index_[r].push_back(index_of(id));
      for (GrainId id : recv_ids_[r]) recv_index_[r].push_back(index_of(id));
    }
  }

  // Every owner sends its ghosts' state to the ranks that hold them. Collective.
  template <class Pack, class Unpack>
  void update_ghosts(Pack&& pack, Unpack&& unpack) const {
    std::vector<std::vector<GhostState<D>>> to(ranks());
    for (int r : partners_) {
      to[r].resize(send_index_[r].size());
      for (std::size_t k = 0; k < send_index_[r].size(); ++k) pack(send_index_[r][k], to[r][k]);
    }
    const std::vector<std::vector<GhostState<D>>> from = team_.exchange_with(to, partners_);
    for (int r : partners_) {
      if (from[r].size() != recv_index_[r].size())
        throw std::logic_error("rank " + std::to_string(r) + " sent " +
                               std::to_string(from[r].size()) + " ghosts, not " +
                               std::to_string(recv_index_[r].size()));
      for (std::size_t k = 0; k < from[r].size(); ++k) unpack(recv_index_[r][k], from[r][k]);
    }
  }

  // The local indices of the ghosts, by the rank that owns them.
  const std::vector<std::vector<std::uint32_t>>& ghosts_from() const { return recv_index_; }
  // How many ghosts this rank holds, and sends each step.
  std::size_t ghosts() const { return count(recv_ids_); }
  std::size_t sent() const { return count(send_ids_); }

 private:
  static std::size_t count(const std::vector<std::vector<GrainId>>& lists) {
    std::size_t n = 0;
    for (const auto& list : lists) n += list.size();
    return n;
  }

  RankTeam team_;
  double reach_;
  std::optional<RecursiveBisection<D>> parts_;
  std::vector<int> partners_;  // the ranks this one sends ghosts to or receives them from
  std::vector<std::vector<GrainId>> send_ids_, recv_ids_;  // by rank, in the order sent
  std::vector<std::vector<std::uint32_t>> send_index_, recv_index_;
};

}  // namespace granjet::dem
