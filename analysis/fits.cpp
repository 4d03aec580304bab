// Before any include: GCC 12 with -march=native (AVX-512) reports a false
// (-Wmaybe-)uninitialized inside Eigen's AVX-512 packets (GCC bug 105593), instantiated here by
// the dense QR solvers and the vectorised pow.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"

#include "analysis/fits.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unsupported/Eigen/LevenbergMarquardt>
#include <unsupported/Eigen/NumericalDiff>
#include <utility>

namespace granjet::analysis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Points {
  Eigen::VectorXd x, y;
};

Points finite_points(std::span<const double> x, std::span<const double> y, bool positive_x) {
  if (x.size() != y.size()) throw std::invalid_argument("fit: x and y differ in length");
  std::vector<double> xs, ys;
  for (std::size_t k = 0; k < x.size(); ++k)
    if (std::isfinite(x[k]) && std::isfinite(y[k]) && (!positive_x || x[k] > 0.0)) {
      xs.push_back(x[k]);
      ys.push_back(y[k]);
    }
  return {Eigen::Map<Eigen::VectorXd>(xs.data(), xs.size()),
          Eigen::Map<Eigen::VectorXd>(ys.data(), ys.size())};
}

// Residuals model(x_k, p) - y_k in the shape Eigen's LevenbergMarquardt expects; the Jacobian
// comes from NumericalDiff (central differences).
struct Residuals : Eigen::DenseFunctor<double> {
  Residuals(const FitModel& m, const Points& d, int parameters)
      : DenseFunctor(parameters, static_cast<int>(d.x.size())), model(&m), data(&d) {}
  int operator()(const InputType& p, ValueType& r) const {
    for (Eigen::Index k = 0; k < data->x.size(); ++k) r[k] = (*model)(data->x[k], p) - data->y[k];
    return 0;
  }
  const FitModel* model;
  const Points* data;
};

FitResult fit_points(const FitModel& model, const Points& data, const Eigen::VectorXd& p0,
                     std::vector<std::string> parameters, std::string law) {
  FitResult fit;
  fit.law = std::move(law);
  fit.parameters = std::move(parameters);
  fit.points = static_cast<int>(data.x.size());
  const auto p = static_cast<int>(p0.size());
  fit.value = p0;
  fit.error = Eigen::VectorXd::Constant(p, kNaN);
  if (fit.points < p) {  // nothing to fit: no value, not the initial guess
    fit.value.setConstant(kNaN);
    fit.ssr = kNaN;
    return fit;
  }
  Eigen::NumericalDiff<Residuals, Eigen::Central> functor(Residuals(model, data, p));
  Eigen::LevenbergMarquardt<decltype(functor)> lm(functor);
  lm.setMaxfev(2000 * (p + 1));
  const auto status = lm.minimize(fit.value);
  fit.converged = lm.info() == Eigen::Success &&
                  status != Eigen::LevenbergMarquardtSpace::TooManyFunctionEvaluation;

  Eigen::VectorXd r(fit.points);
  functor(fit.value, r);
  fit.ssr = r.squaredNorm();
  if (fit.points > p) {
    Eigen::MatrixXd jac(fit.points, p);
    functor.df(fit.value, jac);
    const Eigen::MatrixXd jtj = jac.transpose().lazyProduct(jac);  // p x p: no GEMM needed
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(jtj);
    if (lu.isInvertible()) {
      const double s2 = fit.ssr / (fit.points - p);
      fit.error = (s2 * lu.inverse().diagonal()).cwiseSqrt();
    }
  }
  return fit;
}

// Initial guess for a model linear in all parameters but one, g: for each g of `grid`, the
// linear least-squares coefficients of the columns basis(x, g); returns the best (g, coeffs).
template <class Basis>
std::pair<double, Eigen::VectorXd> linear_start(const Points& d, const std::vector<double>& grid,
                                                Basis basis) {
  double best_ssr = std::numeric_limits<double>::infinity();
  std::pair<double, Eigen::VectorXd> best{grid.front(), Eigen::VectorXd()};
  for (double g : grid) {
    const Eigen::MatrixXd a = basis(d.x, g);
    const Eigen::VectorXd c = a.colPivHouseholderQr().solve(d.y);
    const double ssr = (a * c - d.y).squaredNorm();
    if (std::isfinite(ssr) && ssr < best_ssr) {
      best_ssr = ssr;
      best = {g, c};
    }
  }
  if (best.second.size() == 0) best.second = Eigen::VectorXd::Zero(basis(d.x, grid.front()).cols());
  return best;
}

