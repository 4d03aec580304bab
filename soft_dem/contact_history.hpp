// Which listed pairs touched at the last force evaluation, and the tangential history u_t of
// each (contact laws that keep one, kKeepShear). The history goes on while a pair keeps
// touching and ends when it parts [model §2]: from one pass to the next a merge of the two
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
#include "core/parallel_sort.hpp"
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

  // Moves on to this pass's contacts, `found` (increasing pair-list indices): a pair still
  // touching keeps its u_t, a new one starts from zero. Both lists increase, so a merge finds
  // every previous u_t. In three parts, so that threads can share the middle one:
  // prepare_carry(found.size()) once, carry(found, begin, end) over stretches that cover the
  // list (each a merge of its own, started by a binary search), then finish_carry(found), which
  // hands the last pass's list back in `found`, to be reused as scratch. shear() is this pass's
  // from prepare_carry on (complete once every stretch is carried); pairs() is the last pass's
  // until finish_carry.
  void prepare_carry(std::size_t found) {
    if constexpr (kKeepShear) {
      shear_.swap(last_shear_);
      shear_.resize(found);
    }
  }
  void carry(std::span<const std::uint32_t> found, std::size_t begin, std::size_t end) {
    if constexpr (kKeepShear) {
      if (begin == end) return;
      std::size_t before =
          std::lower_bound(pair_.begin(), pair_.end(), found[begin]) - pair_.begin();
      for (std::size_t c = begin; c < end; ++c) {
        while (before < pair_.size() && pair_[before] < found[c]) ++before;
        const bool continues = before < pair_.size() && pair_[before] == found[c];
        shear_.store(c, continues ? last_shear_.load(before) : LaneVec<D>::Zero());
      }
    }
  }
  void finish_carry(std::vector<std::uint32_t>& found) { pair_.swap(found); }

  // The u_t of listed pair k: zero unless it touched at the last evaluation.
  Vec<D> of(std::uint32_t k) const {
    if constexpr (kKeepShear) {
      const auto c = std::lower_bound(pair_.begin(), pair_.end(), k);
      if (c != pair_.end() && *c == k) return shear_.template get<Vec<D>>(c - pair_.begin());
    }
    return Vec<D>::Zero();
  }

  // Every touching pair's u_t by grain ids (empty without kKeepShear); pair_row and partner
  // give the grains of each listed pair. `threads` share the work (the same list for any count).
  std::vector<ByIds> by_ids(std::span<const GrainId> id, std::span<const std::uint32_t> pair_row,
                            std::span<const std::uint32_t> partner, int threads = 1) const {
    std::vector<ByIds> history;
    if constexpr (kKeepShear) {
      const auto contacts = static_cast<std::int64_t>(pair_.size());
      history.resize(contacts);
#pragma omp parallel for num_threads(threads) schedule(static) if (threads > 1)
      for (std::int64_t c = 0; c < contacts; ++c) {
        const std::uint32_t k = pair_[c];
        history[c] = {id[pair_row[k]], id[partner[k]], shear_.template get<Vec<D>>(c)};
      }
    }
    return history;
  }

  // After a neighbour rebuild: the pairs of `history` whose grains are both still there
  // (index_of(id) gives a grain's new index, or nothing once it was removed), by their index
  // in the new list. A pair still touching is still listed.
  template <class IndexOf>
  void restore(const std::vector<ByIds>& history, IndexOf&& index_of, const PairList& pairs,
               int threads = 1) {
    constexpr std::uint32_t kGone = UINT32_MAX;
    const auto entries = static_cast<std::int64_t>(history.size());
    std::vector<std::pair<std::uint32_t, Vec<D>>> carried(entries);
#pragma omp parallel for num_threads(threads) schedule(static) if (threads > 1)
    for (std::int64_t h = 0; h < entries; ++h) {
      carried[h] = {kGone, history[h].shear};
      const std::optional<std::uint32_t> a = index_of(history[h].a), b = index_of(history[h].b);
      if (!a || !b) continue;
      const std::uint32_t i = std::min(*a, *b), j = std::max(*a, *b);
      // Find j in row i (a handful of partners).
      for (std::uint32_t k = pairs.first[i]; k < pairs.first[i + 1]; ++k)
        if (pairs.partner[k] == j) {
          carried[h].first = k;
          break;
        }
    }
    std::erase_if(carried, [](const auto& c) { return c.first == kGone; });
    parallel_sort(
        carried, [](const auto& x, const auto& y) { return x.first < y.first; }, threads);
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
  Columns<D> last_shear_;  // carry's source: the last pass's u_t
};

}  // namespace granjet::dem
