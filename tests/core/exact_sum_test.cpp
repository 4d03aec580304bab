// The exact sum (core/exact_sum.hpp) rounds once, to nearest with ties to even, whatever the
// order of its terms or their split between accumulators.
#include "core/exact_sum.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace granjet {
namespace {

__extension__ typedef __int128 Int128;  // GCC's and Clang's

double exact_sum(const std::vector<double>& terms) {
  ExactSum s;
  for (double x : terms) s.add(x);
  return s.value();
}

// Same bits (so +0 and -0 differ, and a NaN equals a NaN).
void expect_bits(double expected, double got) {
  EXPECT_EQ(std::bit_cast<std::uint64_t>(expected), std::bit_cast<std::uint64_t>(got))
      << expected << " against " << got;
}

// Doubles with random signs, mantissas and exponents in [low, high).
std::vector<double> random_terms(std::size_t n, int low, int high, std::uint64_t seed) {
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> mantissa(1.0, 2.0);
  std::uniform_int_distribution<int> exponent(low, high - 1);
  std::vector<double> terms(n);
  for (double& x : terms) x = std::ldexp(gen() % 2 ? mantissa(gen) : -mantissa(gen), exponent(gen));
  return terms;
}

// IEEE addition of two doubles is itself rounded once from the exact sum.
TEST(ExactSum, TwoTermsGiveTheirRoundedIeeeSum) {
  const std::vector<double> a = random_terms(20000, -60, 60, 1),
                            b = random_terms(20000, -60, 60, 2);
  for (std::size_t k = 0; k < a.size(); ++k) {
    expect_bits(a[k] + b[k], exact_sum({a[k], b[k]}));
    // terms that differ only in their last bits: the sum cancels most of them
    const double near = std::nextafter(-a[k], 0.0);
    expect_bits(a[k] + near, exact_sum({a[k], near}));
  }
}

// An exact integer sum of terms no finer than 2^-100 (and below 2^110: 1000 of them fit in
// 128 bits), converted once to double.
TEST(ExactSum, ManyTermsGiveTheirExactSumRoundedOnce) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const std::vector<double> terms = random_terms(1000, -48, 10, seed);
    Int128 scaled = 0;  // in units of 2^-100: each term is a multiple of 2^(-48-52)
    for (double x : terms) scaled += static_cast<Int128>(std::ldexp(x, 100));
    expect_bits(std::ldexp(static_cast<double>(scaled), -100), exact_sum(terms));
  }
}

TEST(ExactSum, TiesGoToEvenAndAnyBitBelowBreaksThem) {
  const double half_ulp = std::ldexp(1.0, -53);  // of 1
  expect_bits(1.0, exact_sum({1.0, half_ulp}));
  expect_bits(1.0 + 2 * half_ulp, exact_sum({1.0, half_ulp, std::ldexp(1.0, -900)}));
  expect_bits(1.0 + 4 * half_ulp, exact_sum({1.0 + 2 * half_ulp, half_ulp}));
  expect_bits(1.0, exact_sum({1.0, half_ulp, -std::ldexp(1.0, -900)}));
}

TEST(ExactSum, CancellationLosesNothing) {
  expect_bits(1.0, exact_sum({1e100, 1.0, -1e100}));
  expect_bits(std::ldexp(1.0, -1074), exact_sum({1e300, std::ldexp(1.0, -1074), -1e300}));
  const double max = std::numeric_limits<double>::max();
  expect_bits(max, exact_sum({max, max, -max}));  // beyond the range of double on the way
  expect_bits(0.0, exact_sum({0.1, -0.1}));
  expect_bits(0.0, exact_sum({}));
}

TEST(ExactSum, SubnormalsAndOverflow) {
  const double tiny = std::ldexp(1.0, -1074);
  expect_bits(3 * tiny, exact_sum({tiny, tiny, tiny}));
  const double min_normal = std::numeric_limits<double>::min();
  expect_bits(min_normal + tiny, exact_sum({min_normal - tiny, 2 * tiny}));
  const double max = std::numeric_limits<double>::max();
  const double inf = std::numeric_limits<double>::infinity();
  expect_bits(inf, exact_sum({max, max}));
  expect_bits(-inf, exact_sum({-max, -max, -max}));
  // below the half-way point to 2^1024 rounds down to max, at it rounds to infinity
  const double half_ulp_of_max = std::ldexp(1.0, 970);
  expect_bits(max, exact_sum({max, std::nextafter(half_ulp_of_max, 0.0)}));
  expect_bits(inf, exact_sum({max, half_ulp_of_max}));
}

TEST(ExactSum, InfinitiesAndNanRuleAsInAPlainSum) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(inf, exact_sum({1.0, inf, -3.0}));
  EXPECT_EQ(-inf, exact_sum({-inf, 1e308}));
  EXPECT_TRUE(std::isnan(exact_sum({inf, 1.0, -inf})));
  EXPECT_TRUE(std::isnan(exact_sum({1.0, std::numeric_limits<double>::quiet_NaN()})));
}

// Sums over ranks add the accumulators' words: any order and any split gives the same bits.
TEST(ExactSum, AnyOrderAndAnySplitGiveTheSameBits) {
  std::vector<double> terms = random_terms(30000, -1074, 1000, 7);
  const std::vector<double> more = random_terms(30000, -30, 30, 8);
  terms.insert(terms.end(), more.begin(), more.end());
  const double expected = exact_sum(terms);
  std::mt19937_64 gen(9);
  for (int round = 0; round < 5; ++round) {
    std::shuffle(terms.begin(), terms.end(), gen);
    expect_bits(expected, exact_sum(terms));
    ExactSum part[3];
    for (std::size_t k = 0; k < terms.size(); ++k) part[gen() % 3].add(terms[k]);
    const auto joined = part[0].words();
    for (int p = 1; p < 3; ++p) {
      const auto words = part[p].words();
      for (std::size_t w = 0; w < words.size(); ++w) joined[w] += words[w];
    }
    expect_bits(expected, part[0].value());
  }
}

// A checkpoint keeps the words: the sum made of them goes on with the same bits.
TEST(ExactSum, WordsMakeTheSameSumAgain) {
  const std::vector<double> terms = random_terms(1000, -60, 60, 11);
  ExactSum whole, first;
  for (std::size_t k = 0; k < terms.size(); ++k) {
    whole.add(terms[k]);
    if (k < terms.size() / 2) first.add(terms[k]);
  }
  const auto words = first.words();
  ExactSum again = ExactSum::of_words(std::vector<std::int64_t>(words.begin(), words.end()));
  for (std::size_t k = terms.size() / 2; k < terms.size(); ++k) again.add(terms[k]);
  expect_bits(whole.value(), again.value());
  EXPECT_THROW(ExactSum::of_words(std::vector<std::int64_t>(3, 0)), std::invalid_argument);
}

}  // namespace
}  // namespace granjet
