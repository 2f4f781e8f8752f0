// SPDX-License-Identifier: MIT
// Residual diagnostics of a linear(ised) least-squares fit, used to tell LOS from NLOS timestamps
// (Bordoy 2020 PhD thesis, Univ. Freiburg, Sec. 5.1, Eq. 5.7-5.15): leverages (the hat matrix's
// diagonal, 5.11), the noise estimate (5.13), studentized residuals (5.12), Cook's distance and its
// F-distribution threshold.
// Assumptions and choices (digest Sec. 2.6, typo list items 5 and 6):
//  - the rows have equal noise variance; whiten rows and residuals first otherwise;
//  - Cook's distance is the textbook D_i = e_i^2 l_ii / (p' sigma^2 (1 - l_ii)^2), which equals
//    (x - x_(-i))^T H^T H (x - x_(-i)) / (p' sigma^2) with x_(-i) the fit without row i. The
//    printed (5.15) drops l_ii and sigma^2, and (5.14) drops the H^T H metric;
//  - p' = p + 1 by default, following the thesis's (p + 1) normalisation (the textbook counts an
//    intercept among the p parameters and divides by p);
//  - a row with leverage 1 (1 - l_ii <= 1e-10) alone fixes a direction of x: its residual is 0 by
//    construction and cannot be tested, so its studentized residual and Cook's distance are NaN
//    (every comparison with a threshold is then false: the row never counts as "low influence").
#pragma once

#include <optional>

#include <Eigen/Core>

namespace mirage::estimation {

/// How the diagnostics are normalised.
struct RegressionDiagnosticsOptions {
  /// The rows' noise standard deviation sigma (residual unit), > 0, when known; empty: the
  /// estimate sigma_hat of Eq. (5.13).
  std::optional<double> sigma = std::nullopt;
  /// The divisor p' of Cook's distance, >= 1; empty: p + 1, the thesis's normalisation.
  std::optional<int> p_prime = std::nullopt;
};

/// The diagnostics of every row of the fit.
struct RegressionDiagnostics {
  /// Leverages l_ii = diag(H (H^T H)^-1 H^T), Eq. (5.11), in [0, 1]; they sum to p.
  Eigen::VectorXd leverage;
  /// sqrt(sum e_i^2 / (m - p)), Eq. (5.13) (residual unit); NaN when m == p.
  double sigma_hat = 0.0;
  /// The sigma used below: the given one, or sigma_hat.
  double sigma_used = 0.0;
  /// The divisor p' used in Cook's distance.
  int p_prime = 0;
  /// e_i / (sigma sqrt(1 - l_ii)), Eq. (5.12), with the sign of e_i; NaN for leverage 1.
  Eigen::VectorXd studentized;
  /// e_i^2 l_ii / (p' sigma^2 (1 - l_ii)^2) (textbook form of 5.14-5.15); NaN for leverage 1.
  Eigen::VectorXd cooks_distance;
};

/// The diagnostics of a least-squares fit with Jacobian H (m x p) and residuals e (m) at the
/// solution (either sign convention: e = z_hat - z as in Eq. 5.9, or z - z_hat).
/// std::nullopt when H^T H is singular (H not of full column rank), or when sigma is not given
/// and m <= p (no redundancy to estimate it).
std::optional<RegressionDiagnostics> DiagnoseRegression(const Eigen::MatrixXd& H, const Eigen::VectorXd& residuals,
                                                        const RegressionDiagnosticsOptions& options = {});

/// The regularized incomplete beta function I_x(a, b) for x in [0, 1], a, b > 0 (continued
/// fraction, relative accuracy ~1e-14).
double RegularizedIncompleteBeta(double x, double a, double b);

/// P(F <= x) for F ~ F(d1, d2), d1, d2 > 0; 0 for x <= 0.
double FCdf(double x, double d1, double d2);

/// The x with FCdf(x, d1, d2) = prob, for prob in [0, 1) and d1, d2 > 0 (bisection to 1e-12
/// relative).
double FQuantile(double prob, double d1, double d2);

/// The Cook's-distance threshold F_prob(p', m - p') (thesis Sec. 5.1: "Cook's distance follows an
/// F distribution"); a row with D_i above it is influential at level prob.
/// @param prob    the quantile's probability, in [0, 1) (0.5 is the usual textbook choice).
/// @param p_prime the divisor p' of Cook's distance, >= 1.
/// @param m       the number of rows, > p'.
double CookThreshold(double prob, int p_prime, int m);

}  // namespace mirage::estimation
