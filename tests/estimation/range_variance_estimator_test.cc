// SPDX-License-Identifier: MIT
// Online SINR and range-variance estimation per VA (Lafer 2014 Sec. 3.6, digest Sec. 2.9):
// the moment estimator of Eq. (3.26) on seeded Rician amplitudes, the CRLB variance of
// Eq. (3.28) with its clamps, the fallback rules and the sliding spatial window of Eq. (3.30).
#include "mirage/estimation/range_variance_estimator.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/options_descriptor_expectations.h"
#include "mirage/core/rng.h"

namespace mirage::estimation {
namespace {

// c / (sqrt(8) pi beta) of the T_p = 0.5 ns RC pulse: 6.3 cm (digest Sec. 2.9).
constexpr double kSigma1M = 0.063;
constexpr int kVa = 7;

double Db(double linear) { return 10.0 * std::log10(linear); }

// |a + n| with n ~ CN(0, s^2) and |a|^2 = K s^2 (s = 1).
double RicianAmplitude(core::Rng& rng, double k_factor) {
  const Complex a(std::sqrt(k_factor), 0.0);
  return std::abs(a + rng.ComplexNormal(1.0));
}

// Walks 1 m along +x in 5 cm steps starting at start_x_m (21 samples, so the window spans
// d_max = 1 m up to rounding: 20 or 21 samples, both >= N_min = 15 and >= d_min = 0.9 m) and
// returns the variance of the last step.
RangeVariance WalkOneMetre(RangeVarianceEstimator& estimator, core::Rng& rng, double k_factor, double start_x_m) {
  for (int i = 0; i <= 20; ++i) {
    estimator.AddSample(kVa, Vec2(start_x_m + 0.05 * i, 1.0), RicianAmplitude(rng, k_factor));
  }
  return estimator.Variance(kVa, true);
}

// Adds constant amplitudes along +x with the given spacing; returns the last position.
Vec2 AddConstant(RangeVarianceEstimator& estimator, int count, double spacing_m, double amplitude, double start_x_m = 0.0) {
  Vec2 p(start_x_m, 0.0);
  for (int i = 0; i < count; ++i) {
    p = Vec2(start_x_m + spacing_m * i, 0.0);
    estimator.AddSample(kVa, p, amplitude);
  }
  return p;
}

TEST(RangeVarianceEstimator, EstimatesTheRicianKFactorOfTenDecibelsFromTwentySampleWindows) {
  // Arrange: 200 independent 1 m windows (20-21 samples each) of K = |a|^2 / s^2 = 10 amplitudes.
  // A single window's estimate spreads by about 1.7 dB (sd, simulated) with a +0.2 dB small-sample
  // bias, so the mean over 200 windows has a standard error of about 0.12 dB: 1 dB is the
  // bias plus more than 6 standard errors.
  const RangeVarianceOptions options;
  core::Rng rng(2024, 1);
  std::vector<double> estimates_db;

  // Act
  for (int rep = 0; rep < 200; ++rep) {
    RangeVarianceEstimator estimator(options, kSigma1M);
    const RangeVariance v = WalkOneMetre(estimator, rng, 10.0, 0.0);
    ASSERT_TRUE(v.sinr.has_value()) << "window " << rep << " gave no estimate";
    ASSERT_GT(*v.sinr, 0.0) << "window " << rep;
    estimates_db.push_back(Db(*v.sinr));
  }

  // Assert
  double mean_db = 0.0;
  for (const double e : estimates_db) mean_db += e;
  mean_db /= static_cast<double>(estimates_db.size());
  double var_db = 0.0;
  for (const double e : estimates_db) var_db += (e - mean_db) * (e - mean_db);
  const double sd_db = std::sqrt(var_db / static_cast<double>(estimates_db.size() - 1));
  EXPECT_NEAR(mean_db, 10.0, 1.0);
  EXPECT_GT(sd_db, 0.5);  // the estimates do come from noisy windows
  EXPECT_LT(sd_db, 3.0);
}

TEST(RangeVarianceEstimator, TurnsTheSinrEstimateIntoTheCrlbVarianceOfEq328) {
  // Arrange
  const RangeVarianceOptions options;
  RangeVarianceEstimator estimator(options, kSigma1M);
  core::Rng rng(7, 0);

  // Act
  const RangeVariance v = WalkOneMetre(estimator, rng, 10.0, 0.0);
  const auto m = estimator.Moments(kVa, Vec2(1.0, 1.0));

  // Assert: Eq. (3.26) with m2 = Var[Y] of the window, then sigma_1^2 / SINR, inside
  // [min_sigma^2, 10 sigma_VA^2] at about 10 dB.
  ASSERT_TRUE(v.sinr.has_value());
  ASSERT_TRUE(m.has_value());
  EXPECT_NEAR(*v.sinr, 1.0 / (m->mean / std::sqrt(m->mean * m->mean - m->variance) - 1.0), 1e-9 * *v.sinr);
  const double expected = kSigma1M * kSigma1M / *v.sinr;
  EXPECT_GT(expected, options.min_sigma_m * options.min_sigma_m);
  EXPECT_LT(expected, options.max_variance_factor * options.default_sigma_m * options.default_sigma_m);
  EXPECT_DOUBLE_EQ(v.variance_m2, expected);
}

TEST(RangeVarianceEstimator, ClampsTheVarianceAtTheFloorForNoiselessAmplitudes) {
  // Arrange: constant amplitudes, Var[Y] = 0, SINR infinite, variance 0 before the clamp.
  const RangeVarianceOptions options;
  RangeVarianceEstimator estimator(options, kSigma1M);
  AddConstant(estimator, 21, 0.05, 0.3);

  // Act
  const RangeVariance v = estimator.Variance(kVa, true);

  // Assert
  ASSERT_TRUE(v.sinr.has_value());
  EXPECT_GT(*v.sinr, 1e6);
  EXPECT_DOUBLE_EQ(v.variance_m2, options.min_sigma_m * options.min_sigma_m);
}

TEST(RangeVarianceEstimator, ClampsTheVarianceAtTenTimesTheDefaultForAWideRangeSigma) {
  // Arrange: sigma_1 = 2 m, so sigma_1^2 / SINR ~ 0.4 m^2 at 10 dB, far above 10 * 0.07^2 =
  // 0.049 m^2 (it would take an estimate above 19 dB, 5 sd of the estimator, to stay below).
  const RangeVarianceOptions options;
  RangeVarianceEstimator estimator(options, 2.0);
  core::Rng rng(11, 0);

  // Act
  const RangeVariance v = WalkOneMetre(estimator, rng, 10.0, 0.0);

  // Assert: an estimate was made, and the clamp applied.
  ASSERT_TRUE(v.sinr.has_value());
  EXPECT_GT(4.0 / *v.sinr, options.max_variance_factor * options.default_sigma_m * options.default_sigma_m);
  EXPECT_DOUBLE_EQ(v.variance_m2, options.max_variance_factor * options.default_sigma_m * options.default_sigma_m);
}

TEST(RangeVarianceEstimator, GivesTheMaximumVarianceWhenTheSinrIsZeroOrComplex) {
  // Arrange: Y alternates 0 and 2 (amplitudes 0 and sqrt 2): m1 = 1, unbiased Var[Y] > 1 = m1^2,
  // so m1^2 - Var < 0 and Eq. (3.26) has no real solution.
  const RangeVarianceOptions options;
  RangeVarianceEstimator estimator(options, kSigma1M);
  for (int i = 0; i <= 20; ++i) estimator.AddSample(kVa, Vec2(0.05 * i, 0.0), i % 2 == 0 ? 0.0 : std::sqrt(2.0));

  // Act
  const RangeVariance v = estimator.Variance(kVa, true);

  // Assert
  ASSERT_TRUE(v.sinr.has_value());
  EXPECT_EQ(*v.sinr, 0.0);
  EXPECT_DOUBLE_EQ(v.variance_m2, options.max_variance_factor * options.default_sigma_m * options.default_sigma_m);
}

TEST(RangeVarianceEstimator, GivesRayleighAmplitudesTheMaximumVarianceOftenAndNeverAKFactorTenVa) {
  // Arrange: K = 0 (Rayleigh): Var[Y] = m1^2 in expectation, so the sample discriminant
  // m1^2 - Var is negative in about 36 % of 21-sample windows (simulated), which the rule maps to
  // sigma_VA,max^2; the others give small SINRs. K = 10 windows never reach the maximum.
  const RangeVarianceOptions options;
  const double max_variance = options.max_variance_factor * options.default_sigma_m * options.default_sigma_m;
  core::Rng rng(99, 3);
  int rayleigh_at_max = 0;
  int rician_at_max = 0;
  std::vector<double> rayleigh_variances;
  constexpr int kWindows = 200;

  // Act
  for (int rep = 0; rep < kWindows; ++rep) {
    RangeVarianceEstimator rayleigh(options, kSigma1M);
    const RangeVariance v = WalkOneMetre(rayleigh, rng, 0.0, 0.0);
    rayleigh_variances.push_back(v.variance_m2);
    if (v.variance_m2 == max_variance) ++rayleigh_at_max;
    RangeVarianceEstimator rician(options, kSigma1M);
    if (WalkOneMetre(rician, rng, 10.0, 0.0).variance_m2 == max_variance) ++rician_at_max;
  }

  // Assert: binomial(200, 0.37) has sd 6.8, so [0.2, 0.55] is more than 5 sd wide on each side.
  EXPECT_GT(rayleigh_at_max, kWindows / 5);
  EXPECT_LT(rayleigh_at_max, kWindows * 55 / 100);
  EXPECT_EQ(rician_at_max, 0);
  // Rayleigh VAs are trusted less than the default sigma_VA (median about 0.0073 m^2 > 0.0049 m^2).
  std::nth_element(rayleigh_variances.begin(), rayleigh_variances.begin() + kWindows / 2, rayleigh_variances.end());
  EXPECT_GT(rayleigh_variances[kWindows / 2], options.default_sigma_m * options.default_sigma_m);
}

TEST(RangeVarianceEstimator, UsesTheDefaultVarianceBeforeMinSamples) {
  // Arrange: 10 samples over 1 m (extent fine, count below N_min = 15).
  const RangeVarianceOptions options;
  RangeVarianceEstimator estimator(options, kSigma1M);
  AddConstant(estimator, 10, 0.1, 0.5);

  // Act
  const RangeVariance v = estimator.Variance(kVa, true);

  // Assert
  EXPECT_FALSE(v.sinr.has_value());
  EXPECT_DOUBLE_EQ(v.variance_m2, options.default_sigma_m * options.default_sigma_m);
}

TEST(RangeVarianceEstimator, UsesTheDefaultVarianceBeforeTheWindowSpansMinExtent) {
  // Arrange: 30 samples (count fine) 2 cm apart: the extent 0.58 m is below d_min = 0.9 m.
  const RangeVarianceOptions options;
  RangeVarianceEstimator estimator(options, kSigma1M);
  const Vec2 last = AddConstant(estimator, 30, 0.02, 0.5);

  // Act
  const RangeVariance v = estimator.Variance(kVa, true);

  // Assert
  EXPECT_FALSE(estimator.Moments(kVa, last).has_value());
  EXPECT_FALSE(v.sinr.has_value());
  EXPECT_DOUBLE_EQ(v.variance_m2, options.default_sigma_m * options.default_sigma_m);
}

TEST(RangeVarianceEstimator, FallsBackToTheAverageOfPreviousVariancesBeforeEnoughSamples) {
  // Arrange: two estimates for the VA, then the window is restarted far away (d_max drops the
  // old samples) with only a few samples.
  const RangeVarianceOptions options;
  RangeVarianceEstimator estimator(options, kSigma1M);
  core::Rng rng(5, 0);
  const RangeVariance first = WalkOneMetre(estimator, rng, 10.0, 0.0);
  estimator.AddSample(kVa, Vec2(1.05, 1.0), RicianAmplitude(rng, 3.0));
  const RangeVariance second = estimator.Variance(kVa, true);
  ASSERT_TRUE(first.sinr.has_value());
  ASSERT_TRUE(second.sinr.has_value());
  ASSERT_NE(first.variance_m2, second.variance_m2);
  for (int i = 0; i < 5; ++i) estimator.AddSample(kVa, Vec2(10.0 + 0.05 * i, 1.0), 1.0);

  // Act
  const RangeVariance fallback = estimator.Variance(kVa, true);

  // Assert
  EXPECT_FALSE(fallback.sinr.has_value());
  EXPECT_DOUBLE_EQ(fallback.variance_m2, 0.5 * (first.variance_m2 + second.variance_m2));
}

TEST(RangeVarianceEstimator, FallsBackToTheAverageWhenTheVaWasNotAssociatedNow) {
  // Arrange: a full window and one estimate.
  const RangeVarianceOptions options;
  RangeVarianceEstimator estimator(options, kSigma1M);
  core::Rng rng(6, 0);
  const RangeVariance estimate = WalkOneMetre(estimator, rng, 10.0, 0.0);
  ASSERT_TRUE(estimate.sinr.has_value());

  // Act: the window is still full, but the VA was not associated at this step.
  const RangeVariance not_associated = estimator.Variance(kVa, false);
  const RangeVariance again = estimator.Variance(kVa, false);

  // Assert: the previous average, and the fallback itself is not averaged in.
  EXPECT_FALSE(not_associated.sinr.has_value());
  EXPECT_DOUBLE_EQ(not_associated.variance_m2, estimate.variance_m2);
  EXPECT_DOUBLE_EQ(again.variance_m2, estimate.variance_m2);
}

TEST(RangeVarianceEstimator, FallsBackToTheDefaultForAVaNeverSeen) {
  // Arrange
  const RangeVarianceOptions options;
  RangeVarianceEstimator estimator(options, kSigma1M);

  // Act
  const RangeVariance v = estimator.Variance(42, false);

  // Assert
  EXPECT_FALSE(v.sinr.has_value());
  EXPECT_DOUBLE_EQ(v.variance_m2, options.default_sigma_m * options.default_sigma_m);
  EXPECT_DOUBLE_EQ(estimator.CurrentVariance(43), options.default_sigma_m * options.default_sigma_m);
}

TEST(RangeVarianceEstimator, ComputesTheMeanAndUnbiasedVarianceOfTheEnergies) {
  // Arrange: 16 samples 1/16 m apart (exact in binary) with Y = |alpha|^2 in {1, 4}.
  RangeVarianceOptions options;
  RangeVarianceEstimator estimator(options, kSigma1M);
  std::vector<double> y;
  for (int i = 0; i <= 15; ++i) {
    const double amplitude = i % 4 == 0 ? 2.0 : 1.0;
    estimator.AddSample(kVa, Vec2(i / 16.0, 0.0), amplitude);
    y.push_back(amplitude * amplitude);
  }
  double mean = 0.0;
  for (const double v : y) mean += v;
  mean /= static_cast<double>(y.size());
  double variance = 0.0;
  for (const double v : y) variance += (v - mean) * (v - mean);
  variance /= static_cast<double>(y.size() - 1);

  // Act: extent 15/16 m >= d_min, 16 samples >= N_min.
  const auto moments = estimator.Moments(kVa, Vec2(15.0 / 16.0, 0.0));

  // Assert
  ASSERT_TRUE(moments.has_value());
  EXPECT_EQ(moments->count, 16);
  EXPECT_DOUBLE_EQ(moments->mean, mean);
  EXPECT_DOUBLE_EQ(moments->variance, variance);
}

TEST(RangeVarianceEstimator, DropsSamplesFartherThanMaxExtentFromTheNewest) {
  // Arrange: 49 samples 1/16 m apart along 3 m; d_max = 1 m keeps the newest 17 (0 .. 16/16 m).
  const RangeVarianceOptions options;
  RangeVarianceEstimator estimator(options, kSigma1M);
  for (int i = 0; i <= 48; ++i) estimator.AddSample(kVa, Vec2(i / 16.0, 0.0), 1.0);

  // Act
  const auto at_end = estimator.Moments(kVa, Vec2(3.0, 0.0));
  const auto at_start = estimator.Moments(kVa, Vec2(0.0, 0.0));

  // Assert: at the start there would be 17 samples within 1 m had they been kept.
  ASSERT_TRUE(at_end.has_value());
  EXPECT_EQ(at_end->count, 17);
  EXPECT_FALSE(at_start.has_value());
}

TEST(RangeVarianceEstimator, LetsTheWindowExpireWhenTheAgentMovesAway) {
  // Arrange: a full window over x in [0, 1] m.
  const RangeVarianceOptions options;
  RangeVarianceEstimator estimator(options, kSigma1M);
  for (int i = 0; i <= 16; ++i) estimator.AddSample(kVa, Vec2(i / 16.0, 0.0), 1.0);

  // Act
  const auto here = estimator.Moments(kVa, Vec2(1.0, 0.0));
  const auto half_a_metre_on = estimator.Moments(kVa, Vec2(1.5, 0.0));
  const auto beside = estimator.Moments(kVa, Vec2(0.5, 2.0));

  // Assert: 0.5 m on only 9 samples lie within d_max; 2 m beside none.
  ASSERT_TRUE(here.has_value());
  EXPECT_EQ(here->count, 17);
  EXPECT_FALSE(half_a_metre_on.has_value());
  EXPECT_FALSE(beside.has_value());
}

TEST(RangeVarianceEstimator, ReportsTheAverageOfRecordedVariancesAsCurrentVarianceWithoutRecording) {
  // Arrange
  const RangeVarianceOptions options;
  RangeVarianceEstimator estimator(options, kSigma1M);
  core::Rng rng(8, 0);
  const RangeVariance first = WalkOneMetre(estimator, rng, 10.0, 0.0);
  const RangeVariance second = WalkOneMetre(estimator, rng, 10.0, 1.05);
  ASSERT_TRUE(first.sinr.has_value());
  ASSERT_TRUE(second.sinr.has_value());
  const double average = 0.5 * (first.variance_m2 + second.variance_m2);

  // Act
  const double current = estimator.CurrentVariance(kVa);
  const double current_again = estimator.CurrentVariance(kVa);
  estimator.Reset();
  const double after_reset = estimator.CurrentVariance(kVa);

  // Assert
  EXPECT_DOUBLE_EQ(current, average);
  EXPECT_DOUBLE_EQ(current_again, average);
  EXPECT_DOUBLE_EQ(after_reset, options.default_sigma_m * options.default_sigma_m);
}

TEST(RangeVarianceEstimator, KeepsTheVariancesOfDifferentVasApart) {
  // Arrange: VA 1 gets constant amplitudes (floor), VA 2 alternating ones (maximum).
  const RangeVarianceOptions options;
  RangeVarianceEstimator estimator(options, kSigma1M);
  for (int i = 0; i <= 20; ++i) {
    estimator.AddSample(1, Vec2(0.05 * i, 0.0), 1.0);
    estimator.AddSample(2, Vec2(0.05 * i, 0.0), i % 2 == 0 ? 0.0 : std::sqrt(2.0));
  }

  // Act
  const RangeVariance one = estimator.Variance(1, true);
  const RangeVariance two = estimator.Variance(2, true);

  // Assert
  EXPECT_DOUBLE_EQ(one.variance_m2, options.min_sigma_m * options.min_sigma_m);
  EXPECT_DOUBLE_EQ(two.variance_m2, options.max_variance_factor * options.default_sigma_m * options.default_sigma_m);
}

bool Mentions(const std::vector<std::string>& problems, const std::string& key) {
  return std::any_of(problems.begin(), problems.end(), [&](const std::string& p) { return p.find(key) != std::string::npos; });
}

TEST(RangeVarianceOptions, AcceptsTheDefaults) { EXPECT_TRUE(Validate(RangeVarianceOptions{}).empty()); }

TEST(RangeVarianceOptions, NamesEveryInvalidField) {
  const auto with = [](auto change) {
    RangeVarianceOptions o;
    change(o);
    return Validate(o);
  };
  EXPECT_TRUE(Mentions(with([](auto& o) { o.window_min_m = 0.0; }), "window_min_m"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.window_min_m = std::nan(""); }), "window_min_m"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.window_max_m = 0.5; }), "window_max_m"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.min_samples = 2; }), "min_samples"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.default_sigma_m = -0.07; }), "default_sigma_m"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.max_variance_factor = 0.5; }), "max_variance_factor"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.min_sigma_m = 0.0; }), "min_sigma_m"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.min_sigma_m = 0.08; }), "min_sigma_m"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.overlap_distance_m = -1.0; }), "overlap_distance_m"));
  EXPECT_EQ(with([](auto& o) { o.window_max_m = 0.5; }).size(), 1u);
}

TEST(RangeVarianceOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMember) {
  test::ExpectDescribesEveryMember(RangeVarianceOptionsDescriptor(),
                                   {"enabled", "window_min_m", "window_max_m", "min_samples", "default_sigma_m",
                                    "max_variance_factor", "min_sigma_m", "overlap_distance_m"});
}

TEST(RangeVarianceOptions, NamesBothFieldsOfAFailedCrossCheck) {
  RangeVarianceOptions o;
  o.window_max_m = 0.5;
  o.min_sigma_m = 0.08;

  EXPECT_EQ(Validate(o), (std::vector<std::string>{"window_max_m: 0.5 m must be >= window_min_m (0.9 m)",
                                                   "min_sigma_m: 0.08 m must be <= default_sigma_m (0.07 m)"}));
}

}  // namespace
}  // namespace mirage::estimation
