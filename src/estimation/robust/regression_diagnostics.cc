// SPDX-License-Identifier: MIT
#include "mirage/estimation/robust/regression_diagnostics.h"

#include <cassert>
#include <cmath>
#include <limits>

#include <Eigen/QR>

namespace mirage::estimation {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The continued fraction of I_x(a, b) (Abramowitz & Stegun 26.5.8):
// I_x(a, b) = x^a (1 - x)^b / (a B(a, b)) / (1 + c_1 / (1 + c_2 / (1 + ...))), with
// c_{2k+1} = -(a + k)(a + b + k) x / ((a + 2k)(a + 2k + 1)), c_{2k} = k (b - k) x / ((a + 2k - 1)(a + 2k)).
// It converges quickly for x < (a + 1) / (a + b + 2). Evaluated by the modified Lentz method.
double BetaContinuedFraction(double x, double a, double b) {
  constexpr double kTiny = 1e-300;
  constexpr double kEps = 1e-15;
  double f = 1.0;  // value of 1 + c_1 / (1 + ...), built up term by term
  double C = f;
  double D = 0.0;
  for (int j = 1; j <= 1000; ++j) {
    const int k = j / 2;
    const double c = j % 2 == 1 ? -(a + k) * (a + b + k) * x / ((a + 2 * k) * (a + 2 * k + 1))
                                : k * (b - k) * x / ((a + 2 * k - 1) * (a + 2 * k));
    D = 1.0 + c * D;
    if (std::abs(D) < kTiny) D = kTiny;
    C = 1.0 + c / C;
    if (std::abs(C) < kTiny) C = kTiny;
    D = 1.0 / D;
    const double delta = C * D;
    f *= delta;
    if (std::abs(delta - 1.0) < kEps) break;
  }
  return 1.0 / f;
}

}  // namespace

std::optional<RegressionDiagnostics> DiagnoseRegression(const Eigen::MatrixXd& H, const Eigen::VectorXd& residuals,
                                                        const RegressionDiagnosticsOptions& options) {
  const Eigen::Index m = H.rows();
  const Eigen::Index p = H.cols();
  assert(residuals.size() == m && p >= 1);
  assert(!options.sigma || *options.sigma > 0.0);
  assert(!options.p_prime || *options.p_prime >= 1);
  if (m < p) return std::nullopt;
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(H);
  if (qr.rank() < p) return std::nullopt;

  RegressionDiagnostics out;
  // L_v = Q Q^T with Q the thin orthonormal basis of H's columns (5.11), so l_ii = ||Q_i.||^2.
  const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(m, p);
  out.leverage = Q.rowwise().squaredNorm();
  out.sigma_hat = m > p ? std::sqrt(residuals.squaredNorm() / static_cast<double>(m - p)) : kNaN;  // (5.13)
  if (!options.sigma && !(m > p)) return std::nullopt;
  out.sigma_used = options.sigma ? *options.sigma : out.sigma_hat;
  out.p_prime = options.p_prime ? *options.p_prime : static_cast<int>(p) + 1;

  out.studentized.resize(m);
  out.cooks_distance.resize(m);
  const double sigma2 = out.sigma_used * out.sigma_used;
  for (Eigen::Index i = 0; i < m; ++i) {
    const double l = out.leverage(i);
    const double e = residuals(i);
    const double one_minus_l = 1.0 - l;
    if (one_minus_l <= 1e-10) {
      out.studentized(i) = kNaN;
      out.cooks_distance(i) = kNaN;
    } else if (e == 0.0) {
      // Also covers sigma_hat = 0 (an exact fit), where the formulas would divide 0 by 0.
      out.studentized(i) = 0.0;
      out.cooks_distance(i) = 0.0;
    } else {
      out.studentized(i) = e / (out.sigma_used * std::sqrt(one_minus_l));  // (5.12)
      out.cooks_distance(i) = e * e * l / (out.p_prime * sigma2 * one_minus_l * one_minus_l);
    }
  }
  return out;
}

double RegularizedIncompleteBeta(double x, double a, double b) {
  assert(a > 0.0 && b > 0.0 && x >= 0.0 && x <= 1.0);
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  const double log_beta = std::lgamma(a) + std::lgamma(b) - std::lgamma(a + b);
  const double log_front = a * std::log(x) + b * std::log1p(-x) - log_beta;
  // Use the fraction where it converges fast, and I_x(a, b) = 1 - I_{1-x}(b, a) elsewhere.
  if (x < (a + 1.0) / (a + b + 2.0)) return std::exp(log_front) / a * BetaContinuedFraction(x, a, b);
  return 1.0 - std::exp(log_front) / b * BetaContinuedFraction(1.0 - x, b, a);
}

double FCdf(double x, double d1, double d2) {
  assert(d1 > 0.0 && d2 > 0.0);
  if (!(x > 0.0)) return 0.0;
  return RegularizedIncompleteBeta(d1 * x / (d1 * x + d2), 0.5 * d1, 0.5 * d2);
}

double FQuantile(double prob, double d1, double d2) {
  assert(prob >= 0.0 && prob < 1.0 && d1 > 0.0 && d2 > 0.0);
  if (prob == 0.0) return 0.0;
  double lo = 0.0;
  double hi = 1.0;
  while (FCdf(hi, d1, d2) < prob) {
    lo = hi;
    hi *= 2.0;
  }
  while (hi - lo > 1e-12 * hi) {
    const double mid = 0.5 * (lo + hi);
    (FCdf(mid, d1, d2) < prob ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double CookThreshold(double prob, int p_prime, int m) {
  assert(p_prime >= 1 && m > p_prime);
  return FQuantile(prob, p_prime, m - p_prime);
}

}  // namespace mirage::estimation
