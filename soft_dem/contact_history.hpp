// Which listed pairs touched at the last force evaluation, and the tangential history u_t of
// each (contact laws that keep one, kKeepShear). The history goes on while a pair keeps
// touching and ends when it parts [spec §2]: from one pass to the next a merge of the two
// contact lists carries it; across neighbour rebuilds and checkpoints, where list indices and
// grain indices change, it travels by grain-id pair.
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "core/dim.hpp"
#include "core/neighbour_list.hpp"
#include "core/particles.hpp"
#include "soft_dem/contact_table.hpp"
#include "soft_dem/lane_vec.hpp"

namespace granjet::dem {

template <int D, bool kKeepShear>
class ContactHistory {
 public:
  // One touching pair's u_t by the grains' ids (a and b in either order).
  struct ByIds {
    GrainId a, b;
    Vec<D> shear;
  };

  // The pairs in contact, as pair-list indices in increasing order.
  const std::vector<std::uint32_t>& pairs() const { return pair_; }
  std::size_t size() const { return pair_.size(); }
  // Their u_t, one row per contact, advanced in place by the contact law (kKeepShear only).
  Columns<D>& shear() { return shear_; }

  // Moves on to this pass's contacts, `found` (increasing pair-list indices; it receives the
  // last pass's list, to be reused as scratch): a pair still touching keeps its u_t, a new one
  // starts from zero. Both lists increase, so one merge finds every previous u_t.
  void carry_over(std::vector<std::uint32_t>& found) {
    if constexpr (kKeepShear) {
      next_shear_.resize(found.size());
      std::size_t before = 0;
      for (std::size_t c = 0; c < found.size(); ++c) {
        while (before < pair_.size() && pair_[before] < found[c]) ++before;
        const bool continues = before < pair_.size() && pair_[before] == found[c];
        next_shear_.store(c, continues ? shear_.load(before) : LaneVec<D>::Zero());
      }
      shear_.swap(next_shear_);
    }
    pair_.swap(found);
  }

  // The u_t of listed pair k: zero unless it touched at the last evaluation.
  Vec<D> of(std::uint32_t k) const {
    if constexpr (kKeepShear) {
      const auto c = std::lower_bound(pair_.begin(), pair_.end(), k);
      if (c != pair_.end() && *c == k) return shear_.template get<Vec<D>>(c - pair_.begin());
    }
    return Vec<D>::Zero();
  }

  // Every touching pair's u_t by grain ids (empty without kKeepShear); pair_row and partner
  // give the grains of each listed pair.
  std::vector<ByIds> by_ids(std::span<const GrainId> id, std::span<const std::uint32_t> pair_row,
                            std::span<const std::uint32_t> partner) const {
    std::vector<ByIds> history;
    if constexpr (kKeepShear)
      for (std::size_t c = 0; c < pair_.size(); ++c) {
        const std::uint32_t k = pair_[c];
        history.push_back({id[pair_row[k]], id[partner[k]], shear_.template get<Vec<D>>(c)});
      }
    return history;
  }

  // After a neighbour rebuild: the pairs of `history` whose grains are both still there
  // (index_of(id) gives a grain's new index, or nothing once it was removed), by their index
  // in the new list. A pair still touching is still listed.
  template <class IndexOf>
  void restore(const std::vector<ByIds>& history, IndexOf&& index_of, const PairList& pairs) {
    std::vector<std::pair<std::uint32_t, Vec<D>>> carried;
    for (const ByIds& h : history) {
      const std::optional<std::uint32_t> a = index_of(h.a), b = index_of(h.b);
      if (!a || !b) continue;
      const std::uint32_t i = std::min(*a, *b), j = std::max(*a, *b);
      // Find j in row i (a handful of partners).
      for (std::uint32_t k = pairs.first[i]; k < pairs.first[i + 1]; ++k)
        if (pairs.partner[k] == j) {
          carried.emplace_back(k, h.shear);
          break;
        }
    }
    std::sort(carried.begin(), carried.end(),
              [](const auto& x, const auto& y) { return x.first < y.first; });
    pair_.resize(carried.size());
    shear_.resize(carried.size());
    for (std::size_t c = 0; c < carried.size(); ++c) {
      pair_[c] = carried[c].first;
      shear_.set(c, carried[c].second);
    }
  }

 private:
  std::vector<std::uint32_t> pair_;
  Columns<D> shear_;
  Columns<D> next_shear_;  // carry_over's scratch
};

}  // namespace granjet::dem
