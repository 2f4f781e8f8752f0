// SPDX-License-Identifier: MIT
// End-to-end regression of the anchors-only SLAM example (examples/seminar_room_slam.yaml,
// Leitinger et al.): simulated CIRs -> MPC extraction -> SLAM with only the two anchors known,
// 5 runs per trajectory with the file's seed. Guards the issue-4 headline: p90 <= 6 cm on each
// trajectory (README, 25 runs: 3.3 / 3.9 cm) with no diverged run, and a discovered map whose
// matched VAs are within 15 cm. The bound is the target itself, not a widened one: these
// 5 runs reach 3.3 / 3.9 cm; with the thesis's promotion rule trajectory 2 reaches 6.1 cm. It
// does not guard the shadow-stretch safeguards (LOS re-acquisition, recovery: these 5 runs pass
// without them, 3.9 cm; over 25 runs of seeds 2 and 3 they save 2 and 1 runs, README) nor
// discovery.max_agent_sigma_m (the run that rule saves is seed 4's).
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "mirage/io/scenario.h"
#include "mirage/methods/slam/slam_tracker.h"
#include "mirage/pipeline/runner.h"
#include "mirage/pipeline/summary.h"

namespace mirage::pipeline {
namespace {

constexpr int kRuns = 5;
constexpr double kP90Bound_m = 0.06;           // issue 4: p90 <= 0.06 m
constexpr double kMatchedErrorBound_m = 0.15;  // issue 4: matched VAs within 0.15 m on average

TEST(SeminarRoomSlam, AnchorsOnlyTracksWithinSixCentimetresAtP90AndMapsTrueVas) {
  // Arrange
  io::ScenarioOverrides overrides;
  overrides.runs = kRuns;
  overrides.threads = 0;  // all cores; the results do not depend on it
  const io::Scenario scenario =
      io::LoadScenario(std::string(MIRAGE_SOURCE_DIR) + "/examples/seminar_room_slam.yaml", overrides);
  const Experiment& config = scenario.variants.front().experiment;
  ASSERT_EQ(config.method.name, "slam");
  const auto& slam = *static_cast<const methods::slam::SlamOptions*>(config.method.options.get());
  ASSERT_EQ(slam.prior_max_order, 0) << "the example must start from the anchors alone";

  // Act
  const auto result = RunExperiment(scenario.variants);
  const VariantSummary summary = Summarize(scenario.variants, result).front();

  // Assert
  EXPECT_EQ(summary.overall.runs, 2 * kRuns);
  for (const auto& t : summary.groups) {
    ASSERT_TRUE(t.map.has_value()) << t.name;
    const MapSummary& map = *t.map;
    std::printf("%s (seed %llu, %d runs): p90 %.4f m, diverged %d; map per run: %.1f scored, %.1f matched, "
                "%.1f false, matched error %.3f m\n",
                t.name.c_str(), static_cast<unsigned long long>(config.seed), t.runs, t.error.p90,
                t.diverged_runs, map.estimated_mean, map.matched_mean, map.false_mean,
                map.matched_error_mean_m.value_or(-1.0));
    EXPECT_LE(t.error.p90, kP90Bound_m) << t.name;
    EXPECT_EQ(t.diverged_runs, 0) << t.name;
    // The map: true VAs found (each run discovers 2-4), few false ones, and accurate.
    EXPECT_GE(map.matched_mean, 2.0) << t.name;
    EXPECT_LE(map.false_mean, 1.0) << t.name;
    ASSERT_TRUE(map.matched_error_mean_m.has_value()) << t.name;
    EXPECT_LE(*map.matched_error_mean_m, kMatchedErrorBound_m) << t.name;
  }
}

}  // namespace
}  // namespace mirage::pipeline
