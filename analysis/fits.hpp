// Least-squares fits of the study's laws (model §6, "Fits") by Eigen's Levenberg-Marquardt
// (unsupported module), with parameter standard errors from the Jacobian at the optimum:
// cov = s^2 (J^T J)^-1, s^2 = SSR/(n - p). The errors are therefore scaled by the scatter of the
// data about the fit (what scipy calls absolute_sigma=False); no per-point weights are used.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace granjet::analysis {

struct FitResult {
  // Which law: "6.2", "6.3", "6.9", "6.10" (model labels), "mu_linear", "mu_affine", "psi0_X";
  // also the
  // fit's name in the JSON and HDF5 output.
  std::string law;
  std::vector<std::string> parameters;  // names, in the order of `value`
  Eigen::VectorXd value;                // NaN when there are fewer points than parameters
  Eigen::VectorXd error;                // standard errors; NaN when n <= p or J^T J is singular
  double ssr = 0.0;                     // sum of squared residuals at the optimum
  int points = 0;
  bool converged = false;

  double operator[](const std::string& name) const;  // value by name
  double error_of(const std::string& name) const;
};

// y = model(x, p).
using FitModel = std::function<double(double x, const Eigen::VectorXd& p)>;

// General fit from the initial guess p0. Points where x or y is not finite are skipped.
FitResult fit_curve(const FitModel& model, std::span<const double> x, std::span<const double> y,
                    const Eigen::VectorXd& p0, std::vector<std::string> parameters,
                    std::string law);

// The laws, as used by the fits below (and by tests to make synthetic data).
double packing_law(double i, double phi_0, double a, double alpha);              // [6.2]/[6.3]
double friction_saturating(double i_s, double mu_s, double mu_max, double i_0);  // [6.9]
double friction_power(double i_s, double mu_s, double b, double beta);           // [6.10]
double friction_linear(double i, double a);                                      // 3D mu* = a I
double scattering_angle_law(double x, double c0, double c1, double c2);          // §6 psi0(X)

// The fits; initial guesses come from the data. Points with a non-positive inertial number are
// skipped by the power laws (they are undefined there).
// [6.2] phi = phi_T - a_T I_T^(2/alpha_T): parameters phi_T, a_T, alpha_T.
FitResult fit_phi_of_i_t(std::span<const double> i_t, std::span<const double> phi);
// [6.3] phi = phi_s - a_s I_s^(2/alpha_s): parameters phi_s, a_s, alpha_s.
FitResult fit_phi_of_i_s(std::span<const double> i_s, std::span<const double> phi);
// [6.9] mu* = mu_s + (mu_max - mu_s)/(1 + I_0/I_s): parameters mu_s, mu_max, I_0.
FitResult fit_mu_saturating(std::span<const double> i_s, std::span<const double> mu);
// [6.10] mu* = mu_s + b I_s^beta with mu_s = 0, as the study fits it: parameters b, beta.
FitResult fit_mu_power(std::span<const double> i_s, std::span<const double> mu);
// 3D mu* = a I through the origin: parameter a.
FitResult fit_mu_linear(std::span<const double> i, std::span<const double> mu);
// 3D mu* = mu_0 + a I, the line with a free intercept (a reading of F5.7 that allows a yield
// value mu_0): parameters mu_0, a.
FitResult fit_mu_affine(std::span<const double> i, std::span<const double> mu);
// psi0(X) = sqrt(C0'^2 (1 - exp(-C1^2 X^2/C0'^2))) + C2, C0' = C0 - C2: parameters C0, C1, C2.
// C1 enters squared; its magnitude is reported.
FitResult fit_scattering_angle(std::span<const double> x, std::span<const double> psi0);

}  // namespace granjet::analysis
