// The soft DEM's grains spread over MPI ranks by space (domain decomposition): each rank owns
// the grains of one part of a recursive coordinate bisection (core/recursive_bisection.hpp)
// and holds, as ghosts, copies of the grains of other parts within the reach of a pair (2
// R_max + skin, or a tether bond) of its part; with run.lengthwise_cuts = auto a jet's column
// is cut lengthwise in the first levels (soft_dem/jet_cuts.hpp). At every neighbour rebuild
// the grains move to their owners and the ghosts are chosen anew; at every step each owner
// sends the state of each of its ghosts that a force moved (the holders coast the others, as
// the owner does, bit for bit). The parts are cut anew, weighted by measured work, when the ranks'
// busy times grow uneven. No rank ever holds the whole run: each builds only its share of the
// initial grains (core/initial_state.hpp's GrainShare), the first cut bisects over the ranks,
// and the first rebuild moves the grains to their owners.
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
#include <utility>
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
  GrainKind kind;
  std::uint8_t ghost;  // a copy for a rank that does not own it
  double x[D], v[D], w[kSpinWidth<D>];
  double radius, mass;
  double force_prev[D], torque_prev[kSpinWidth<D>];
  double plate_shear[D];
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
  // reach: how far from its part a grain is needed as a ghost; lengthwise: how the parts' cuts
  // keep along the jet axis (soft_dem/jet_cuts.hpp).
  Domain(RankTeam team, double reach, LengthwiseCuts lengthwise = {})
      : team_(team), reach_(reach), lengthwise_(lengthwise) {}

  const RankTeam& team() const { return team_; }
  int rank() const { return team_.rank(); }
  int ranks() const { return team_.size(); }
  double reach() const { return reach_; }

  // Cuts the parts anew from the owned grains of every rank (`owned` flags) with their weights.
  // Collective. The cut bisects over the ranks: no rank gathers the others' grains.
  void partition(std::span<const Vec<D>> x, std::span<const double> weight,
                 std::span<const std::uint8_t> owned) {
    std::vector<Vec<D>> mine_x;
    std::vector<double> mine_w;
    for (std::size_t i = 0; i < x.size(); ++i)
      if (owned[i]) {
        mine_x.push_back(x[i]);
        mine_w.push_back(weight[i]);
      }
    parts_.emplace(RecursiveBisection<D>::over_ranks(team_, mine_x, mine_w, ranks(), lengthwise_));
  }
  bool partitioned() const { return parts_.has_value(); }
  int owner_of(const Vec<D>& x) const { return parts_->part_of(x); }
  // The owner of a grain at x, calling visit(rank) first for every other rank that needs it
  // as a ghost.
  template <class Visit>
  int owner_and_ghost_ranks(const Vec<D>& x, Visit&& visit) const {
    return parts_->part_and_others_near(x, reach_, visit);
  }

  // Sends to[r] to every other rank r (to[rank()] is not sent) and returns what they sent
  // here, in rank order. Collective.
  template <class Record>
  std::vector<Record> move(const std::vector<std::vector<Record>>& to) const {
    std::vector<int> others;
    for (int r = 0; r < ranks(); ++r)
      if (r != rank()) others.push_back(r);
    std::vector<Record> all;
    for (const std::vector<Record>& from : team_.exchange_with(to, others))
      all.insert(all.end(), from.begin(), from.end());
    return all;
  }

  // Lists the halo once the grains held here are in their places: each owned grain within
  // reach of another part goes there, each ghost comes from the owner of its position. Both
  // sides list a rank's ghosts in id order, so that the states need no ids.
  void list_halo(std::span<const Vec<D>> x, std::span<const GrainId> id,
                 std::span<const std::uint8_t> owned) {
    using Listed = std::pair<GrainId, std::uint32_t>;
    std::vector<std::vector<Listed>> send(ranks()), recv(ranks());
    for (std::uint32_t i = 0; i < x.size(); ++i) {
      if (owned[i])
        owner_and_ghost_ranks(x[i], [&](int r) { send[r].push_back({id[i], i}); });
      else
        recv[owner_of(x[i])].push_back({id[i], i});
    }
    const auto indices = [](std::vector<Listed>& listed) {
      std::sort(listed.begin(), listed.end());
      std::vector<std::uint32_t> index(listed.size());
      for (std::size_t k = 0; k < listed.size(); ++k) index[k] = listed[k].second;
      return index;
    };
    partners_.clear();
    send_index_.assign(ranks(), {});
    recv_index_.assign(ranks(), {});
    for (int r = 0; r < ranks(); ++r) {
      send_index_[r] = indices(send[r]);
      recv_index_[r] = indices(recv[r]);
      if (!send_index_[r].empty() || !recv_index_[r].empty()) partners_.push_back(r);
    }
    outbox_.assign(ranks(), {});
    inbox_.assign(ranks(), {});
  }

  // Every owner sends the states of those of its ghosts that `moved(i)` says moved otherwise
  // than by coasting, `width` doubles each (pack(i, row) writes grain i's, unpack(i, row) reads
  // them), to the ranks that hold them; the holders' own passes coasted the others as their
  // owners did. Each row starts with the ghost's place in the list both sides hold. A ghost
  // that moved otherwise here (`moved` on the holder) with no row from its owner is an error.
  // Collective.
  template <class Moved, class Pack, class Unpack>
  void update_ghosts(std::size_t width, Moved&& moved, Pack&& pack, Unpack&& unpack) {
    const std::size_t stride = width + 1;
    for (int r : partners_) {
      const std::vector<std::uint32_t>& listed = send_index_[r];
      std::vector<double>& rows = outbox_[r];
      rows.resize(listed.size() * stride);
      std::size_t sent = 0;
      for (std::size_t k = 0; k < listed.size(); ++k) {
        if (!moved(listed[k])) continue;
        double* row = &rows[sent++ * stride];
        row[0] = static_cast<double>(k);  // exact: a list holds far fewer than 2^53 ghosts
        pack(listed[k], row + 1);
      }
      rows.resize(sent * stride);
      halo_.rows_sent += static_cast<std::int64_t>(sent);
      halo_.rows_held += static_cast<std::int64_t>(listed.size());
    }
    ++halo_.exchanges;
    team_.exchange_into(outbox_, inbox_, partners_, false);
    for (int r : partners_) {
      const std::vector<std::uint32_t>& listed = recv_index_[r];
      const std::vector<double>& rows = inbox_[r];
      if (rows.size() % stride != 0)
        throw std::logic_error("rank " + std::to_string(r) + " sent ghost states of " +
                               std::to_string(rows.size()) + " doubles, not rows of " +
                               std::to_string(stride));
      // The ghosts between two rows coasted at their owner; one that moved otherwise here
      // would part from its owner's state for good.
      std::size_t next = 0;
      const auto coasted_before = [&](std::size_t end) {
        for (; next < end; ++next)
          if (moved(listed[next]))
            throw std::logic_error("ghost " + std::to_string(next) + " of the " +
                                   std::to_string(listed.size()) + " from rank " +
                                   std::to_string(r) +
                                   " was pushed here, but its owner sent no state for it");
      };
      for (std::size_t at = 0; at < rows.size(); at += stride) {
        const double k = rows[at];
        if (!(k >= static_cast<double>(next) && k < static_cast<double>(listed.size())))
          throw std::logic_error("rank " + std::to_string(r) + " sent the state of ghost " +
                                 std::to_string(k) + " of the " + std::to_string(listed.size()) +
                                 " it sends here, after ghost " + std::to_string(next));
        coasted_before(static_cast<std::size_t>(k));
        unpack(listed[next], &rows[at + 1]);
        ++next;
      }
      coasted_before(listed.size());
    }
  }
  // What this rank's ghost exchanges sent since it was built: how many, the rows sent, and the
  // rows it would have sent had every ghost been pushed.
  struct HaloCount {
    std::int64_t exchanges = 0, rows_sent = 0, rows_held = 0;
  };
  const HaloCount& halo_count() const { return halo_; }

 private:
  RankTeam team_;
  double reach_;
  LengthwiseCuts lengthwise_;
  std::optional<RecursiveBisection<D>> parts_;
  std::vector<int> partners_;  // the ranks this one sends ghosts to or receives them from
  std::vector<std::vector<std::uint32_t>> send_index_, recv_index_;  // by rank, in id order
  std::vector<std::vector<double>> outbox_, inbox_;  // the states, kept for their memory
  HaloCount halo_;
};

}  // namespace granjet::dem
