// [2.1]-[2.4] on random inputs (the seed is printed so a failure can be replayed).
#include "core/collision_rules.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "core/dim.hpp"

namespace granjet {
namespace {

template <class T>
class CollisionRules : public ::testing::Test {};
using Dims = ::testing::Types<Dim<2>, Dim<3>>;
TYPED_TEST_SUITE(CollisionRules, Dims);

template <class VecT>
struct RandomPair {
  explicit RandomPair(std::mt19937_64& rng) {
    std::normal_distribution<double> g;
    for (int d = 0; d < VecT::RowsAtCompileTime; ++d) {
      k[d] = g(rng);
      v1[d] = g(rng);
      v2[d] = g(rng);
    }
    k.normalize();
    std::uniform_real_distribution<double> u(0.05, 1.0);
    e = u(rng);
    inv_m1 = 1.0 / (0.2 + 3.0 * u(rng));
    inv_m2 = 1.0 / (0.2 + 3.0 * u(rng));
  }
  VecT k, v1, v2;
  double e, inv_m1, inv_m2;
};

constexpr std::uint64_t kSeed = 20261122;
constexpr int kTrials = 1000;

TYPED_TEST(CollisionRules, Eq2_1_ConservesMomentumScalesNormalKeepsTangential) {
  using VecT = typename TypeParam::Vec;
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  std::mt19937_64 rng(kSeed);
  for (int t = 0; t < kTrials; ++t) {
    RandomPair<VecT> c(rng);
    VecT a = c.v1, b = c.v2;
    const VecT impulse = collide(c.k, a, b, c.inv_m1, c.inv_m2, c.e);
    const VecT p_before = c.v1 / c.inv_m1 + c.v2 / c.inv_m2;
    const VecT p_after = a / c.inv_m1 + b / c.inv_m2;
    EXPECT_NEAR((p_after - p_before).norm(), 0.0, 1e-12);
    EXPECT_NEAR((a - c.v1).dot(c.k) / c.inv_m1, impulse.dot(c.k), 1e-12);
    const double vn_before = c.k.dot(c.v1 - c.v2), vn_after = c.k.dot(a - b);
    EXPECT_NEAR(vn_after, -c.e * vn_before, 1e-12);
    const VecT vt_before = (c.v1 - c.v2) - vn_before * c.k;
    const VecT vt_after = (a - b) - vn_after * c.k;
    EXPECT_NEAR((vt_after - vt_before).norm(), 0.0, 1e-12);
  }
}

TYPED_TEST(CollisionRules, EnergyLossIsOneMinusESquaredQuarterMVnSquared) {
  using VecT = typename TypeParam::Vec;
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  std::mt19937_64 rng(kSeed + 1);
  for (int t = 0; t < kTrials; ++t) {
    RandomPair<VecT> c(rng);
    c.inv_m1 = c.inv_m2 = 1.0;  // equal masses m = 1: loss = (1-e^2)/4 m (k.v12)^2 [model §1]
    VecT a = c.v1, b = c.v2;
    collide(c.k, a, b, 1.0, 1.0, c.e);
    const double before = 0.5 * (c.v1.squaredNorm() + c.v2.squaredNorm());
    const double after = 0.5 * (a.squaredNorm() + b.squaredNorm());
    const double vn = c.k.dot(c.v1 - c.v2);
    EXPECT_NEAR(before - after, (1.0 - c.e * c.e) / 4.0 * vn * vn, 1e-12);
    EXPECT_NEAR(before - after, collision_energy_loss(c.k, c.v1, c.v2, 1.0, 1.0, c.e), 1e-12);
  }
}

TYPED_TEST(CollisionRules, Eq2_3_InverseThenDirectIsIdentity) {
  using VecT = typename TypeParam::Vec;
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  std::mt19937_64 rng(kSeed + 2);
  for (int t = 0; t < kTrials; ++t) {
    RandomPair<VecT> c(rng);
    VecT a = c.v1, b = c.v2;
    collide_inverse(c.k, a, b, c.inv_m1, c.inv_m2, c.e);
    collide(c.k, a, b, c.inv_m1, c.inv_m2, c.e);
    EXPECT_NEAR((a - c.v1).norm(), 0.0, 1e-12);
    EXPECT_NEAR((b - c.v2).norm(), 0.0, 1e-12);
  }
}

TYPED_TEST(CollisionRules, ElasticCollisionConservesEnergy) {
  using VecT = typename TypeParam::Vec;
  std::mt19937_64 rng(kSeed + 3);
  for (int t = 0; t < kTrials; ++t) {
    RandomPair<VecT> c(rng);
    VecT a = c.v1, b = c.v2;
    collide(c.k, a, b, c.inv_m1, c.inv_m2, 1.0);
    const double before = 0.5 * (c.v1.squaredNorm() / c.inv_m1 + c.v2.squaredNorm() / c.inv_m2);
    const double after = 0.5 * (a.squaredNorm() / c.inv_m1 + b.squaredNorm() / c.inv_m2);
    EXPECT_NEAR(after, before, 1e-12 * before);
  }
}

TYPED_TEST(CollisionRules, InfiniteMassPartnerReflectsWithE) {
  using VecT = typename TypeParam::Vec;
  std::mt19937_64 rng(kSeed + 4);
  for (int t = 0; t < kTrials; ++t) {
    RandomPair<VecT> c(rng);
    VecT a = c.v1;
    VecT wall = VecT::Zero();
    collide(c.k, a, wall, c.inv_m1, 0.0, c.e);
    EXPECT_EQ(wall, VecT::Zero());
    EXPECT_NEAR(c.k.dot(a), -c.e * c.k.dot(c.v1), 1e-12);
    EXPECT_NEAR((a - a.dot(c.k) * c.k - (c.v1 - c.v1.dot(c.k) * c.k)).norm(), 0.0, 1e-12);
  }
  EXPECT_DOUBLE_EQ(reduced_mass(0.5, 0.0), 2.0);
}

}  // namespace
}  // namespace granjet
