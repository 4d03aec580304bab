// Which listed pairs the force pass must test for contact. A jet flies as a lattice whose
// neighbours are 1e-9 d apart (core/initial_state.cpp), so most of its listed pairs join grains
// that have not touched anything yet and share one velocity, bit for bit. Such a grain is quiet:
// no force at the last pass (nor at this one, checked after it), so its velocity stays and
// every quiet grain moves by the same increment each step; the separation of two of them
// changes only by the rounding of their positions, at most sqrt(D) 2^-52 max|x| per step. A pair of
// quiet grains apart by more than that drift over kMaxAge passes cannot touch within them while
// both stay quiet, so the pass skips it. A quiet grain can only be pushed through a tested pair (a
// partner that is not quiet) or the plate; once one is, the classification is redone before the
// next pass. The contacts found are the same ones in the same order, so results are bit-identical.
//
// Only grains whose listed partners are all quiet, kMargin times over, are trusted (eroded
// inwards from the quiet region's edge): the impact's compression wave then has to cross a few
// layers of tested pairs before it pushes a trusted grain and forces a new classification.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "core/dim.hpp"
#include "core/neighbour_list.hpp"
#include "core/particles.hpp"

namespace granjet::dem {

template <int D>
class QuietPairs {
 public:
  // Passes a classification serves at most (the drift bound above grows with it).
  static constexpr int kMaxAge = 128;
  static constexpr int kMargin = 3;

  // threads: how many share the last pass over the pairs (the same list for any count).
  explicit QuietPairs(int threads = 1) : threads_(threads) {}

  // The listed pairs to test (increasing pair-list indices), for the pass about to run.
  std::span<const std::uint32_t> tested() const { return tested_; }
  // Whether the classification still holds for the next pass.
  bool fresh() const { return age_ < kMaxAge; }
  // After a neighbour rebuild: the list it classified is gone.
  void expire() { age_ = kMaxAge; }

  // Classifies the pairs of `pairs` (rows pair_row) at the start of a pass. force_before: each
  // grain's force at the last pass (a grain with none moves this pass as if it coasted, whatever
  // its forced bits say); reach(i, j): the sum of the radii; step: the time step (a coasting
  // grain moves by step times its velocity).
  template <class Space, class Reach>
  void classify(const Particles<D>& p, std::span<const Vec<D>> force_before, const PairList& pairs,
                std::span<const std::uint32_t> pair_row, const Space& space, double step,
                Reach&& reach) {
    const std::size_t n = p.size(), listed = pairs.size();
    const auto x = p.position();
    const auto v = p.velocity();
    const auto kind = p.kind();
    age_ = 0;
    // The shared velocity: the one most grains without a force have, if more than half of them
    // have one (a majority vote, Boyer and Moore's). Another choice only skips fewer pairs.
    Vec<D> shared = Vec<D>::Zero();
    std::size_t votes = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (kind[i] != GrainKind::kFree || !force_before[i].isZero(0.0)) continue;
      if (votes == 0) shared = v[i];
      votes += v[i] == shared ? 1 : -1;
    }
    trusted_.resize(n);
    double largest = 0.0;  // max |x| over the grains
    std::size_t quiet = 0;
    for (std::size_t i = 0; i < n; ++i) {
      trusted_[i] = kind[i] == GrainKind::kFree && v[i] == shared && force_before[i].isZero(0.0);
      quiet += trusted_[i];
      largest = std::max(largest, x[i].cwiseAbs().maxCoeff());
    }
    tested_.resize(listed);
    // Too few to skip much (a gas: only the vote's winner): spare the passes over the pairs.
    if (8 * quiet < n) {
      for (std::size_t k = 0; k < listed; ++k) tested_[k] = static_cast<std::uint32_t>(k);
      return;
    }
    next_.resize(n);
    const std::uint32_t* row = pair_row.data();
    const std::uint32_t* partner = pairs.partner.data();
    for (int layer = 0; layer < kMargin; ++layer) {
      // Raw pointers: a store through a byte may alias anything, a vector's own pointer too.
      const std::uint8_t* now = trusted_.data();
      std::uint8_t* next = next_.data();
      std::copy(now, now + n, next);
      for (std::size_t k = 0; k < listed; ++k) {
        next[row[k]] &= now[partner[k]];
        next[partner[k]] &= now[row[k]];
      }
      trusted_.swap(next_);
    }
    // The drift of a separation over kMaxAge steps, with the coordinates grown by as many
    // steps (twice over: the increment is rounded too), and room for the rounding of the
    // contact test itself.
    const double reach_of_x = largest + 2.0 * kMaxAge * step * shared.cwiseAbs().maxCoeff();
    const double drift = 2.0 * kMaxAge * std::sqrt(double{D}) * 0x1p-52 * reach_of_x;
    // Each thread writes the kept indices of its stretch of pairs at the stretch's start; the
    // stretches then move down into one list, in order.
    std::vector<std::size_t> kept(threads_, 0);
#pragma omp parallel for num_threads(threads_) schedule(static, 1) if (threads_ > 1)
    for (int t = 0; t < threads_; ++t) {
      const std::size_t begin = listed * t / threads_, end = listed * (t + 1) / threads_;
      std::size_t count = begin;
      for (std::size_t k = begin; k < end; ++k) {
        const std::uint32_t i = pair_row[k], j = pairs.partner[k];
        const double apart = reach(i, j) * (1.0 + 0x1p-40) + drift;
        const bool skip = (trusted_[i] & trusted_[j]) != 0 &&
                          space.separation(x[i], x[j]).squaredNorm() > apart * apart;
        tested_[count] = static_cast<std::uint32_t>(k);
        count += !skip;
      }
      kept[t] = count - begin;
    }
    std::size_t count = kept[0];
    for (int t = 1; t < threads_; ++t) {
      const std::size_t begin = listed * t / threads_;
      for (std::size_t m = 0; m < kept[t]; ++m) tested_[count + m] = tested_[begin + m];
      count += kept[t];
    }
    tested_.resize(count);
  }

  // After the pass's forces are summed (forced bit 0: pushed at this pass): the classification
  // ends if a trusted grain was pushed, and ages by a pass otherwise.
  void after_pass(std::span<const std::uint8_t> forced) {
    std::uint8_t pushed = 0;
    for (std::size_t i = 0; i < forced.size(); ++i) pushed |= trusted_[i] & forced[i];
    age_ = (pushed & 1) != 0 ? kMaxAge : age_ + 1;
  }

 private:
  int threads_;
  int age_ = kMaxAge;
  std::vector<std::uint8_t> trusted_, next_;  // per grain: its pairs with trusted grains skip
  std::vector<std::uint32_t> tested_;
};

}  // namespace granjet::dem
