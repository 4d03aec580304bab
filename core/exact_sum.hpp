// A sum of doubles kept exactly and rounded once, to nearest (ties to even): the result does
// not depend on the order of the terms, nor on how they are split between accumulators that
// are then joined. So a sum over MPI ranks, each rank adding its own grains and the ranks'
// accumulators added as integers (RankTeam::sum over words()), has the bits of the same sum on
// one process, with no rank gathering the terms.
//
// Every finite double is an integer multiple of 2^-1074 below 2^1024: the accumulator holds
// that integer in 32-bit digits, each in a signed 64-bit word, so that 2^30 terms add before a
// carry must move on. Infinities and NaNs are counted apart and rule the result, as in a
// plain sum.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>

namespace granjet {

class ExactSum {
  // 128 bits, GCC's and Clang's extension (no ISO type is as wide).
  __extension__ typedef unsigned __int128 Wide;

 public:
  void add(double x) {
    const auto bits = std::bit_cast<std::uint64_t>(x);
    const auto biased = static_cast<int>((bits >> 52) & 0x7ff);
    const std::uint64_t fraction = bits & ((std::uint64_t{1} << 52) - 1);
    const bool negative = (bits >> 63) != 0;
    if (biased == 0x7ff) {
      ++word_[fraction != 0 ? kNaN : negative ? kMinusInf : kPlusInf];
      return;
    }
    // x = m 2^(p - 1074), p >= 0: subnormals have no hidden bit and the exponent of 1.
    const std::uint64_t m = biased == 0 ? fraction : fraction | (std::uint64_t{1} << 52);
    const int p = biased == 0 ? 0 : biased - 1;
    const Wide shifted = static_cast<Wide>(m) << (p % kDigitBits);
    const std::int64_t sign = negative ? -1 : 1;
    const int at = p / kDigitBits;
    for (int k = 0; k < 3; ++k)
      word_[at + k] += sign * static_cast<std::int64_t>((shifted >> (k * kDigitBits)) & kDigitMask);
    if (++terms_ == kTermsBeforeCarry) carry();
  }

  // The words a sum over ranks adds up (RankTeam::sum), with their carries moved on first, so
  // that up to 2^30 ranks may add theirs: the words' sum holds the sum of all ranks' terms.
  std::span<std::int64_t> words() {
    carry();
    return word_;
  }

  // The sum whose words() were `words` (a checkpoint's copy of them): it goes on as that one.
  static ExactSum of_words(std::span<const std::int64_t> words) {
    if (words.size() != kWords)
      throw std::invalid_argument("an exact sum has " + std::to_string(kWords) + " words, not " +
                                  std::to_string(words.size()));
    ExactSum s;
    std::copy(words.begin(), words.end(), s.word_.begin());
    return s;
  }

  // The sum of the terms, rounded once to the nearest double.
  double value() const {
    if (word_[kNaN] > 0 || (word_[kPlusInf] > 0 && word_[kMinusInf] > 0))
      return std::numeric_limits<double>::quiet_NaN();
    if (word_[kPlusInf] > 0) return std::numeric_limits<double>::infinity();
    if (word_[kMinusInf] > 0) return -std::numeric_limits<double>::infinity();
    ExactSum magnitude = *this;
    magnitude.carry();
    const bool negative = magnitude.word_[kTop] < 0;
    if (negative) {
      for (int k = 0; k <= kTop; ++k) magnitude.word_[k] = -magnitude.word_[k];
      magnitude.carry();
    }
    const double v = magnitude.rounded_magnitude();
    return negative ? -v : v;
  }

 private:
  static constexpr int kDigitBits = 32;
  static constexpr std::int64_t kDigitMask = (std::int64_t{1} << kDigitBits) - 1;
  // Digits up to 2^(32 k - 1074) for k < 68: the largest double's three digits end at 65, and
  // the top digit takes the carries beyond 2^1024, which round to infinity.
  static constexpr int kDigits = 68, kTop = kDigits - 1;
  static constexpr int kPlusInf = kDigits, kMinusInf = kDigits + 1, kNaN = kDigits + 2;
  static constexpr int kWords = kDigits + 3;
  static constexpr std::int64_t kTermsBeforeCarry = std::int64_t{1} << 30;

  // Each digit but the top into [0, 2^32), the rest carried up: the same integer.
  void carry() {
    for (int k = 0; k < kTop; ++k) {
      const std::int64_t up = word_[k] >> kDigitBits;  // floor division by 2^32
      word_[k] -= up * (std::int64_t{1} << kDigitBits);
      word_[k + 1] += up;
    }
    terms_ = 0;
  }

  // A carried, non-negative sum rounded to 53 bits: its highest three digits, and whether any
  // digit below them is not zero (a sticky bit, which breaks a tie upwards).
  double rounded_magnitude() const {
    int high = kTop;
    while (high >= 0 && word_[high] == 0) --high;
    if (high < 0) return 0.0;
    if (high == kTop) return std::numeric_limits<double>::infinity();
    const int low = std::max(high - 2, 0);
    Wide top = 0;
    for (int k = high; k >= low; --k)
      top = (top << kDigitBits) | static_cast<std::uint64_t>(word_[k]);
    bool sticky = false;
    for (int k = 0; k < low; ++k) sticky = sticky || word_[k] != 0;
    const int width = 128 - count_leading_zeros(top);
    const int exponent = kDigitBits * low - 1074;
    if (width <= 53)
      return std::ldexp(static_cast<double>(static_cast<std::uint64_t>(top)), exponent);
    // Below 2^-1022 every sum is exact (an integer times 2^-1074 below 2^52): width <= 53 there,
    // so rounding to 53 bits here never meets a subnormal.
    const int drop = width - 53;
    auto mantissa = static_cast<std::uint64_t>(top >> drop);
    const Wide rest = top & ((static_cast<Wide>(1) << drop) - 1);
    const Wide half = static_cast<Wide>(1) << (drop - 1);
    if (rest > half || (rest == half && (sticky || (mantissa & 1) != 0))) ++mantissa;
    return std::ldexp(static_cast<double>(mantissa), exponent + drop);
  }

  static int count_leading_zeros(Wide v) {
    const auto high = static_cast<std::uint64_t>(v >> 64);
    return high != 0 ? std::countl_zero(high)
                     : 64 + std::countl_zero(static_cast<std::uint64_t>(v));
  }

  std::array<std::int64_t, kWords> word_{};
  std::int64_t terms_ = 0;  // since the last carry
};

}  // namespace granjet
