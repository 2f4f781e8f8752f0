// SPDX-License-Identifier: MIT
// End-to-end regression of examples/acoustic_hall.yaml (Bordoy 2020 Sec. 5.3, the synthetic
// regime: 40 % of the direct stamps delayed by 3-13 ms): the failure rates (error over 1 m or no
// fix) keep the thesis's order combinatorial ~ REKF < EKF < NLLS, NLLS at least 5 times the
// REKF; the combinatorial method's window vote fails less than half as often as the thesis's Cook
// vote at F_0.5, which leaves about one emission in five without a fix. 20 runs (7000 emissions)
// per variant with the file's seed; the 300-run table is in docs/results/acoustic.md.
#include <string>

#include <gtest/gtest.h>

#include "e2e/extended_example.h"
#include "e2e/find_variant.h"

namespace mirage::pipeline {
namespace {

TEST(AcousticHall, FailureRatesKeepTheThesisOrderAndTheWindowVoteBeatsCooks) {
  const auto summaries = testing::RunExtendedExample("acoustic_hall.yaml", R"(
grid:
  - {method.estimator: [rekf, ekf, nlls, combinatorial]}
  - {method.estimator: [combinatorial], method.los.cook_voting: [true]}
)",
                                                     20);
  const auto rate = [&](const std::string& name) {
    return testing::FindVariant(summaries, name).overall.failure_rate_1m;
  };
  const double rekf = rate("method.estimator=rekf");
  const double ekf = rate("method.estimator=ekf");
  const double nlls = rate("method.estimator=nlls");
  const double combinatorial = rate("method.estimator=combinatorial");
  const double cook = rate("method.estimator=combinatorial, method.los.cook_voting=true");
  // 300 runs: 6.07 / 29.3 / 56.9 / 8.76 %, Cook 20.9 %.
  EXPECT_LT(rekf, ekf);
  EXPECT_LT(ekf, nlls);
  EXPECT_GE(nlls, 5.0 * rekf);
  EXPECT_LT(combinatorial, 2.0 * rekf);
  EXPECT_LT(combinatorial, ekf);
  EXPECT_LT(combinatorial, 0.5 * cook);
  // The window vote's floor: 5.5 % of the emissions have fewer than four direct stamps.
  const auto& comb = testing::FindVariant(summaries, "method.estimator=combinatorial").overall;
  EXPECT_GT(comb.no_fix_steps, 0);
  EXPECT_LT(comb.no_fix_steps, 0.08 * comb.steps);
  // Its LOS labels against the simulator's (300 runs: precision 0.986, recall 0.965; Cook's vote
  // 0.993 and 0.757: it drops a LOS receiver in five).
  const auto& cook_labels =
      testing::FindVariant(summaries, "method.estimator=combinatorial, method.los.cook_voting=true").overall.los_labels;
  ASSERT_TRUE(comb.los_labels.has_value() && cook_labels.has_value());
  EXPECT_GT(comb.los_labels->Precision().value_or(0.0), 0.97);
  EXPECT_GT(comb.los_labels->Recall().value_or(0.0), 0.94);
  EXPECT_LT(cook_labels->Recall().value_or(1.0), 0.85);
  EXPECT_FALSE(testing::FindVariant(summaries, "method.estimator=rekf").overall.los_labels.has_value());
}

// Table 5.1's order (means, 2-D): REKF + IMU < REKF < EKF + IMU (300 runs: 0.059 / 0.216 /
// 0.563 m; the thesis 0.13 / 0.16 / 0.38). The virtual-sender test (acoustic_virtual_sender_test)
// costs the REKF + IMU nothing here: a track is confirmed only once its prediction explains the
// stamps, so the corrections after a poor start are taken (without that, 20 runs: 0.22 m).
TEST(AcousticHall, Table51OrderHoldsAndTheVirtualSenderTestCostsNothing) {
  const auto summaries = testing::RunExtendedExample("acoustic_hall.yaml", R"(
method: {virtual_sender_false_alarm: 1.0e-3}
grid:
  - {method.estimator: [rekf]}
  - {method.estimator: [rekf, ekf], method.inertial: [true]}
  - {method.inertial: [true], method.virtual_sender_false_alarm: [0]}
)",
                                                     20);
  const auto mean = [&](const std::string& name) {
    return testing::FindVariant(summaries, name).overall.error.mean;
  };
  const double rekf_imu = mean("method.estimator=rekf, method.inertial=true");
  const double rekf = mean("method.estimator=rekf");
  const double ekf_imu = mean("method.estimator=ekf, method.inertial=true");
  const double without_test = mean("method.inertial=true, method.virtual_sender_false_alarm=0");
  EXPECT_LT(rekf_imu, rekf);
  EXPECT_LT(rekf, ekf_imu);
  EXPECT_LE(rekf_imu, 1.05 * without_test);  // 20 runs: 0.052 against 0.056 m
}

}  // namespace
}  // namespace mirage::pipeline
