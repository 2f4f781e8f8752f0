// SPDX-License-Identifier: MIT
// Regression diagnostics (Bordoy Eq. 5.11-5.15): Cook's distance against its definition by
// deleting each row, leverages against the explicit hat matrix, studentized residuals with unit
// variance, a planted outlier, degenerate fits, and the F distribution against closed forms,
// tables and numerical integration.
#include "mirage/estimation/robust/regression_diagnostics.h"

#include <cmath>
#include <numbers>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "mirage/core/rng.h"

namespace mirage::estimation {
namespace {

Eigen::MatrixXd RandomMatrix(int rows, int cols, core::Rng& rng) {
  Eigen::MatrixXd A(rows, cols);
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) A(i, j) = rng.Normal();
  }
  return A;
}

Eigen::VectorXd LeastSquares(const Eigen::MatrixXd& H, const Eigen::VectorXd& z) {
  return (H.transpose() * H).ldlt().solve(H.transpose() * z);
}

Eigen::MatrixXd WithoutRow(const Eigen::MatrixXd& A, int row) {
  Eigen::MatrixXd out(A.rows() - 1, A.cols());
  out << A.topRows(row), A.bottomRows(A.rows() - row - 1);
  return out;
}

// A 12-row, 3-parameter problem with noise 0.1 and a few high-leverage rows.
struct Problem {
  Eigen::MatrixXd H;
  Eigen::VectorXd z;
  Eigen::VectorXd x;
  Eigen::VectorXd e;  // z - H x
};

Problem MakeProblem(core::Rng& rng, int m = 12, int p = 3, bool high_leverage_row = true) {
  Problem out;
  out.H = RandomMatrix(m, p, rng);
  if (high_leverage_row) out.H.row(2) *= 4.0;
  const Eigen::VectorXd truth = RandomMatrix(p, 1, rng);
  out.z = out.H * truth + 0.1 * RandomMatrix(m, 1, rng);
  out.x = LeastSquares(out.H, out.z);
  out.e = out.z - out.H * out.x;
  return out;
}

TEST(DiagnoseRegression, CooksDistanceEqualsTheDeletionDefinition) {
  core::Rng rng(1);
  const Problem pr = MakeProblem(rng);
  const Eigen::MatrixXd G = pr.H.transpose() * pr.H;
  for (const std::optional<double> sigma : {std::optional<double>{}, std::optional<double>{0.1}}) {
    const auto diag = DiagnoseRegression(pr.H, pr.e, {.sigma = sigma});
    ASSERT_TRUE(diag.has_value());
    EXPECT_EQ(diag->p_prime, 4);  // p + 1
    for (int i = 0; i < pr.H.rows(); ++i) {
      const Eigen::VectorXd x_minus_i = LeastSquares(WithoutRow(pr.H, i), WithoutRow(pr.z, i));
      const Eigen::VectorXd dx = pr.x - x_minus_i;
      const double s2 = diag->sigma_used * diag->sigma_used;
      const double definition = dx.dot(G * dx) / (diag->p_prime * s2);
      EXPECT_NEAR(diag->cooks_distance(i), definition, 1e-9 * definition) << "row " << i;
    }
  }
}

TEST(DiagnoseRegression, UsesTheGivenNormalisation) {
  core::Rng rng(2);
  const Problem pr = MakeProblem(rng);
  const auto thesis = DiagnoseRegression(pr.H, pr.e);
  const auto textbook = DiagnoseRegression(pr.H, pr.e, {.p_prime = 3});
  ASSERT_TRUE(thesis && textbook);
  EXPECT_EQ(textbook->p_prime, 3);
  EXPECT_LT((textbook->cooks_distance * 3.0 - thesis->cooks_distance * 4.0).cwiseAbs().maxCoeff(), 1e-12);
  // sigma_hat of Eq. (5.13).
  EXPECT_NEAR(thesis->sigma_hat, std::sqrt(pr.e.squaredNorm() / 9.0), 1e-15);
  EXPECT_EQ(thesis->sigma_used, thesis->sigma_hat);
}