std::vector<double> log_grid(double lo, double hi, int n) {
  std::vector<double> grid;
  for (int k = 0; k < n; ++k) grid.push_back(lo * std::pow(hi / lo, k / (n - 1.0)));
  return grid;
}

// Columns [1, x^e] for the power laws [6.2], [6.3].
Eigen::MatrixXd power_basis(const Eigen::VectorXd& x, double exponent) {
  Eigen::MatrixXd a(x.size(), 2);
  a.col(0).setOnes();
  a.col(1) = x.array().pow(exponent);
  return a;
}

FitResult fit_packing(std::span<const double> i, std::span<const double> phi,
                      std::vector<std::string> names, std::string law) {
  const Points d = finite_points(i, phi, true);
  const FitModel model = [](double x, const Eigen::VectorXd& p) {
    return packing_law(x, p[0], p[1], p[2]);
  };
  Eigen::VectorXd p0(3);
  p0 << 0.0, 0.0, 2.0;
  if (d.x.size() >= 2) {
    const auto [exponent, c] = linear_start(d, log_grid(0.1, 10.0, 41), power_basis);
    p0 << c[0], -c[1], 2.0 / exponent;
  }
  return fit_points(model, d, p0, std::move(names), std::move(law));
}

}  // namespace

double FitResult::operator[](const std::string& name) const {
  const auto it = std::find(parameters.begin(), parameters.end(), name);
  if (it == parameters.end()) throw std::out_of_range("fit " + law + " has no parameter " + name);
  return value[it - parameters.begin()];
}

double FitResult::error_of(const std::string& name) const {
  const auto it = std::find(parameters.begin(), parameters.end(), name);
  if (it == parameters.end()) throw std::out_of_range("fit " + law + " has no parameter " + name);
  return error[it - parameters.begin()];
}

FitResult fit_curve(const FitModel& model, std::span<const double> x, std::span<const double> y,
                    const Eigen::VectorXd& p0, std::vector<std::string> parameters,
                    std::string law) {
  return fit_points(model, finite_points(x, y, false), p0, std::move(parameters), std::move(law));
}

double packing_law(double i, double phi_0, double a, double alpha) {
  return phi_0 - a * std::pow(i, 2.0 / alpha);  // [6.2] (I_T) and [6.3] (I_s)
}

double friction_saturating(double i_s, double mu_s, double mu_max, double i_0) {
  return mu_s + (mu_max - mu_s) / (1.0 + i_0 / i_s);  // [6.9]
}

double friction_power(double i_s, double mu_s, double b, double beta) {
  return mu_s + b * std::pow(i_s, beta);  // [6.10]
}

double friction_linear(double i, double a) { return a * i; }

double scattering_angle_law(double x, double c0, double c1, double c2) {
  const double c0p = c0 - c2;  // C0' (model §6)
  return std::sqrt(c0p * c0p * (1.0 - std::exp(-c1 * c1 * x * x / (c0p * c0p)))) + c2;
}

FitResult fit_phi_of_i_t(std::span<const double> i_t, std::span<const double> phi) {
  return fit_packing(i_t, phi, {"phi_T", "a_T", "alpha_T"}, "6.2");
}

FitResult fit_phi_of_i_s(std::span<const double> i_s, std::span<const double> phi) {
  return fit_packing(i_s, phi, {"phi_s", "a_s", "alpha_s"}, "6.3");
}

