// The fits recover the parameters of noisy synthetic data within their error bars, and the error
// bars are calibrated (about 68% of repeated fits lie within one standard error).
#include "analysis/fits.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "analysis/line_fit.hpp"

namespace granjet::analysis {
namespace {

struct Synthetic {
  std::vector<double> x, y;
};

// n points, x log-spaced over [lo, hi], y = law(x) + Gaussian noise of deviation `noise` (0:
// exact data).
Synthetic make_data(const std::function<double(double)>& law, double lo, double hi, int n,
                    double noise, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  const auto gauss = [&](std::mt19937_64& r) { return noise * unit(r); };
  Synthetic s;
  for (int k = 0; k < n; ++k) {
    const double x = lo * std::pow(hi / lo, k / (n - 1.0));
    s.x.push_back(x);
    s.y.push_back(law(x) + gauss(rng));
  }
  return s;
}

// Every parameter within 3 standard errors of its true value (a 0.3% chance per parameter of a
// false failure for a correct fit; the seeds are fixed, so a pass is reproducible), and the
// standard errors finite and small against the values.
void expect_recovered(const FitResult& fit, const std::vector<double>& truth) {
  SCOPED_TRACE(fit.law);
  ASSERT_TRUE(fit.converged);
  ASSERT_EQ(fit.value.size(), static_cast<Eigen::Index>(truth.size()));
  for (std::size_t k = 0; k < truth.size(); ++k) {
    SCOPED_TRACE(fit.parameters[k]);
    ASSERT_TRUE(std::isfinite(fit.error[k]));
    EXPECT_GT(fit.error[k], 0.0);
    EXPECT_LT(fit.error[k], 0.2 * std::abs(truth[k]));
    EXPECT_LT(std::abs(fit.value[k] - truth[k]), 3.0 * fit.error[k]);
  }
}

TEST(Fits, Eq6_2_PhiOfITRecovered) {
  const auto d =
      make_data([](double i) { return packing_law(i, 0.82, 0.45, 1.6); }, 0.02, 0.8, 40, 0.003, 11);
  expect_recovered(fit_phi_of_i_t(d.x, d.y), {0.82, 0.45, 1.6});
}

TEST(Fits, Eq6_3_PhiOfISRecovered) {
  const auto d =
      make_data([](double i) { return packing_law(i, 0.80, 0.3, 2.5); }, 0.01, 1.0, 40, 0.003, 12);
  const FitResult fit = fit_phi_of_i_s(d.x, d.y);
  expect_recovered(fit, {0.80, 0.3, 2.5});
  EXPECT_EQ(fit.parameters, (std::vector<std::string>{"phi_s", "a_s", "alpha_s"}));
}

TEST(Fits, Eq6_9_SaturatingFrictionRecovered) {
  const auto d = make_data([](double i) { return friction_saturating(i, 0.25, 0.7, 0.3); }, 0.01,
                           5.0, 40, 0.005, 13);
  const FitResult fit = fit_mu_saturating(d.x, d.y);
  expect_recovered(fit, {0.25, 0.7, 0.3});
  EXPECT_EQ(fit.law, "6.9");
}

// [6.10] as the study fits it, "assuming mu_s = 0" (model §6): exactly two parameters, b and
// beta. Exact data give them back to rounding (the standard errors, s^2 from SSR ~ 0, vanish
// with it); noisy data within 3 standard errors.
TEST(Fits, Eq6_10_PowerFrictionWithMuSZeroHasTwoParameters) {
  const auto exact =
      make_data([](double i) { return friction_power(i, 0.0, 0.6, 0.7); }, 0.01, 1.0, 40, 0.0, 14);
  const FitResult fit = fit_mu_power(exact.x, exact.y);
  EXPECT_EQ(fit.law, "6.10");
  ASSERT_EQ(fit.parameters, (std::vector<std::string>{"b", "beta"}));
  ASSERT_TRUE(fit.converged);
  EXPECT_NEAR(fit["b"], 0.6, 1e-9);
  EXPECT_NEAR(fit["beta"], 0.7, 1e-9);
  EXPECT_EQ(fit.points, 40);
  for (const char* name : {"b", "beta"}) {
    SCOPED_TRACE(name);
    EXPECT_TRUE(std::isfinite(fit.error_of(name)));
    EXPECT_LT(fit.error_of(name), 1e-8);
  }
  const auto noisy = make_data([](double i) { return friction_power(i, 0.0, 0.6, 0.7); }, 0.01, 1.0,
                               40, 0.005, 14);
  expect_recovered(fit_mu_power(noisy.x, noisy.y), {0.6, 0.7});
}

// With mu_s fixed at 0 the fit does not absorb an offset: data with mu_s = 0.2 leave a
// residual far above the noise, where a free mu_s would fit them to the noise level.
TEST(Fits, Eq6_10_MuSIsFixedAtZeroNotFitted) {
  const auto d = make_data([](double i) { return friction_power(i, 0.2, 0.6, 0.7); }, 0.01, 1.0, 40,
                           0.005, 18);
  const FitResult fit = fit_mu_power(d.x, d.y);
  ASSERT_EQ(fit.value.size(), 2);
  EXPECT_GT(fit.ssr / fit.points, 10.0 * 0.005 * 0.005);
}

// The reported errors of the two-parameter fit are calibrated: over 200 noisy data sets about
// 68.3% of the fits lie within one standard error of the truth (binomial spread 0.033; the
// window is 3 of those), for b and for beta.
TEST(Fits, Eq6_10_StandardErrorsAreCalibrated) {
  constexpr int kTrials = 200;
  int b_within = 0, beta_within = 0;
  for (int t = 0; t < kTrials; ++t) {
    const auto d = make_data([](double i) { return friction_power(i, 0.0, 0.6, 0.7); }, 0.01, 1.0,
                             25, 0.01, 2000 + t);
    const FitResult fit = fit_mu_power(d.x, d.y);
    b_within += std::abs(fit["b"] - 0.6) < fit.error_of("b");
    beta_within += std::abs(fit["beta"] - 0.7) < fit.error_of("beta");
  }
  EXPECT_NEAR(b_within / double(kTrials), 0.683, 0.1);
  EXPECT_NEAR(beta_within / double(kTrials), 0.683, 0.1);
}

TEST(Fits, LinearFrictionThroughOriginRecovered) {
  const auto d = make_data([](double i) { return 1.3 * i; }, 0.01, 0.3, 20, 0.01, 15);
  expect_recovered(fit_mu_linear(d.x, d.y), {1.3});
}

// The free-intercept line against the closed form of least squares: slope S_xy/S_xx, intercept
// mean(y) - slope mean(x), and the textbook standard errors s^2/S_xx and s^2 (1/n + xbar^2/S_xx).
TEST(Fits, AffineFrictionMatchesTheClosedForm) {
  const auto d = make_data([](double i) { return 0.1 + 1.3 * i; }, 0.01, 0.3, 20, 0.01, 19);
  const double n = static_cast<double>(d.x.size());
  double xbar = 0, ybar = 0;
  for (std::size_t k = 0; k < d.x.size(); ++k) xbar += d.x[k] / n, ybar += d.y[k] / n;
  double sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < d.x.size(); ++k) {
    sxx += (d.x[k] - xbar) * (d.x[k] - xbar);
    sxy += (d.x[k] - xbar) * (d.y[k] - ybar);
  }
  const double slope = sxy / sxx, intercept = ybar - slope * xbar;
  double ssr = 0;
  for (std::size_t k = 0; k < d.x.size(); ++k) {
    const double r = d.y[k] - intercept - slope * d.x[k];
    ssr += r * r;
  }
  const double s2 = ssr / (n - 2);
  const FitResult fit = fit_mu_affine(d.x, d.y);
  EXPECT_TRUE(fit.converged);
  EXPECT_NEAR(fit["a"], slope, 1e-9);
  EXPECT_NEAR(fit["mu_0"], intercept, 1e-9);
  EXPECT_NEAR(fit.error_of("a"), std::sqrt(s2 / sxx), 1e-6 * std::sqrt(s2 / sxx));
  EXPECT_NEAR(fit.error_of("mu_0"), std::sqrt(s2 * (1 / n + xbar * xbar / sxx)),
              1e-6 * std::sqrt(s2 * (1 / n + xbar * xbar / sxx)));
  EXPECT_NEAR(fit.ssr, ssr, 1e-12);
}

TEST(Fits, ScatteringAngleInterpolationRecovered) {
  // psi0 rises as C1 X from C2 and saturates at C0 (X = D_tar/D_jet).
  const auto d = make_data([](double x) { return scattering_angle_law(x, 1.9, 1.2, 0.3); }, 0.2,
                           4.0, 30, 0.01, 16);
  const FitResult fit = fit_scattering_angle(d.x, d.y);
  expect_recovered(fit, {1.9, 1.2, 0.3});
  EXPECT_NEAR(scattering_angle_law(0.0, 1.9, 1.2, 0.3), 0.3, 1e-15);  // C2 at X = 0
  EXPECT_NEAR(scattering_angle_law(1e3, 1.9, 1.2, 0.3), 1.9, 1e-12);  // C0 for X -> infinity
}

TEST(Fits, NonFinitePointsAndNonPositiveISkipped) {
  auto d = make_data([](double i) { return friction_power(i, 0.2, 0.6, 0.7); }, 0.01, 1.0, 30,
                     0.005, 17);
  d.x.push_back(-0.5);  // power laws are undefined for I <= 0
  d.y.push_back(0.3);
  d.x.push_back(0.5);
  d.y.push_back(std::nan(""));  // an empty bin
  EXPECT_EQ(fit_mu_power(d.x, d.y).points, 30);
}

// Fewer points than parameters: no value at all (not the initial guess); as many: the values
// pass through the points, with no error to give.
TEST(Fits, TooFewPointsGiveNaN) {
  const std::vector<double> x{0.1, 0.2}, y{0.3, 0.4};
  const FitResult few = fit_mu_saturating(x, y);
  EXPECT_TRUE(std::isnan(few.value[0]) && std::isnan(few.value[2]) && std::isnan(few.ssr));
  EXPECT_TRUE(std::isnan(few.error[0]));
  const FitResult exact = fit_mu_affine(x, y);
  EXPECT_NEAR(exact["a"], 1.0, 1e-9);
  EXPECT_NEAR(exact["mu_0"], 0.2, 1e-9);
  EXPECT_TRUE(std::isnan(exact.error_of("a")));
}

// cov = s^2 (J^T J)^-1 is calibrated: over 200 noisy data sets, the fraction of fits whose I_0
// lies within one standard error of the truth is 0.683 up to its binomial spread 0.033
// (the window below is about 3 of those), and the same for mu_s.
TEST(Fits, Eq6_9_StandardErrorsAreCalibrated) {
  constexpr int kTrials = 200;
  int mu_s_within = 0, i_0_within = 0;
  for (int t = 0; t < kTrials; ++t) {
    const auto d = make_data([](double i) { return friction_saturating(i, 0.25, 0.7, 0.3); }, 0.01,
                             5.0, 25, 0.01, 1000 + t);
    const FitResult fit = fit_mu_saturating(d.x, d.y);
    mu_s_within += std::abs(fit["mu_s"] - 0.25) < fit.error_of("mu_s");
    i_0_within += std::abs(fit["I_0"] - 0.3) < fit.error_of("I_0");
  }
  EXPECT_NEAR(mu_s_within / double(kTrials), 0.683, 0.1);
  EXPECT_NEAR(i_0_within / double(kTrials), 0.683, 0.1);
}

// The running least-squares line recovers a known line from noisy samples with the textbook
// normal-equation solution (checked against a direct solve of the two sums).
TEST(LineFit, RecoversSlopeAndIntercept) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 0.01);
  LineFit fit;
  std::vector<double> x, y;
  for (int k = 0; k < 50; ++k) {
    x.push_back(0.2 * k);
    y.push_back(2.0 - 0.5 * x.back() + noise(rng));
    fit.add(x.back(), y.back());
  }
  EXPECT_NEAR(fit.slope(), -0.5, 0.002);
  EXPECT_NEAR(fit.intercept(), 2.0, 0.01);
  LineFit exact;
  exact.add(1.0, 3.0);
  exact.add(3.0, 7.0);
  EXPECT_DOUBLE_EQ(exact.slope(), 2.0);
  EXPECT_DOUBLE_EQ(exact.intercept(), 1.0);
  EXPECT_EQ(exact.size(), 2);
}

}  // namespace
}  // namespace granjet::analysis
