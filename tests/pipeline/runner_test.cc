// SPDX-License-Identifier: MIT
// The runner on single-agent methods (the seminar-room examples cut short): run offsets on the
// 5 x 5 grid, independence of the thread count, dependence on the seed, the layout of the
// result, the perturbed start drawn with the method's own sigma, per-anchor noise streams, the
// same path truth for CIR and range-level runs, and a short seeded regression.
#include "mirage/pipeline/runner.h"

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/geometry/trajectory.h"
#include "mirage/pipeline/anchor_channel_source.h"
#include "mirage/pipeline/summary.h"
#include "pipeline/short_seminar_room.h"

namespace mirage::pipeline {
namespace {

using testing::ShortExample;
using testing::ShortSeminarRoom;

void ExpectVecNear(const Vec2& actual, const Vec2& expected, double tol) {
  EXPECT_NEAR(actual.x(), expected.x(), tol);
  EXPECT_NEAR(actual.y(), expected.y(), tol);
}

ExperimentResult RunAll(const io::Scenario& scenario, const Progress& progress = {}) {
  return RunExperiment(scenario.variants, progress);
}

const Experiment& ExperimentOf(io::Scenario& scenario) { return scenario.variants.front().experiment; }
Experiment& MutableExperiment(io::Scenario& scenario) { return scenario.variants.front().experiment; }

TEST(RunOffset, CentresTheFiveByFiveCentimetreGridOnTheTrajectory) {
  // Lafer 2014 Sec. 3.7: 5 x 5 points 1 cm apart; run i uses point i, x fastest.
  const RunGrid grid;
  ExpectVecNear(RunOffset(grid, 0), Vec2(-0.02, -0.02), 1e-12);
  ExpectVecNear(RunOffset(grid, 1), Vec2(-0.01, -0.02), 1e-12);
  ExpectVecNear(RunOffset(grid, 4), Vec2(0.02, -0.02), 1e-12);
  ExpectVecNear(RunOffset(grid, 5), Vec2(-0.02, -0.01), 1e-12);
  ExpectVecNear(RunOffset(grid, 12), Vec2(0.0, 0.0), 1e-12);
  ExpectVecNear(RunOffset(grid, 24), Vec2(0.02, 0.02), 1e-12);
}

TEST(RunOffset, WrapsAroundAfterTheLastGridPointAndHandlesOtherGrids) {
  const RunGrid grid;
  ExpectVecNear(RunOffset(grid, 25), RunOffset(grid, 0), 1e-15);
  ExpectVecNear(RunOffset(grid, 37), RunOffset(grid, 12), 1e-15);
  const RunGrid small{3, 2, 0.02};
  ExpectVecNear(RunOffset(small, 0), Vec2(-0.02, -0.01), 1e-12);
  ExpectVecNear(RunOffset(small, 5), Vec2(0.02, 0.01), 1e-12);
  ExpectVecNear(RunOffset(RunGrid{1, 1, 0.5}, 3), Vec2(0.0, 0.0), 1e-15);
}

TEST(RunExperiment, GivesIdenticalResultsOnOneAndTwoThreads) {
  // 2 runs per trajectory, 4 runs plus 2 bound jobs, so two threads really interleave.
  const auto a = RunAll(ShortSeminarRoom(2, 1.5, 1));
  const auto b = RunAll(ShortSeminarRoom(2, 1.5, 2));

  ASSERT_EQ(a.runs.size(), b.runs.size());
  for (std::size_t r = 0; r < a.runs.size(); ++r) {
    const auto& ta = a.runs[r].agents.front().steps;
    const auto& tb = b.runs[r].agents.front().steps;
    ASSERT_EQ(ta.size(), tb.size()) << "run " << r;
    EXPECT_EQ(a.runs[r].group, b.runs[r].group);
    EXPECT_EQ(a.runs[r].run, b.runs[r].run);
    for (std::size_t k = 0; k < ta.size(); ++k) {
      EXPECT_EQ(ta[k].estimate_m, tb[k].estimate_m) << "run " << r << " step " << k;
      EXPECT_EQ(ta[k].covariance_m2, tb[k].covariance_m2) << "run " << r << " step " << k;
      EXPECT_EQ(ta[k].associations, tb[k].associations) << "run " << r << " step " << k;
    }
    ASSERT_EQ(a.runs[r].paths.size(), b.runs[r].paths.size()) << "run " << r;
    for (std::size_t i = 0; i < a.runs[r].paths.size(); ++i) {
      EXPECT_EQ(a.runs[r].paths[i].amplitude, b.runs[r].paths[i].amplitude);
      EXPECT_EQ(a.runs[r].paths[i].estimated_sinr_db, b.runs[r].paths[i].estimated_sinr_db);
    }
  }
}

TEST(RunExperiment, DependsOnTheSeed) {
  // The determinism test above must not pass because nothing is random.
  auto first = ShortSeminarRoom(1, 1.0);
  auto second = ShortSeminarRoom(1, 1.0);
  MutableExperiment(second).seed = ExperimentOf(first).seed + 1;

  const auto a = RunAll(first);
  const auto b = RunAll(second);

  ASSERT_FALSE(a.runs.empty());
  EXPECT_NE(a.runs[0].agents.front().steps.back().estimate_m, b.runs[0].agents.front().steps.back().estimate_m);
}

TEST(RunExperiment, OrdersRunsByTrajectoryThenRunWithTheirGridOffsetsAndReportsProgress) {
  auto scenario = ShortSeminarRoom(3, 0.5);
  const Experiment& e = ExperimentOf(scenario);
  int progress_calls = 0, last_total = 0;

  const auto result = RunAll(scenario, [&](int, int total) {
    ++progress_calls;
    last_total = total;
  });

  ASSERT_EQ(result.runs.size(), 6u);
  EXPECT_EQ(last_total, 8);  // 6 runs and one bound job per trajectory
  EXPECT_EQ(progress_calls, 8);
  EXPECT_GT(result.variants.front().channel_vas.size(), 2);
  EXPECT_EQ(result.variants.front().bound, "snapshot");
  for (std::size_t i = 0; i < result.runs.size(); ++i) {
    const auto& run = result.runs[i];
    EXPECT_EQ(run.group, static_cast<int>(i) / 3);
    EXPECT_EQ(run.run, static_cast<int>(i) % 3);
    ExpectVecNear(run.offset_m, RunOffset(e.run_grid, run.run), 1e-15);
    const auto& spec = e.trajectories[static_cast<std::size_t>(run.group)];
    const auto samples = geometry::SampleTrajectory(spec.waypoints_m, spec.speed_mps, spec.dt_s, run.offset_m);
    const auto& steps = run.agents.front().steps;
    ASSERT_EQ(steps.size(), samples.size());
    ExpectVecNear(steps.front().truth_m->head<2>(), spec.waypoints_m.front() + run.offset_m, 1e-12);
    for (const auto& s : steps) {
      ASSERT_TRUE(s.truth_m && s.error_m);  // simulations always have the truth
      EXPECT_NEAR(*s.error_m, (s.estimate_m - *s.truth_m).head<2>().norm(), 1e-12);
      EXPECT_TRUE(s.bound_m.has_value());
    }
  }
}

TEST(RunExperiment, TracksTheShortSeminarRoomWithinTenCentimetresAtP90) {
  // 1 run per trajectory, the first 2 m (40 steps) of each; seed from the file. The full example
  // reaches about 3 cm (README).
  auto scenario = ShortSeminarRoom(1, 2.0);
  const auto result = RunAll(scenario);
  const auto summary = Summarize(scenario.variants, result);

  const auto& overall = summary.front().overall;
  std::printf("short seminar room: p90 %.4f m, rmse %.4f m, %d steps, %.3f s\n", overall.error.p90, overall.error.rmse,
              overall.steps, result.wall_s);
  EXPECT_GE(overall.steps, 2 * 40);
  EXPECT_LE(overall.steps, 2 * 41);
  EXPECT_LT(overall.error.p90, 0.1);
  EXPECT_EQ(overall.diverged_runs, 0);
  EXPECT_EQ(overall.health.drifted_runs, 0);
}

TEST(RunExperiment, StartsAtAPerturbedPositionWhenAsked) {
  auto exact = ShortSeminarRoom(1, 0.5);
  auto perturbed = ShortSeminarRoom(1, 0.5);
  MutableExperiment(perturbed).perturb_initial_position = true;

  const auto a = RunAll(exact);
  const auto b = RunAll(perturbed);

  // The first estimate is the start after one update; a draw with sigma_i = 10 cm moves it.
  EXPECT_NE(a.runs[0].agents.front().steps.front().estimate_m, b.runs[0].agents.front().steps.front().estimate_m);
}

TEST(RunExperiment, DrawsAPerturbedStartWithTheMethodsOwnInitialSigma) {
  // SLAM with a 0.1 mm start sigma (the file's method section): a start drawn with another sigma
  // (MINT's 10 cm once was) would be decimetres off, and a tracker that trusts its start to 0.1 mm
  // keeps it there.
  const std::string path = ::testing::TempDir() + "/slam_tight_start.yaml";
  {
    std::ofstream file(path);
    file << "extends: " << testing::ExamplePath("seminar_room_slam.yaml") << "\n"
         << "perturb_initial_position: true\n"
         << "method: {initial_position_sigma_m: 0.0001}\n";
  }
  io::ScenarioOverrides overrides;
  overrides.runs = 2;
  auto scenario = io::LoadScenario(path, overrides);
  for (auto& t : MutableExperiment(scenario).trajectories) t.waypoints_m = testing::TruncatePolyline(t.waypoints_m, 0.5);
  EXPECT_DOUBLE_EQ(ExperimentOf(scenario).method.start_sigma_m, 1e-4);

  const auto result = RunAll(scenario);

  for (const auto& run : result.runs) {
    EXPECT_LT(*run.agents.front().steps.front().error_m, 0.01) << "trajectory " << run.group << " run " << run.run;
  }
}

// The range sets of the first anchors at every epoch of run 0 of trajectory 0.
std::vector<std::vector<core::RangeSet>> Measure(const Experiment& e) {
  const AnchorChannelContext context(e);
  AnchorChannelSource source(context, 0, 0);
  std::vector<std::vector<core::RangeSet>> out;
  while (auto step = source.Next()) out.push_back(step->epoch.range_sets);
  return out;
}

void ExpectAddingAnAnchorKeepsTheOthersMeasurements(MeasurementModel model) {
  // The seminar room, and the same room with a third anchor in the middle.
  auto two = ShortSeminarRoom(1, 1.0);
  MutableExperiment(two).measurement_model = model;
  auto three = two;
  MutableExperiment(three).anchors.push_back({"A3", Vec3(3.0, 4.0, 0.0)});

  const auto a = Measure(ExperimentOf(two));
  const auto b = Measure(ExperimentOf(three));

  ASSERT_EQ(a.size(), b.size());
  std::size_t compared = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(b[k].size(), 3u);
    for (std::size_t anchor = 0; anchor < 2; ++anchor) {
      const auto& ra = a[k][anchor].ranges;
      const auto& rb = b[k][anchor].ranges;
      ASSERT_EQ(ra.size(), rb.size()) << "step " << k << " anchor " << anchor;
      for (std::size_t i = 0; i < ra.size(); ++i) {
        EXPECT_EQ(ra[i].range_m, rb[i].range_m) << "step " << k << " anchor " << anchor;
        EXPECT_EQ(ra[i].amplitude, rb[i].amplitude) << "step " << k << " anchor " << anchor;
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 100u);
}

TEST(AnchorChannelSource, RangeLevelNoiseOfOneAnchorDoesNotDependOnTheOtherAnchors) {
  ExpectAddingAnAnchorKeepsTheOthersMeasurements(MeasurementModel::kRangeLevel);
}

TEST(AnchorChannelSource, CirNoiseOfOneAnchorDoesNotDependOnTheOtherAnchors) {
  ExpectAddingAnAnchorKeepsTheOthersMeasurements(MeasurementModel::kCir);
}

TEST(AnchorChannelSource, StampsEveryRangeSetWithItsTimeAndAnchorId) {
  const auto scenario = ShortSeminarRoom(1, 0.3);
  const auto sets = Measure(scenario.variants.front().experiment);
  ASSERT_GT(sets.size(), 2u);
  EXPECT_DOUBLE_EQ(sets[2][1].t_s, 0.2);
  EXPECT_EQ(sets[2][1].anchor_id, "A2");
  EXPECT_EQ(sets[2][1].anchor_index, 1);
}

TEST(RunExperiment, RangeLevelRunsRecordTheSamePathTruthAndBoundAsCirRuns) {
  // Both models see the same specular paths in the same window with the same true SINR (Lafer Eq.
  // 3.25), so every epoch's path records and PEB must agree; only the measurements differ.
  auto cir = ShortSeminarRoom(1, 1.0);
  auto ranges = ShortSeminarRoom(1, 1.0);
  MutableExperiment(ranges).measurement_model = MeasurementModel::kRangeLevel;

  const auto a = RunAll(cir);
  const auto b = RunAll(ranges);

  ASSERT_EQ(a.runs.size(), b.runs.size());
  for (std::size_t r = 0; r < a.runs.size(); ++r) {
    ASSERT_EQ(a.runs[r].paths.size(), b.runs[r].paths.size()) << "run " << r;
    for (std::size_t i = 0; i < a.runs[r].paths.size(); ++i) {
      EXPECT_EQ(a.runs[r].paths[i].step, b.runs[r].paths[i].step);
      EXPECT_EQ(a.runs[r].paths[i].va_id, b.runs[r].paths[i].va_id);
      EXPECT_DOUBLE_EQ(a.runs[r].paths[i].true_sinr_db, b.runs[r].paths[i].true_sinr_db);
    }
    const auto& sa = a.runs[r].agents.front().steps;
    const auto& sb = b.runs[r].agents.front().steps;
    for (std::size_t k = 0; k < sa.size(); ++k) {
      ASSERT_EQ(sa[k].bound_m.has_value(), sb[k].bound_m.has_value());
      if (sa[k].bound_m) {
        EXPECT_DOUBLE_EQ(*sa[k].bound_m, *sb[k].bound_m);
      }
    }
  }
}

}  // namespace
}  // namespace mirage::pipeline