FitResult fit_mu_saturating(std::span<const double> i_s, std::span<const double> mu) {
  const Points d = finite_points(i_s, mu, true);
  const FitModel model = [](double x, const Eigen::VectorXd& p) {
    return friction_saturating(x, p[0], p[1], p[2]);
  };
  Eigen::VectorXd p0(3);
  p0 << 0.0, 0.0, 1.0;
  if (d.x.size() >= 2) {
    // For fixed I_0, [6.9] is mu_s (1 - w) + mu_max w with w = I_s/(I_s + I_0).
    const auto [i_0, c] =
        linear_start(d, log_grid(0.01 * d.x.minCoeff(), 100.0 * d.x.maxCoeff(), 61),
                     [](const Eigen::VectorXd& x, double i0) {
                       Eigen::MatrixXd a(x.size(), 2);
                       a.col(1) = x.array() / (x.array() + i0);
                       a.col(0) = 1.0 - a.col(1).array();
                       return a;
                     });
    p0 << c[0], c[1], i_0;
  }
  return fit_points(model, d, p0, {"mu_s", "mu_max", "I_0"}, "6.9");
}

FitResult fit_mu_power(std::span<const double> i_s, std::span<const double> mu) {
  // The study fits [6.10] "assuming mu_s = 0" (model §6): two free parameters, b and beta.
  const Points d = finite_points(i_s, mu, true);
  const FitModel model = [](double x, const Eigen::VectorXd& p) {
    return friction_power(x, 0.0, p[0], p[1]);
  };
  Eigen::VectorXd p0(2);
  p0 << 0.0, 1.0;
  if (d.x.size() >= 2) {
    // For a fixed beta, b I_s^beta is linear in b.
    const auto [beta, c] =
        linear_start(d, log_grid(0.05, 5.0, 41), [](const Eigen::VectorXd& x, double exponent) {
          return Eigen::MatrixXd(x.array().pow(exponent).matrix());
        });
    p0 << c[0], beta;
  }
  return fit_points(model, d, p0, {"b", "beta"}, "6.10");
}

FitResult fit_mu_linear(std::span<const double> i, std::span<const double> mu) {
  const Points d = finite_points(i, mu, false);
  const FitModel model = [](double x, const Eigen::VectorXd& p) {
    return friction_linear(x, p[0]);
  };
  Eigen::VectorXd p0(1);
  const double xx = d.x.squaredNorm();
  p0 << (xx > 0.0 ? d.x.dot(d.y) / xx : 0.0);
  return fit_points(model, d, p0, {"a"}, "mu_linear");
}

FitResult fit_mu_affine(std::span<const double> i, std::span<const double> mu) {
  const Points d = finite_points(i, mu, false);
  const FitModel model = [](double x, const Eigen::VectorXd& p) {
    return p[0] + friction_linear(x, p[1]);
  };
  Eigen::VectorXd p0 = Eigen::VectorXd::Zero(2);
  if (d.x.size() >= 2) {  // the linear least-squares line is the optimum already
    Eigen::MatrixXd a(d.x.size(), 2);
    a.col(0).setOnes();
    a.col(1) = d.x;
    p0 = a.colPivHouseholderQr().solve(d.y);
  }
  return fit_points(model, d, p0, {"mu_0", "a"}, "mu_affine");
}

FitResult fit_scattering_angle(std::span<const double> x, std::span<const double> psi0) {
  const Points d = finite_points(x, psi0, false);
  const FitModel model = [](double xv, const Eigen::VectorXd& p) {
    return scattering_angle_law(xv, p[0], p[1], p[2]);
  };
  Eigen::VectorXd p0(3);
  p0 << 1.0, 1.0, 0.0;
  if (d.x.size() >= 2) {
    // For a fixed k = C1/C0', psi0 = C0' sqrt(1 - exp(-k^2 X^2)) + C2 is linear in C0', C2.
    const double x_max = d.x.cwiseAbs().maxCoeff();
    const auto [k, c] = linear_start(
        d, log_grid(0.01 / x_max, 100.0 / x_max, 81), [](const Eigen::VectorXd& xv, double kk) {
          Eigen::MatrixXd a(xv.size(), 2);
          a.col(0) = (1.0 - (-kk * kk * xv.array().square()).exp()).sqrt();
          a.col(1).setOnes();
          return a;
        });
    p0 << c[0] + c[1], k * c[0], c[1];
  }
  FitResult fit = fit_points(model, d, p0, {"C0", "C1", "C2"}, "psi0_X");
  fit.value[1] = std::abs(fit.value[1]);
  return fit;
}

}  // namespace granjet::analysis
