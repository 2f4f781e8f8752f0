// SPDX-License-Identifier: MIT
#include "mirage/estimation/solvers/toa_nlls.h"

#include <cmath>
#include <optional>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "mirage/core/rng.h"
#include "rng_vectors.h"

namespace mirage::estimation {
namespace {

std::vector<Vec3> RandomReceivers(core::Rng& rng, int n) {
  std::vector<Vec3> out;
  for (int i = 0; i < n; ++i) out.push_back(testing::UniformVec3(rng, Vec3(0.0, 0.0, 0.3), Vec3(10.0, 8.0, 3.0)));
  return out;
}

std::vector<double> Values(const std::vector<Vec3>& receivers, const Vec3& sender, double offset) {
  std::vector<double> out;
  for (const Vec3& m : receivers) out.push_back((sender - m).norm() + offset);
  return out;
}

Vec3 RandomSender(core::Rng& rng) { return {rng.Uniform(1.0, 9.0), rng.Uniform(1.0, 7.0), rng.Uniform(0.0, 2.5)}; }

struct Case {
  RowModel model;
  int reference;
  const char* name;
};

constexpr Case kCases[] = {{RowModel::kToa, 0, "toa"},
                           {RowModel::kRange, 0, "range"},
                           {RowModel::kTdoa, 2, "tdoa ref 2"},
                           {RowModel::kTdoa, kAllPairs, "tdoa all pairs"}};

NllsProblem MakeProblem(const Case& c, const std::vector<Vec3>& receivers, const std::vector<double>& values,
                        const std::vector<double>& sigmas = {}) {
  NllsProblem problem;
  problem.model = c.model;
  problem.receivers_m = receivers;
  problem.values_m = values;
  problem.sigmas_m = sigmas;
  problem.tdoa_reference = c.reference;
  return problem;
}

// Central differences of Linearize's prediction in every state coordinate.
void ExpectJacobianMatchesCentralDifferences(const NllsProblem& problem, const Eigen::VectorXd& state,
                                             std::optional<double> known_height, double step, double tol,
                                             const std::string& what) {
  const auto lin = Linearize(problem, state, known_height);
  ASSERT_TRUE(lin) << what;
  ASSERT_EQ(lin->J_pred_state.cols(), state.size());
  for (Eigen::Index j = 0; j < state.size(); ++j) {
    Eigen::VectorXd plus = state;
    Eigen::VectorXd minus = state;
    plus(j) += step;
    minus(j) -= step;
    const Eigen::VectorXd numeric =
        (Linearize(problem, plus, known_height)->predicted_m - Linearize(problem, minus, known_height)->predicted_m) /
        (2.0 * step);
    for (Eigen::Index i = 0; i < numeric.size(); ++i) {
      EXPECT_NEAR(lin->J_pred_state(i, j), numeric(i), tol) << what << " row " << i << " column " << j;
    }
  }
}

TEST(ToaNlls, JacobiansMatchCentralDifferences) {
  for (const Case& c : kCases) {
    for (const std::optional<double> known_height : {std::optional<double>(), std::optional<double>(1.1)}) {
      for (std::uint64_t seed = 1; seed <= 10; ++seed) {
        core::Rng rng(seed);
        const auto receivers = RandomReceivers(rng, 5);
        const std::vector<double> values(receivers.size(), 0.0);
        const NllsProblem problem = MakeProblem(c, receivers, values);
        Vec3 sender = RandomSender(rng);
        if (known_height) sender.z() = *known_height;
        const Eigen::VectorXd state = PackState(c.model, sender, rng.Uniform(-5.0, 5.0), known_height);
        ExpectJacobianMatchesCentralDifferences(problem, state, known_height, 1e-6, 1e-7,
                                                std::string(c.name) + " seed " + std::to_string(seed));
      }
      // Near a receiver (1 cm): large curvature, still consistent with a smaller step.
      core::Rng rng(99);
      const auto receivers = RandomReceivers(rng, 5);
      const std::vector<double> values(receivers.size(), 0.0);
      Vec3 sender = receivers[1] + Vec3(0.006, -0.005, 0.0);
      if (known_height) sender.z() = *known_height;
      const NllsProblem problem = MakeProblem(c, receivers, values);
      if (!known_height) {
        ExpectJacobianMatchesCentralDifferences(problem, PackState(c.model, sender, 0.3, known_height), known_height,
                                                1e-7, 1e-5, std::string(c.name) + " near receiver");
        // On the receiver the direction is undefined.
        EXPECT_FALSE(Linearize(problem, PackState(c.model, receivers[1], 0.3, known_height), known_height));
      }
    }
  }
}

TEST(ToaNlls, PredictionsAreTheModelsOfTheRows) {
  const std::vector<Vec3> receivers{Vec3(0.0, 0.0, 2.0), Vec3(4.0, 0.0, 2.5), Vec3(0.0, 3.0, 1.0)};
  const std::vector<double> values(3, 0.0);
  const Vec3 s(1.0, 1.0, 1.0);
  const double r0 = (s - receivers[0]).norm();
  const double r1 = (s - receivers[1]).norm();
  const double r2 = (s - receivers[2]).norm();
  const auto toa = Linearize(MakeProblem(kCases[0], receivers, values), PackState(RowModel::kToa, s, 2.0, {}), {});
  EXPECT_NEAR(toa->predicted_m(1), r1 + 2.0, 1e-12);
  const auto tdoa = Linearize(MakeProblem(kCases[3], receivers, values), PackState(RowModel::kTdoa, s, 0.0, {}), {});
  ASSERT_EQ(tdoa->predicted_m.size(), 3);  // (0,1), (0,2), (1,2)
  EXPECT_NEAR(tdoa->predicted_m(0), r0 - r1, 1e-12);
  EXPECT_NEAR(tdoa->predicted_m(2), r1 - r2, 1e-12);
  EXPECT_EQ(TdoaPairs(4, 2), (std::vector<std::pair<int, int>>{{0, 2}, {1, 2}, {3, 2}}));
}

TEST(ToaNlls, RecoversTheSenderExactlyFromNoiseFreeRows) {
  for (const Case& c : kCases) {
    for (const NllsMethod method : {NllsMethod::kGaussNewton, NllsMethod::kLevenbergMarquardt}) {
      for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        core::Rng rng(seed, 1);
        const auto receivers = RandomReceivers(rng, 6);
        const Vec3 sender = RandomSender(rng);
        const double offset = c.model == RowModel::kRange ? 0.0 : rng.Uniform(-20.0, 20.0);
        const auto values = Values(receivers, sender, offset);
        const Vec3 start = sender + Vec3(0.5 * testing::NormalVec3(rng));
        NllsOptions options;
        options.method = method;

        const SolverFix fix = SolveNlls(MakeProblem(c, receivers, values), start, offset + 0.4, options);

        const std::string what = std::string(c.name) + " seed " + std::to_string(seed);
        ASSERT_EQ(fix.status, SolverStatus::kOk) << what;
        EXPECT_TRUE(fix.converged);
        EXPECT_LT(fix.iterations, 20) << what;
        EXPECT_LT((fix.position_m - sender).norm(), 1e-6) << what;
        EXPECT_LT(fix.rms_m, 1e-6);
        if (c.model == RowModel::kToa) {
          EXPECT_NEAR(fix.offset_m, offset, 1e-6) << what;
        }
        EXPECT_EQ(fix.offset_estimated, c.model == RowModel::kToa);
      }
    }
  }
}

TEST(ToaNlls, KnownHeightSolvesThePlaneAndLeavesZOutOfTheCovariance) {
  // Three receivers suffice for x, y, b at a known height.
  const std::vector<Vec3> receivers{Vec3(0.0, 0.0, 2.5), Vec3(6.0, 0.5, 2.5), Vec3(2.0, 5.0, 2.6)};
  const Vec3 sender(2.5, 1.5, 1.0);
  const auto rho = Values(receivers, sender, 3.0);
  const std::vector<double> sigmas(3, 0.05);
  NllsOptions options;
  options.known_height_m = 1.0;
  const SolverFix fix = SolveToaNlls(receivers, rho, sigmas, Vec3(3.0, 2.0, 7.0), 2.5, options);
  ASSERT_EQ(fix.status, SolverStatus::kOk);
  EXPECT_LT((fix.position_m - sender).norm(), 1e-6);
  EXPECT_EQ(fix.position_m.z(), 1.0);
  EXPECT_TRUE(fix.covariance_m2.row(2).isZero());
  EXPECT_TRUE(fix.covariance_m2.col(2).isZero());
  EXPECT_GT(fix.covariance_m2(3, 3), 0.0);
  EXPECT_GT(fix.covariance_m2(0, 0), 0.0);
}

TEST(ToaNlls, LevenbergMarquardtConvergesFromFarStartsWhereGaussNewtonFails) {
  // Far from the array, position along the line of sight and the offset b are nearly
  // interchangeable: GN's undamped steps overshoot along that valley; LM's damping holds them.
  int gn_ok = 0;
  int lm_ok = 0;
  constexpr int kTrials = 50;
  for (std::uint64_t seed = 1; seed <= kTrials; ++seed) {
    core::Rng rng(seed, 2);
    const auto receivers = RandomReceivers(rng, 6);
    const Vec3 sender = RandomSender(rng);
    const auto rho = Values(receivers, sender, 2.0);
    const double angle = rng.Uniform(0.0, 2.0 * M_PI);
    const Vec3 start = sender + 10.0 * Vec3(std::cos(angle), std::sin(angle), rng.Uniform(-0.3, 0.3));
    NllsOptions options;
    options.max_iterations = 100;
    options.method = NllsMethod::kGaussNewton;
    const SolverFix gn = SolveToaNlls(receivers, rho, {}, start, 0.0, options);
    options.method = NllsMethod::kLevenbergMarquardt;
    const SolverFix lm = SolveToaNlls(receivers, rho, {}, start, 0.0, options);
    gn_ok += (gn.position_m - sender).norm() < 1e-6 ? 1 : 0;
    lm_ok += (lm.position_m - sender).norm() < 1e-6 ? 1 : 0;
    if ((lm.position_m - sender).norm() < 1e-6) {
      EXPECT_TRUE(lm.converged);
    }
  }
  EXPECT_GE(lm_ok, 40) << "GN " << gn_ok;
  EXPECT_LE(gn_ok, 10) << "LM " << lm_ok;
}

// The empirical mean and covariance of (fix - truth) over draws of Gaussian noise on the
// pseudo-ranges; the returned covariance at the noise-free fix.
struct MonteCarlo {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d empirical = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d returned = Eigen::Matrix3d::Zero();
};

MonteCarlo RunMonteCarlo(const NllsProblem& base, const Vec3& sender, double offset, int draws) {
  const std::vector<double> clean = Values(std::vector<Vec3>(base.receivers_m.begin(), base.receivers_m.end()), sender,
                                           base.model == RowModel::kRange ? 0.0 : offset);
  NllsOptions options;
  MonteCarlo mc;
  {
    NllsProblem problem = base;
    problem.values_m = clean;
    mc.returned = SolveNlls(problem, sender, offset, options).covariance_m2.topLeftCorner<3, 3>();
  }
  core::Rng rng(2024, 7);
  std::vector<Eigen::Vector3d> errors;
  std::vector<double> noisy(clean.size());
  for (int k = 0; k < draws; ++k) {
    for (std::size_t i = 0; i < clean.size(); ++i) noisy[i] = clean[i] + base.sigmas_m[i] * rng.Normal();
    NllsProblem problem = base;
    problem.values_m = noisy;
    const SolverFix fix = SolveNlls(problem, sender, offset, options);
    EXPECT_EQ(fix.status, SolverStatus::kOk);
    errors.push_back(fix.position_m - sender);
    mc.mean += errors.back();
  }
  mc.mean /= draws;
  for (const auto& e : errors) mc.empirical += (e - mc.mean) * (e - mc.mean).transpose();
  mc.empirical /= draws - 1;
  return mc;
}

void ExpectCovarianceMatches(const MonteCarlo& mc, int draws, const std::string& what) {
  for (int k = 0; k < 3; ++k) {
    // Unbiased to well within the standard error (4 sigma / sqrt(draws)).
    EXPECT_LT(std::abs(mc.mean(k)), 4.0 * std::sqrt(mc.empirical(k, k) / draws)) << what << " axis " << k;
    EXPECT_NEAR(mc.empirical(k, k) / mc.returned(k, k), 1.0, 0.15) << what << " axis " << k;
  }
  EXPECT_NEAR(mc.empirical.trace() / mc.returned.trace(), 1.0, 0.15) << what;
}

const std::vector<Vec3> kLayout{Vec3(0.0, 0.0, 2.8), Vec3(8.0, 0.5, 2.2), Vec3(7.5, 6.0, 2.9),
                                Vec3(0.5, 6.5, 1.8), Vec3(4.0, 3.0, 0.4), Vec3(2.0, 1.0, 1.2)};
const std::vector<double> kSigmas{0.02, 0.03, 0.015, 0.04, 0.025, 0.02};

TEST(ToaNlls, ToaCovarianceMatchesTheMonteCarloSpread) {
  constexpr int kDraws = 2000;
  const MonteCarlo mc = RunMonteCarlo(MakeProblem(kCases[0], kLayout, {}, kSigmas), Vec3(3.0, 2.5, 1.0), 5.0, kDraws);
  ExpectCovarianceMatches(mc, kDraws, "toa");
}

TEST(ToaNlls, TdoaReferenceCovarianceMatchesTheMonteCarloSpread) {
  constexpr int kDraws = 2000;
  const MonteCarlo mc = RunMonteCarlo(MakeProblem(kCases[2], kLayout, {}, kSigmas), Vec3(3.0, 2.5, 1.0), 5.0, kDraws);
  ExpectCovarianceMatches(mc, kDraws, "tdoa ref 2");
}

TEST(ToaNlls, AllPairsWithDiagonalWeightsNeedTheSandwichCovariance) {
  // N(N-1)/2 = 15 rows carry 5 independent values. Weighted as independent, the naive
  // (H^T W H)^-1 understates the spread by about N / 2 = 3 for equal sigmas; the returned
  // sandwich covariance does not.
  constexpr int kDraws = 2000;
  const std::vector<double> sigmas(kLayout.size(), 0.03);
  NllsProblem problem = MakeProblem(kCases[3], kLayout, {}, sigmas);
  problem.tdoa_correlated_weighting = false;
  const Vec3 sender(3.0, 2.5, 1.0);
  const MonteCarlo mc = RunMonteCarlo(problem, sender, 0.0, kDraws);
  ExpectCovarianceMatches(mc, kDraws, "tdoa all pairs, diagonal weights");

  const std::vector<double> clean = Values(kLayout, sender, 0.0);
  problem.values_m = clean;
  const auto lin = Linearize(problem, PackState(RowModel::kTdoa, sender, 0.0, {}), {});
  const Eigen::MatrixXd& H = lin->J_pred_state;
  const Eigen::Matrix3d naive = (H.transpose() * H).inverse() * (2.0 * 0.03 * 0.03);  // W = I / (2 sigma^2)
  EXPECT_NEAR(mc.empirical.trace() / naive.trace(), 3.0, 0.45);
}

TEST(ToaNlls, AllPairsWithCorrelatedWeightsEqualsTheReferenceFix) {
  core::Rng rng(5);
  std::vector<double> rho = Values(kLayout, Vec3(3.0, 2.5, 1.0), 5.0);
  for (std::size_t i = 0; i < rho.size(); ++i) rho[i] += kSigmas[i] * rng.Normal();
  NllsOptions options;
  const SolverFix reference = SolveTdoaNlls(kLayout, rho, kSigmas, 4, Vec3(3.0, 3.0, 1.5), options);
  const SolverFix all = SolveTdoaNlls(kLayout, rho, kSigmas, kAllPairs, Vec3(3.0, 3.0, 1.5), options);
  ASSERT_EQ(reference.status, SolverStatus::kOk);
  ASSERT_EQ(all.status, SolverStatus::kOk);
  EXPECT_LT((reference.position_m - all.position_m).norm(), 1e-7);
  EXPECT_LT((reference.covariance_m2 - all.covariance_m2).norm(), 1e-9);
  EXPECT_NEAR(reference.dop, all.dop, 1e-9);
}

TEST(ToaNlls, DopEqualsTheAnalyticValueOfSymmetricLayouts) {
  const double a = 2.0;   // half side of the square / cube (m)
  const double dz = 2.0;  // sender depth below the square (m)
  // Ranges, square at z = 3, sender below its centre: H^T H = diag(4a^2, 4a^2, 4dz^2) / R^2.
  {
    std::vector<Vec3> square;
    for (const double sx : {-a, a}) {
      for (const double sy : {-a, a}) square.emplace_back(5.0 + sx, 5.0 + sy, 3.0);
    }
    const Vec3 sender(5.0, 5.0, 3.0 - dz);
    const double R2 = 2.0 * a * a + dz * dz;
    const double expected = std::sqrt(2.0 * R2 / (4.0 * a * a) + R2 / (4.0 * dz * dz));
    const auto ranges = Values(square, sender, 0.0);
    NllsProblem problem = MakeProblem(kCases[1], square, ranges);
    const SolverFix fix = AssessFix(problem, sender, 0.0, std::nullopt);
    ASSERT_EQ(fix.status, SolverStatus::kOk);
    EXPECT_NEAR(fix.dop, expected, 1e-12);
    // TOA on the same square: u_z is equal for all, so z and b are inseparable (Eq. 8.57-8.58).
    const auto rho = Values(square, sender, 1.0);
    problem = MakeProblem(kCases[0], square, rho);
    const SolverFix toa = AssessFix(problem, sender, 1.0, std::nullopt);
    EXPECT_EQ(toa.status, SolverStatus::kSingularNormalMatrix);
    EXPECT_TRUE(std::isinf(toa.dop));
  }
  // TOA, cube of 8 receivers (z = 1 +- h), sender at its centre: sum u = 0 and the cross terms
  // vanish, so H^T H = diag(8a^2/R^2, 8a^2/R^2, 8h^2/R^2, 8).
  {
    const double h = 1.5;
    std::vector<Vec3> cube;
    for (const double sx : {-a, a}) {
      for (const double sy : {-a, a}) {
        for (const double sz : {-h, h}) cube.emplace_back(5.0 + sx, 5.0 + sy, 1.0 + sz);
      }
    }
    const Vec3 sender(5.0, 5.0, 1.0);
    const double R2 = 2.0 * a * a + h * h;
    const double expected = std::sqrt(2.0 * R2 / (8.0 * a * a) + R2 / (8.0 * h * h));
    const auto rho = Values(cube, sender, 1.0);
    const SolverFix toa = AssessFix(MakeProblem(kCases[0], cube, rho), sender, 1.0, std::nullopt);
    ASSERT_EQ(toa.status, SolverStatus::kOk);
    EXPECT_NEAR(toa.dop, expected, 1e-12);
    // TDOA DOP = pseudo-range DOP (Shin & Sung, Eq. 8.59-8.67), for any reference and all pairs.
    for (const int reference : {0, 5, kAllPairs}) {
      const Case c{RowModel::kTdoa, reference, "tdoa"};
      const SolverFix tdoa = AssessFix(MakeProblem(c, cube, rho), sender, 0.0, std::nullopt);
      ASSERT_EQ(tdoa.status, SolverStatus::kOk);
      EXPECT_NEAR(tdoa.dop, expected, 1e-9) << "reference " << reference;
    }
  }
}

// The assessed covariance is (H^T R^-1 H)^-1 with per-row sigmas, and the DOP sqrt(trace) of the
// unit-sigma inverse's position block, for every state layout (2-4 unknowns): against Eigen's
// general inverse of the normal matrix built here from the row geometry.
TEST(ToaNlls, AssessedCovarianceIsTheInverseNormalMatrixForEveryStateSize) {
  core::Rng rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const auto receivers = RandomReceivers(rng, 7);
    const Vec3 sender = RandomSender(rng);
    std::vector<double> sigmas;
    for (int i = 0; i < 7; ++i) sigmas.push_back(rng.Uniform(0.02, 0.3));
    for (const RowModel model : {RowModel::kToa, RowModel::kRange}) {
      for (const bool known_height : {false, true}) {
        const bool with_offset = model == RowModel::kToa;
        const int position_columns = known_height ? 2 : 3;
        const int p = position_columns + (with_offset ? 1 : 0);
        Eigen::MatrixXd H(7, p);
        Eigen::VectorXd w(7);
        for (int i = 0; i < 7; ++i) {
          const Vec3 u = (sender - receivers[static_cast<std::size_t>(i)]).normalized();
          H.row(i).head(position_columns) = u.head(position_columns).transpose();
          if (with_offset) H(i, p - 1) = 1.0;
          w(i) = 1.0 / (sigmas[static_cast<std::size_t>(i)] * sigmas[static_cast<std::size_t>(i)]);
        }
        const Eigen::MatrixXd expected = (H.transpose() * w.asDiagonal() * H).inverse();
        const Eigen::MatrixXd unit = (H.transpose() * H).inverse();
        NllsProblem problem;
        problem.model = model;
        problem.receivers_m = receivers;
        const auto values = Values(receivers, sender, with_offset ? 2.0 : 0.0);
        problem.values_m = values;
        problem.sigmas_m = sigmas;
        const auto height = known_height ? std::optional<double>(sender.z()) : std::nullopt;
        const SolverFix fix = AssessFix(problem, sender, with_offset ? 2.0 : 0.0, height);
        ASSERT_EQ(fix.status, SolverStatus::kOk);
        // [x, y, z, b] slots of the state entries.
        std::vector<int> slot{0, 1};
        if (!known_height) slot.push_back(2);
        if (with_offset) slot.push_back(3);
        for (int a = 0; a < p; ++a) {
          for (int b = 0; b < p; ++b) {
            EXPECT_NEAR(fix.covariance_m2(slot[static_cast<std::size_t>(a)], slot[static_cast<std::size_t>(b)]),
                        expected(a, b), 1e-9 * expected.norm())
                << "trial " << trial << " p " << p << " entry " << a << "," << b;
          }
        }
        EXPECT_NEAR(fix.dop, std::sqrt(unit.topLeftCorner(position_columns, position_columns).trace()), 1e-9)
            << "trial " << trial << " p " << p;
      }
    }
  }
}