TEST(DiagnoseRegression, LeveragesAreTheHatMatrixDiagonalAndSumToP) {
  core::Rng rng(3);
  const Problem pr = MakeProblem(rng, 9, 4);
  const auto diag = DiagnoseRegression(pr.H, pr.e);
  ASSERT_TRUE(diag.has_value());
  const Eigen::MatrixXd L = pr.H * (pr.H.transpose() * pr.H).inverse() * pr.H.transpose();  // (5.11)
  EXPECT_LT((diag->leverage - L.diagonal()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR(diag->leverage.sum(), 4.0, 1e-12);
  EXPECT_GE(diag->leverage.minCoeff(), 0.0);
  EXPECT_LE(diag->leverage.maxCoeff(), 1.0);
  // The scaled-up row has the largest leverage.
  Eigen::Index argmax = 0;
  diag->leverage.maxCoeff(&argmax);
  EXPECT_EQ(argmax, 2);
}

TEST(DiagnoseRegression, StudentizedResidualsHaveUnitVarianceWithTheTrueSigma) {
  // e_i ~ N(0, sigma^2 (1 - l_ii)), so e_i / (sigma sqrt(1 - l_ii)) has variance 1 for every row,
  // the high-leverage one included (whose raw residual is much smaller).
  core::Rng rng(4);
  Eigen::MatrixXd H = RandomMatrix(8, 3, rng);
  H.row(0) *= 5.0;
  const double sigma = 0.2;
  const int trials = 4000;
  Eigen::VectorXd sum_sq = Eigen::VectorXd::Zero(8);
  Eigen::VectorXd raw_sq = Eigen::VectorXd::Zero(8);
  for (int t = 0; t < trials; ++t) {
    const Eigen::VectorXd z = sigma * RandomMatrix(8, 1, rng);
    const Eigen::VectorXd e = z - H * LeastSquares(H, z);
    const auto diag = DiagnoseRegression(H, e, {.sigma = sigma});
    ASSERT_TRUE(diag.has_value());
    sum_sq += diag->studentized.array().square().matrix();
    raw_sq += (e / sigma).array().square().matrix();
  }
  for (int i = 0; i < 8; ++i) EXPECT_NEAR(sum_sq(i) / trials, 1.0, 0.1) << "row " << i;
  EXPECT_LT(raw_sq(0) / trials, 0.5);  // the high-leverage row's raw residual is shrunk
}

TEST(DiagnoseRegression, APlantedOutlierHasTheLargestCooksDistance) {
  // A 2-D position and offset seen from 12 directions spread round the circle (the range
  // Jacobian [cos, sin, 1]), so every row has a leverage near p / m = 0.25. With very unequal
  // leverages D ranks influence, not guilt: an outlier on a row of leverage ~0 moves nothing, and
  // a row of leverage ~0.9 dragged towards an outlier elsewhere can show the larger D.
  core::Rng rng(5);
  const double sigma = 0.1;
  const double threshold = CookThreshold(0.5, 4, 12);
  for (int outlier = 0; outlier < 12; ++outlier) {
    Eigen::MatrixXd H(12, 3);
    for (int i = 0; i < 12; ++i) {
      const double angle_rad = 2.0 * std::numbers::pi * i / 12.0 + rng.Uniform(-0.2, 0.2);
      H.row(i) << std::cos(angle_rad), std::sin(angle_rad), 1.0;
    }
    Eigen::VectorXd z = H * Eigen::Vector3d(1.0, -2.0, 0.5) + sigma * RandomMatrix(12, 1, rng);
    z(outlier) += 20.0 * sigma;
    const Eigen::VectorXd e = z - H * LeastSquares(H, z);
    for (const std::optional<double> given : {std::optional<double>{}, std::optional<double>{sigma}}) {
      const auto diag = DiagnoseRegression(H, e, {.sigma = given});
      ASSERT_TRUE(diag.has_value());
      Eigen::Index argmax = 0;
      diag->cooks_distance.maxCoeff(&argmax);
      EXPECT_EQ(argmax, outlier);
    }
    // With the true sigma the outlier exceeds the median F threshold (sigma_hat is inflated by the
    // outlier itself, which keeps D below it at m = 12).
    EXPECT_GT(DiagnoseRegression(H, e, {.sigma = sigma})->cooks_distance(outlier), threshold);
  }
}

TEST(DiagnoseRegression, MarksARowThatAloneFixesADirectionAsUntestable) {
  // Row 3 is the only one that sees x_2: leverage 1, residual 0 by construction.
  Eigen::MatrixXd H(4, 2);
  H << 1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 1.0;
  const Eigen::Vector4d e(0.1, -0.2, 0.1, 0.0);
  const auto diag = DiagnoseRegression(H, e);
  ASSERT_TRUE(diag.has_value());
  EXPECT_NEAR(diag->leverage(3), 1.0, 1e-12);
  EXPECT_TRUE(std::isnan(diag->cooks_distance(3)));
  EXPECT_TRUE(std::isnan(diag->studentized(3)));
  EXPECT_TRUE(std::isfinite(diag->cooks_distance(0)));
}

TEST(DiagnoseRegression, GivesZeroForAnExactFit) {
  core::Rng rng(6);
  const Eigen::MatrixXd H = RandomMatrix(6, 2, rng);
  const auto diag = DiagnoseRegression(H, Eigen::VectorXd::Zero(6));
  ASSERT_TRUE(diag.has_value());
  EXPECT_EQ(diag->sigma_hat, 0.0);
  EXPECT_TRUE((diag->cooks_distance.array() == 0.0).all());
}

TEST(DiagnoseRegression, RefusesARankDeficientOrUnderdeterminedFit) {
  Eigen::MatrixXd H(4, 2);
  H << 1.0, 2.0, 2.0, 4.0, 3.0, 6.0, -1.0, -2.0;  // column 2 = 2 x column 1
  EXPECT_FALSE(DiagnoseRegression(H, Eigen::VectorXd::Zero(4)).has_value());
  const Eigen::MatrixXd square = Eigen::MatrixXd::Identity(3, 3);
  EXPECT_FALSE(DiagnoseRegression(square, Eigen::VectorXd::Zero(3)).has_value());  // no sigma_hat
  EXPECT_TRUE(DiagnoseRegression(square, Eigen::VectorXd::Zero(3), {.sigma = 1.0}).has_value());
}

// ---------------------------------------------------------------------------------------------
// Incomplete beta and the F distribution
// ---------------------------------------------------------------------------------------------

TEST(RegularizedIncompleteBeta, MatchesClosedForms) {
  for (const double x : {0.0, 0.01, 0.3, 0.5, 0.77, 0.999, 1.0}) {
    for (const double a : {0.5, 1.0, 2.5, 7.0, 40.0}) {
      EXPECT_NEAR(RegularizedIncompleteBeta(x, a, 1.0), std::pow(x, a), 1e-13);              // I_x(a, 1) = x^a
      EXPECT_NEAR(RegularizedIncompleteBeta(x, 1.0, a), 1.0 - std::pow(1.0 - x, a), 1e-13);  // I_x(1, b)
      EXPECT_NEAR(RegularizedIncompleteBeta(x, a, a) + RegularizedIncompleteBeta(1.0 - x, a, a), 1.0, 1e-13);
    }
  }
  EXPECT_NEAR(RegularizedIncompleteBeta(0.5, 3.3, 3.3), 0.5, 1e-14);
  // I_x(1/2, 1/2) = (2 / pi) asin(sqrt(x)).
  EXPECT_NEAR(RegularizedIncompleteBeta(0.2, 0.5, 0.5), 2.0 / std::numbers::pi * std::asin(std::sqrt(0.2)), 1e-13);
}

// P(F <= x) by integrating the F density with x = t^2 (smooth at 0 for d1 >= 1), Simpson's rule.
double FCdfByIntegration(double x, double d1, double d2) {
  const double log_beta = std::lgamma(0.5 * d1) + std::lgamma(0.5 * d2) - std::lgamma(0.5 * (d1 + d2));
  const auto integrand = [&](double t) {
    if (t == 0.0) return 0.0;
    const double u = t * t;
    const double log_pdf = 0.5 * (d1 * std::log(d1 * u) + d2 * std::log(d2) - (d1 + d2) * std::log(d1 * u + d2)) -
                           std::log(u) - log_beta;
    return std::exp(log_pdf) * 2.0 * t;
  };
  const int n = 20000;
  const double h = std::sqrt(x) / n;
  double sum = integrand(0.0) + integrand(std::sqrt(x));
  for (int k = 1; k < n; ++k) sum += (k % 2 == 1 ? 4.0 : 2.0) * integrand(k * h);
  return sum * h / 3.0;
}

TEST(FCdf, MatchesTheIntegralOfTheDensity) {
  for (const auto& [d1, d2, x] : {std::tuple{3.0, 6.0, 0.8858}, std::tuple{3.0, 10.0, 3.708}, std::tuple{4.0, 7.0, 2.0},
                                  std::tuple{2.0, 20.0, 0.3}, std::tuple{5.0, 1.0, 10.0}}) {
    EXPECT_NEAR(FCdf(x, d1, d2), FCdfByIntegration(x, d1, d2), 1e-8) << d1 << ", " << d2 << ", " << x;
  }
}

TEST(FQuantile, MatchesTablesAndClosedForms) {
  EXPECT_NEAR(FQuantile(0.95, 3, 10), 3.708, 1e-3);   // F table, alpha = 0.05
  EXPECT_NEAR(FQuantile(0.99, 3, 10), 6.552, 1e-3);   // F table, alpha = 0.01
  EXPECT_NEAR(FQuantile(0.95, 1, 10), 4.965, 1e-3);   // = t_{0.975}(10)^2 = 2.2281^2
  EXPECT_NEAR(FQuantile(0.5, 3, 6), 0.8858, 1e-3);
  // The median of F(3, 6) where its CDF, integrated independently, is 1/2.
  EXPECT_NEAR(FCdfByIntegration(FQuantile(0.5, 3, 6), 3, 6), 0.5, 1e-8);
  // d1 = 2: P(F <= x) = 1 - (1 + 2x / d2)^(-d2 / 2), so x_p = (d2 / 2)((1 - p)^(-2 / d2) - 1).
  for (const double d2 : {2.0, 5.0, 10.0, 30.0}) {
    for (const double p : {0.1, 0.5, 0.95, 0.999}) {
      const double exact = 0.5 * d2 * (std::pow(1.0 - p, -2.0 / d2) - 1.0);
      EXPECT_NEAR(FQuantile(p, 2.0, d2), exact, 1e-9 * exact);
    }
  }
  EXPECT_EQ(FQuantile(0.0, 3, 6), 0.0);
}

TEST(CookThreshold, IsTheFQuantileWithPPrimeAndMMinusPPrimeDegreesOfFreedom) {
  EXPECT_DOUBLE_EQ(CookThreshold(0.5, 3, 10), FQuantile(0.5, 3, 7));
  EXPECT_NEAR(CookThreshold(0.95, 3, 13), 3.708, 1e-3);
}

}  // namespace
}  // namespace mirage::estimation
