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
      if (words.size() % kSize != 0)
        throw std::runtime_error("checkpoint entry " + exact + " holds " +
                                 std::to_string(words.size()) + " words, not " +
                                 std::to_string(kSize) + " sums' worth");
      const std::size_t each = words.size() / kSize;
      for (int k = 0; k < kSize; ++k)
        sum_[k] = ExactSum::of_words(std::span(words).subspan(k * each, each));
    } else {
      std::vector<std::int64_t> words;
      for (ExactSum& s : sum_) {
        const std::span<std::int64_t> w = s.words();
        words.insert(words.end(), w.begin(), w.end());
      }
      v(exact, words);
    }
  }

 private:
  std::array<ExactSum, kSize> sum_{};
};

}  // namespace granjet::analysis