TEST(ToaNlls, FlagsTooFewRowsAndDegenerateStarts) {
  const std::vector<Vec3> three{Vec3(0.0, 0.0, 2.5), Vec3(6.0, 0.5, 2.0), Vec3(2.0, 5.0, 1.0)};
  const auto rho = Values(three, Vec3(2.0, 2.0, 1.0), 1.0);
  const NllsOptions options;
  const SolverFix toa = SolveToaNlls(three, rho, {}, Vec3(1.0, 1.0, 1.0), 0.0, options);
  EXPECT_EQ(toa.status, SolverStatus::kTooFewRows);
  EXPECT_TRUE(toa.degenerate());
  EXPECT_EQ(SolveTdoaNlls(three, rho, {}, 0, Vec3(1.0, 1.0, 1.0), options).status, SolverStatus::kTooFewRows);
  EXPECT_EQ(SolveRangeNlls(std::span(three).first(2), std::span(rho).first(2), {}, Vec3::Zero(), options).status,
            SolverStatus::kTooFewRows);
  // Starting on a receiver: the direction, hence the Jacobian, is undefined.
  NllsOptions gn;
  gn.method = NllsMethod::kGaussNewton;
  gn.known_height_m = 2.5;
  EXPECT_EQ(SolveToaNlls(three, rho, {}, three[0], 0.0, gn).status, SolverStatus::kDegenerateGeometry);
  // Collinear receivers with a known height: x, y, b are not separable.
  const std::vector<Vec3> line{Vec3(0.0, 0.0, 2.5), Vec3(2.0, 0.0, 2.5), Vec3(4.0, 0.0, 2.5), Vec3(6.0, 0.0, 2.5)};
  gn.known_height_m = 1.0;
  const SolverFix singular =
      SolveToaNlls(line, Values(line, Vec3(3.0, 0.0, 1.0), 0.0), {}, Vec3(2.0, 0.0, 1.0), 0.0, gn);
  EXPECT_EQ(singular.status, SolverStatus::kSingularNormalMatrix);
}

TEST(ToaNlls, RejectsInvalidOptionsAndInput) {
  NllsOptions options;
  EXPECT_TRUE(Validate(options).empty());
  options.max_iterations = 0;
  options.tolerance_m = -1.0;
  options.lm_initial_lambda = 0.0;
  EXPECT_EQ(Validate(options).size(), 3u);
  const std::vector<double> rho{1.0, 2.0, 3.0, 4.0};
  EXPECT_EQ(SolveToaNlls(kLayout, rho, {}, Vec3::Zero(), 0.0, NllsOptions{}).status, SolverStatus::kInvalidInput);
  const std::vector<double> rho6(6, 5.0);
  const std::vector<double> bad_sigmas{0.1, 0.1, 0.0, 0.1, 0.1, 0.1};
  EXPECT_EQ(SolveToaNlls(kLayout, rho6, bad_sigmas, Vec3::Zero(), 0.0, NllsOptions{}).status,
            SolverStatus::kInvalidInput);
  EXPECT_EQ(SolveTdoaNlls(kLayout, rho6, {}, 6, Vec3::Zero(), NllsOptions{}).status, SolverStatus::kInvalidInput);
}

}  // namespace
}  // namespace mirage::estimation
