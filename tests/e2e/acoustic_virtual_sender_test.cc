// SPDX-License-Identifier: MIT
// End-to-end regression of examples/acoustic_virtual_sender.yaml (Bordoy 2020 Sec. 5.2, Fig. 5.3):
// for 3 s the walker faces the wall beside them and only its echoes arrive, which fit the sender
// mirrored 5 m behind the wall. The thesis's claim: its REKF (direct paths only) is caught with
// the IMU and not without it. Without the IMU it locks onto the virtual sender and never returns;
// with it the virtual-sender test (a confirmed track whose update breaks the dead reckoning
// coasts on it) keeps the true sender. The REKF that predicts the echoes keeps it with and
// without the IMU (the stamps fit it as the wall's echoes; the prior breaks the tie). 5 runs per
// variant with the file's seed; the hold-out file is run with default options. The plot's data
// carry one error CDF per variant.
#include <string>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "e2e/extended_example.h"
#include "e2e/find_variant.h"
#include "mirage/io/plot.h"
#include "mirage/io/scenario.h"
#include "mirage/pipeline/runner.h"
#include "mirage/pipeline/summary.h"

namespace mirage::pipeline {
namespace {

TEST(AcousticVirtualSender, CaughtWithTheImuNotWithoutAndByTheEchoModel) {
  io::ScenarioOverrides overrides;
  overrides.runs = 5;
  overrides.threads = 0;
  const io::Scenario scenario =
      io::LoadScenario(std::string(MIRAGE_SOURCE_DIR) + "/examples/acoustic_virtual_sender.yaml", overrides);
  ASSERT_EQ(scenario.variants.size(), 4u);
  const auto result = RunExperiment(scenario.variants);
  const auto summaries = Summarize(scenario.variants, result);
  for (const auto& v : summaries) {
    SCOPED_TRACE(v.name);
    if (v.name.find("echo_order=1") != std::string::npos) {
      EXPECT_LT(v.overall.error.max, 0.3);  // 5 runs, 231 emissions each, the episode included
      EXPECT_EQ(v.overall.diverged_runs, 0);
    } else if (v.name == "method.inertial=true") {
      // Direct paths only, with the IMU: caught (20 runs: largest error 0.30 m).
      EXPECT_LT(v.overall.error.max, 1.0);
      EXPECT_EQ(v.overall.diverged_runs, 0);
    } else {
      EXPECT_EQ(v.overall.diverged_runs, v.overall.runs);  // direct paths, no IMU: the virtual sender wins
    }
  }
  // The plot draws one error CDF per variant: quantiles of all its errors, the largest last.
  const nlohmann::json plot = io::PlotData(scenario, result, summaries, "");
  ASSERT_EQ(plot["variants"].size(), summaries.size());
  for (std::size_t v = 0; v < summaries.size(); ++v) {
    const auto& cdf = plot["variants"][v]["error_cdf"];
    ASSERT_FALSE(cdf.empty());
    EXPECT_LE(cdf.size(), 400u);
    for (std::size_t i = 1; i < cdf.size(); ++i) {
      EXPECT_LE(cdf[i - 1][0].get<double>(), cdf[i][0].get<double>());
      EXPECT_LT(cdf[i - 1][1].get<double>(), cdf[i][1].get<double>());
    }
    EXPECT_DOUBLE_EQ(cdf.back()[0].get<double>(), summaries[v].overall.error.max);
    EXPECT_DOUBLE_EQ(cdf.back()[1].get<double>(), 1.0);
  }
}

// examples/acoustic_virtual_sender_holdout.yaml, default options: another room, walker, chirp
// interval, noise, clutter and IMU error. On its clean channel (every path detected, no false
// alarm) the wall's echoes are every microphone's first arrival: the thesis's REKF is lost
// without the IMU, and with it too when the test is off; the test catches it. On the realistic
// channel it is caught with the IMU (there with or without the test).
TEST(AcousticVirtualSender, TheHoldOutIsCaughtWithTheImuByTheTest) {
  const auto summaries = testing::RunExtendedExample("acoustic_virtual_sender_holdout.yaml", R"(
method: {virtual_sender_false_alarm: 1.0e-3}
grid:
  - {method.inertial: [true]}
  - {measurements.detection_probability: [1.0], measurements.false_alarm_rate: [0.0],
     measurements.heavy_tail_fraction: [0.0], method.inertial: [false, true]}
  - {measurements.detection_probability: [1.0], measurements.false_alarm_rate: [0.0],
     measurements.heavy_tail_fraction: [0.0], method.inertial: [true], method.virtual_sender_false_alarm: [0]}
)",
                                                     5);
  const std::string clean =
      "measurements.detection_probability=1.0, measurements.false_alarm_rate=0.0, "
      "measurements.heavy_tail_fraction=0.0, method.inertial=";
  for (const std::string& name : {std::string("method.inertial=true"), clean + "true"}) {
    SCOPED_TRACE(name);
    const auto& v = testing::FindVariant(summaries, name);
    EXPECT_LT(v.overall.error.max, 1.0);  // 20 runs: 0.80 m (realistic), 0.36 m (clean)
    EXPECT_EQ(v.overall.diverged_runs, 0);
  }
  for (const std::string& name : {clean + "false", clean + "true, method.virtual_sender_false_alarm=0"}) {
    SCOPED_TRACE(name);
    const auto& lost = testing::FindVariant(summaries, name);
    EXPECT_EQ(lost.overall.diverged_runs, lost.overall.runs);
  }
}

}  // namespace
}  // namespace mirage::pipeline
