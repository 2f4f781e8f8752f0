// SPDX-License-Identifier: MIT
#include "core/options_descriptor_expectations.h"
#include "mirage/eval/error_stats.h"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace mirage::eval {
namespace {

constexpr double kTol = 1e-12;

// ---------------------------------------------------------------------------------------------
// Percentile (numpy.percentile, method="linear": position q/100 * (n - 1) in the sorted values)
// ---------------------------------------------------------------------------------------------

TEST(Percentile, InterpolatesLinearlyBetweenOrderStatistics) {
  // [1, 2, 3, 4]: p90 at position 0.9 * 3 = 2.7 -> 3 + 0.7 * (4 - 3) = 3.7;
  // p50 at 1.5 -> 2.5; p25 at 0.75 -> 1.75.
  const std::vector<double> v{1, 2, 3, 4};

  EXPECT_NEAR(Percentile(v, 90.0), 3.7, kTol);
  EXPECT_NEAR(Percentile(v, 50.0), 2.5, kTol);
  EXPECT_NEAR(Percentile(v, 25.0), 1.75, kTol);
}

TEST(Percentile, ReturnsTheExtremesAtZeroAndOneHundred) {
  const std::vector<double> v{3, -1, 8, 2};

  EXPECT_DOUBLE_EQ(Percentile(v, 0.0), -1.0);
  EXPECT_DOUBLE_EQ(Percentile(v, 100.0), 8.0);
}

TEST(Percentile, SortsItsInput) {
  // Unsorted [40, 10, 50, 30, 20]: p95 at 0.95 * 4 = 3.8 -> 40 + 0.8 * 10 = 48;
  // p10 at 0.4 -> 10 + 0.4 * 10 = 14.
  const std::vector<double> v{40, 10, 50, 30, 20};

  EXPECT_NEAR(Percentile(v, 95.0), 48.0, kTol);
  EXPECT_NEAR(Percentile(v, 10.0), 14.0, kTol);
}

TEST(Percentile, LandsExactlyOnAnOrderStatisticWhenThePositionIsAnInteger) {
  // Five values: p75 at 3 -> the fourth smallest.
  EXPECT_DOUBLE_EQ(Percentile({0.5, 0.1, 0.9, 0.3, 0.7}, 75.0), 0.7);
}

TEST(Percentile, OfASingleValueIsThatValue) {
  EXPECT_DOUBLE_EQ(Percentile({7.25}, 0.0), 7.25);
  EXPECT_DOUBLE_EQ(Percentile({7.25}, 63.0), 7.25);
  EXPECT_DOUBLE_EQ(Percentile({7.25}, 100.0), 7.25);
}

TEST(Percentile, InterpolatesBetweenTwoValues) {
  // [0, 10]: p33 at 0.33 -> 3.3.
  EXPECT_NEAR(Percentile({10.0, 0.0}, 33.0), 3.3, kTol);
}

// ---------------------------------------------------------------------------------------------
// ComputeErrorStats
// ---------------------------------------------------------------------------------------------

TEST(ComputeErrorStats, SummarisesAHandComputedSet) {
  // {1, 2, 3, 4, 10}: mean 20/5 = 4, rmse sqrt((1+4+9+16+100)/5) = sqrt(26), max 10,
  // p50 at 2 -> 3, p90 at 3.6 -> 4 + 0.6 * 6 = 7.6, p95 at 3.8 -> 4 + 0.8 * 6 = 8.8.
  const std::vector<double> errors{4, 1, 10, 3, 2};

  const ErrorStats s = ComputeErrorStats(errors);

  EXPECT_EQ(s.count, 5U);
  EXPECT_NEAR(s.mean, 4.0, kTol);
  EXPECT_NEAR(s.rmse, std::sqrt(26.0), kTol);
  EXPECT_DOUBLE_EQ(s.max, 10.0);
  EXPECT_NEAR(s.p50, 3.0, kTol);
  EXPECT_NEAR(s.p90, 7.6, kTol);
  EXPECT_NEAR(s.p95, 8.8, kTol);
}

TEST(ComputeErrorStats, OfAConstantErrorHasEqualMeanRmseAndPercentiles) {
  const std::vector<double> errors(17, 0.3);

  const ErrorStats s = ComputeErrorStats(errors);

  EXPECT_NEAR(s.mean, 0.3, kTol);
  EXPECT_NEAR(s.rmse, 0.3, kTol);
  EXPECT_NEAR(s.p95, 0.3, kTol);
  EXPECT_DOUBLE_EQ(s.max, 0.3);
}

TEST(ComputeErrorStats, IsAllZeroForNoErrors) {
  const ErrorStats s = ComputeErrorStats(std::vector<double>{});

  EXPECT_EQ(s.count, 0U);
  EXPECT_EQ(s.rmse, 0.0);
  EXPECT_EQ(s.mean, 0.0);
  EXPECT_EQ(s.p50, 0.0);
  EXPECT_EQ(s.p90, 0.0);
  EXPECT_EQ(s.p95, 0.0);
  EXPECT_EQ(s.max, 0.0);
}

// ---------------------------------------------------------------------------------------------
// DivergenceRule
// ---------------------------------------------------------------------------------------------

TEST(IsDiverged, AveragesOnlyTheLastTwentyPercent) {
  // 10 steps, last_fraction 0.2 -> the last 2 steps.
  const DivergenceRule rule{0.5, 0.2};
  // A large early error that recovers: last two {0.1, 0.1}, mean 0.1 <= 0.5.
  const std::vector<double> recovered{9, 9, 9, 9, 9, 9, 9, 9, 0.1, 0.1};
  // Last two {0.6, 0.6} -> 0.6 > 0.5; the last three {0, 0.6, 0.6} would average 0.4.
  const std::vector<double> drifted{0, 0, 0, 0, 0, 0, 0, 0, 0.6, 0.6};
  // Last two {0.0, 0.0}; the third-to-last 3.0 would make the last three average 1.0.
  const std::vector<double> late_spike{0, 0, 0, 0, 0, 0, 0, 3.0, 0, 0};

  EXPECT_FALSE(IsDiverged(recovered, rule));
  EXPECT_TRUE(IsDiverged(drifted, rule));
  EXPECT_FALSE(IsDiverged(late_spike, rule));
}

TEST(IsDiverged, RoundsTheTailLengthUp) {
  // 7 steps * 0.2 = 1.4 -> 2 steps.
  const DivergenceRule rule{0.5, 0.2};
  // Last two {0.2, 0.9}: 0.55 > 0.5 (three steps would give 1.1 / 3 = 0.37).
  const std::vector<double> a{0, 0, 0, 0, 0, 0.2, 0.9};
  // Last two {0.9, 0.2}: 0.55 > 0.5 (the last step alone, 0.2, would not diverge).
  const std::vector<double> b{0, 0, 0, 0, 0, 0.9, 0.2};
  // Last two {0.0, 0.8}: 0.4 (three steps {5, 0, 0.8} would give 1.93).
  const std::vector<double> c{0, 0, 0, 0, 5.0, 0.0, 0.8};

  EXPECT_TRUE(IsDiverged(a, rule));
  EXPECT_TRUE(IsDiverged(b, rule));
  EXPECT_FALSE(IsDiverged(c, rule));
}

TEST(IsDiverged, UsesOnlyTheLastStepWhenTheFractionCoversOneStep) {
  // 5 steps * 0.2 = 1 step exactly.
  const DivergenceRule rule{0.5, 0.2};

  EXPECT_TRUE(IsDiverged(std::vector<double>{0, 0, 0, 0, 0.6}, rule));
  // The last two average (0.9 + 0.2) / 2 = 0.55 > 0.5, but only the last (0.2) counts.
  EXPECT_FALSE(IsDiverged(std::vector<double>{0, 0, 0, 0.9, 0.2}, rule));
}

TEST(IsDiverged, UsesAtLeastOneStepForATinyFraction) {
  // 3 steps * 0.01 = 0.03 -> rounded up to 1.
  const DivergenceRule rule{0.5, 0.01};

  EXPECT_TRUE(IsDiverged(std::vector<double>{0, 0, 0.7}, rule));
  EXPECT_FALSE(IsDiverged(std::vector<double>{0.7, 0.7, 0.1}, rule));
  EXPECT_FALSE(IsDiverged(std::vector<double>{0.7}, DivergenceRule{1.0, 0.01}));
  EXPECT_TRUE(IsDiverged(std::vector<double>{1.5}, DivergenceRule{1.0, 0.01}));
}

TEST(IsDiverged, AveragesEveryStepForFractionOne) {
  // Mean of {0.2, 0.4, 1.2} = 0.6.
  const std::vector<double> errors{0.2, 0.4, 1.2};

  EXPECT_TRUE(IsDiverged(errors, DivergenceRule{0.59, 1.0}));
  EXPECT_FALSE(IsDiverged(errors, DivergenceRule{0.61, 1.0}));
}

TEST(IsDiverged, RequiresTheMeanToExceedTheThresholdStrictly) {
  // Last two {0.5, 0.5}: mean exactly 0.5, not > 0.5.
  const std::vector<double> errors{1, 1, 1, 1, 1, 1, 1, 1, 0.5, 0.5};

  EXPECT_FALSE(IsDiverged(errors, DivergenceRule{0.5, 0.2}));
  EXPECT_TRUE(IsDiverged(errors, DivergenceRule{0.4999, 0.2}));
}

TEST(IsDiverged, IsFalseForAnEmptyRun) {
  EXPECT_FALSE(IsDiverged(std::vector<double>{}, DivergenceRule{}));
}

TEST(IsDiverged, AveragesExactlySevenOfOneHundredStepsForSevenPercent) {
  // 0.07 * 100 is 7.000000000000001 in double precision, and ceil() of it is 8.
  // 92 zeros, the 8th-from-last step 8.0 m, the last 7 steps 0.0: the last 7 % averages 0.
  std::vector<double> errors(100, 0.0);
  errors[92] = 8.0;

  EXPECT_FALSE(IsDiverged(errors, DivergenceRule{0.5, 0.07}));
}

TEST(DivergenceRule, DescribeStatesTheFractionAndTheThreshold) {
  const std::string default_text = Describe(DivergenceRule{});
  const std::string custom_text = Describe(DivergenceRule{1.25, 0.1});

  EXPECT_NE(default_text.find("20 %"), std::string::npos) << default_text;
  EXPECT_NE(default_text.find("0.5 m"), std::string::npos) << default_text;
  EXPECT_NE(custom_text.find("10 %"), std::string::npos) << custom_text;
  EXPECT_NE(custom_text.find("1.25 m"), std::string::npos) << custom_text;
}

TEST(DivergenceRule, DescribeStatesANonIntegerPercentageWithoutRounding) {
  // last_fraction 0.125 is 12.5 %, 0.005 is 0.5 %; "{:.0f}" prints "12 %" and "0 %".
  const std::string eighth = Describe(DivergenceRule{0.5, 0.125});
  const std::string half_percent = Describe(DivergenceRule{0.5, 0.005});

  EXPECT_NE(eighth.find("12.5 %"), std::string::npos) << eighth;
  EXPECT_NE(half_percent.find("0.5 %"), std::string::npos) << half_percent;
}

TEST(DivergenceRule, DefaultsAreValid) {
  EXPECT_TRUE(Validate(DivergenceRule{}).empty());
  EXPECT_TRUE(Validate(DivergenceRule{0.1, 1.0}).empty());
}

TEST(DivergenceRule, RejectsANonPositiveOrNonFiniteThreshold) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const double bad : {0.0, -0.5, nan, inf}) {
    const auto problems = Validate(DivergenceRule{bad, 0.2});

    ASSERT_EQ(problems.size(), 1U) << bad;
    EXPECT_NE(problems[0].find("threshold_m"), std::string::npos);
  }
}

TEST(DivergenceRule, RejectsAFractionOutsideZeroToOne) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const double bad : {0.0, -0.1, 1.0001, nan}) {
    const auto problems = Validate(DivergenceRule{0.5, bad});

    ASSERT_EQ(problems.size(), 1U) << bad;
    EXPECT_NE(problems[0].find("last_fraction"), std::string::npos);
  }
}

TEST(DivergenceRule, ReportsEveryProblem) {
  EXPECT_EQ(Validate(DivergenceRule{-1.0, 2.0}).size(), 2U);
}

TEST(DivergenceRuleDescriptor, AcceptsTheDefaultsAndDescribesEveryMember) {
  test::ExpectDescribesEveryMember(DivergenceRuleDescriptor(), {"threshold_m", "last_fraction"});
}

TEST(DivergenceRule, ValidateNamesTheKeyTheValueAndTheRange) {
  EXPECT_EQ(Validate(DivergenceRule{0.5, 0.0}),
            std::vector<std::string>{"last_fraction: 0 is out of range, expected a number in [1e-09, 1]"});
}

}  // namespace
}  // namespace mirage::eval
