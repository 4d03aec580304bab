// Where each grain a process holds lies in its arrays, by grain id: an open-addressing hash
// table (linear probing, at most half full) sized to the grains held, not to the largest id. A
// table indexed by id costs every rank of a run 4 bytes for each grain of the whole run, 400 MB
// at 1e8 grains, where a rank holds 1e5 of them (docs/performance.md, "a 1e8-grain jet").
#pragma once

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <vector>

#include "core/particles.hpp"

namespace granjet {

class IdIndex {
 public:
  static constexpr std::uint32_t kAbsent = std::numeric_limits<std::uint32_t>::max();

  // Maps ids[i] to i, for every i, on `threads` threads; nothing else is held after. The ids
  // must be distinct and not negative (either is a logic error).
  void assign(std::span<const GrainId> ids, int threads = 1) {
    if (ids.size() >= kAbsent) throw std::length_error("IdIndex: more grains than 32-bit indices");
    const std::size_t slots = std::bit_ceil(std::max<std::size_t>(2 * ids.size(), 16));
    shift_ = 64 - std::countr_zero(slots);
    key_.assign(slots, kEmpty);
    index_.resize(slots);
    const auto n = static_cast<std::int64_t>(ids.size());
    bool bad = false;
    if (threads <= 1) {
      for (std::int64_t i = 0; i < n; ++i) bad |= !insert<false>(ids[i], i);
    } else {
#pragma omp parallel for num_threads(threads) schedule(static) reduction(|| : bad)
      for (std::int64_t i = 0; i < n; ++i) bad = !insert<true>(ids[i], i) || bad;
    }
    if (bad) throw std::logic_error("IdIndex: a grain id held twice, or a negative one");
  }

  // Where grain `id` lies, kAbsent when it is not held.
  std::uint32_t operator[](GrainId id) const {
    if (key_.empty()) return kAbsent;
    const std::size_t mask = key_.size() - 1;
    for (std::size_t s = slot_of(id);; s = (s + 1) & mask) {
      if (key_[s] == id) return index_[s];
      if (key_[s] == kEmpty) return kAbsent;
    }
  }

  // The table's bytes: what it costs, for the memory figures.
  std::size_t bytes() const {
    return key_.capacity() * sizeof(GrainId) + index_.capacity() * sizeof(std::uint32_t);
  }

 private:
  static constexpr GrainId kEmpty = -1;
  // Fibonacci hashing: the top bits of id times 2^64 over the golden ratio. A rank holds runs
  // of consecutive ids (a jet's layers), which this spreads evenly over the slots.
  std::size_t slot_of(GrainId id) const {
    return static_cast<std::size_t>((static_cast<std::uint64_t>(id) * 0x9E3779B97F4A7C15ull) >>
                                    shift_);
  }

  // Puts id at index i; false for a negative id or one already held. kShared: other threads
  // insert too, and each claims its slot by an atomic compare-exchange on the key (where a
  // probe ends may then depend on the threads' timing, what a lookup finds does not); alone, a
  // plain store does.
  template <bool kShared>
  bool insert(GrainId id, std::int64_t i) {
    if (id < 0) return false;
    const std::size_t mask = key_.size() - 1;
    for (std::size_t s = slot_of(id);; s = (s + 1) & mask) {
      GrainId seen = kEmpty;
      if constexpr (kShared) {
        std::atomic_ref<GrainId>(key_[s]).compare_exchange_strong(seen, id,
                                                                  std::memory_order_relaxed);
      } else {
        seen = key_[s];
        if (seen == kEmpty) key_[s] = id;
      }
      if (seen == kEmpty) {
        index_[s] = static_cast<std::uint32_t>(i);
        return true;
      }
      if (seen == id) return false;
    }
  }

  std::vector<GrainId> key_;
  std::vector<std::uint32_t> index_;
  int shift_ = 64;
};

}  // namespace granjet
