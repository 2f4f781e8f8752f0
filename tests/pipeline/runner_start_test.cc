// SPDX-License-Identifier: MIT
// How the runner starts an estimator: from the truth, or from the data (self_start, and every
// run without truth or start point), and what it reports for a run that never starts.
#include <gtest/gtest.h>

#include "mirage/pipeline/runner.h"
#include "mirage/pipeline/summary.h"
#include "pipeline/short_seminar_room.h"

namespace mirage::pipeline {
namespace {

using testing::ShortExample;
using testing::ShortSeminarRoom;

TEST(RunExperiment, SelfStartedRunsBeginAfterTheirStartingEpochsAndTrackWithErrors) {
  auto truth_start = ShortSeminarRoom(2);
  auto self_start = ShortSeminarRoom(2);
  self_start.variants.front().experiment.self_start = true;

  const auto given = RunExperiment(truth_start.variants, {});
  const auto own = RunExperiment(self_start.variants, {});

  for (std::size_t r = 0; r < own.runs.size(); ++r) {
    const RunHealth& h = own.runs[r].health;
    EXPECT_TRUE(h.started);
    // MINT's search needs a second epoch to confirm the first.
    EXPECT_GE(h.epochs_before_start, 2);
    EXPECT_EQ(own.runs[r].agents.front().steps.size() + static_cast<std::size_t>(h.epochs_before_start),
              given.runs[r].agents.front().steps.size());
    EXPECT_EQ(given.runs[r].health.epochs_before_start, 0);
  }
  const auto summary = Summarize(self_start.variants, own).front().overall;
  EXPECT_LT(summary.error.p90, 0.1);
  EXPECT_EQ(summary.diverged_runs, 0);
}

TEST(RunExperiment, ARunThatNeverStartsIsUnhealthyAndCountsAsDiverged) {
  // SLAM from two anchors with the floor plan removed: the crossings of the two range circles
  // cannot be told apart, so no epoch gives a start.
  auto scenario = ShortExample("seminar_room_slam.yaml", 1);
  Experiment& e = scenario.variants.front().experiment;
  e.self_start = true;
  e.plan = geometry::FloorPlan();
  e.in_plan.clear();
  e.measurement_model = MeasurementModel::kRanging;

  const auto result = RunExperiment(scenario.variants, {});

  for (const auto& run : result.runs) {
    EXPECT_FALSE(run.health.started);
    EXPECT_TRUE(run.health.drifted);
    EXPECT_NE(run.health.drift_reason.find("never started"), std::string::npos) << run.health.drift_reason;
    EXPECT_TRUE(run.agents.front().steps.empty());
    EXPECT_TRUE(run.agents.front().diverged);
  }
  const auto summary = Summarize(scenario.variants, result).front().overall;
  EXPECT_EQ(summary.diverged_runs, static_cast<int>(result.runs.size()));
  EXPECT_EQ(summary.health.drifted_runs, static_cast<int>(result.runs.size()));
}

}  // namespace
}  // namespace mirage::pipeline
