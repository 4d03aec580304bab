// A sum of doubles, or of fixed-size Eigen vectors or matrices component by component, kept
// exactly (core/exact_sum.hpp) and rounded once when read: its value does not depend on the
// order of its terms. The fields of a window are then the same bits in whatever order the grains
// and contacts come, and sums kept apart (on MPI ranks, each its own grains) and joined as
// integers are the bits of one.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "core/exact_sum.hpp"
#include "core/state_archive.hpp"

namespace granjet::analysis {

template <class T>
class ExactSums {
 public:
  static constexpr int kSize = [] {
    if constexpr (std::is_floating_point_v<T>)
      return 1;
    else
      return static_cast<int>(T::SizeAtCompileTime);
  }();

  void add(const T& x) {
    if constexpr (std::is_floating_point_v<T>)
      sum_[0].add(x);
    else
      for (int k = 0; k < kSize; ++k) sum_[k].add(x.data()[k]);
  }

  T value() const {
    if constexpr (std::is_floating_point_v<T>) {
      return sum_[0].value();
    } else {
      T x;
      for (int k = 0; k < kSize; ++k) x.data()[k] = sum_[k].value();
      return x;
    }
  }

  // The components' words one after another, after `out`'s (ExactSum::words: carried, so that
  // up to 2^30 such lists may be added up word by word, as over MPI ranks).
  void append_words(std::vector<std::int64_t>& out) {
    for (ExactSum& s : sum_) {
      const std::span<std::int64_t> w = s.words();
      out.insert(out.end(), w.begin(), w.end());
    }
  }
  // The sums whose words append_words gave, from the front of `words`; returns what is left.
  std::span<const std::int64_t> take_words(std::span<const std::int64_t> words) {
    const std::size_t each = ExactSum{}.words().size();
    if (words.size() < kSize * each)
      throw std::runtime_error("exact sums: " + std::to_string(words.size()) + " words, " +
                               std::to_string(kSize * each) + " needed");
    for (int k = 0; k < kSize; ++k) sum_[k] = ExactSum::of_words(words.subspan(k * each, each));
    return words.subspan(kSize * each);
  }

  // Checkpoints: the components' words one after another under name + "_exact". A checkpoint
  // of a granjet that kept plain sums holds the rounded sum under `name`: that becomes the
  // first term, and the sum goes on from it.
  template <class Visitor>
  void visit(Visitor& v, const std::string& name) {
    const std::string exact = name + "_exact";
    if constexpr (std::is_same_v<Visitor, StateReader>) {
      *this = {};
      if (!v.contains(exact)) {
        T rounded{};
        v(name, rounded);
        add(rounded);
        return;
      }
      std::vector<std::int64_t> words;
      v(exact, words);
      if (!take_words(words).empty())
        throw std::runtime_error("checkpoint entry " + exact + " holds more than " +
                                 std::to_string(kSize) + " sums");
    } else {
      std::vector<std::int64_t> words;
      append_words(words);
      v(exact, words);
    }
  }

 private:
  std::array<ExactSum, kSize> sum_{};
};

}  // namespace granjet::analysis
