// SPDX-License-Identifier: MIT
// The MINT Monte-Carlo driver: run offsets on the 5 x 5 grid, independence of the thread count,
// the layout of the result and a short seeded regression on the seminar-room example (its two
// trajectories cut to their first 2 m, 40 steps each).
#include "mirage/pipeline/mint_experiment.h"

#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/geometry/trajectory.h"
#include "mirage/pipeline/mint_summary.h"
#include "pipeline/short_seminar_room.h"

namespace mirage::pipeline {
namespace {

using testing::ShortSeminarRoom;

void ExpectVecNear(const Vec2& actual, const Vec2& expected, double tol) {
  EXPECT_NEAR(actual.x(), expected.x(), tol);
  EXPECT_NEAR(actual.y(), expected.y(), tol);
}

TEST(RunOffset, CentresTheFiveByFiveCentimetreGridOnTheTrajectory) {
  // Arrange: Lafer 2014 Sec. 3.7: 5 x 5 points 1 cm apart; run i uses point i, x fastest.
  const RunGrid grid;

  // Act / Assert
  ExpectVecNear(RunOffset(grid, 0), Vec2(-0.02, -0.02), 1e-12);
  ExpectVecNear(RunOffset(grid, 1), Vec2(-0.01, -0.02), 1e-12);
  ExpectVecNear(RunOffset(grid, 4), Vec2(0.02, -0.02), 1e-12);
  ExpectVecNear(RunOffset(grid, 5), Vec2(-0.02, -0.01), 1e-12);
  ExpectVecNear(RunOffset(grid, 12), Vec2(0.0, 0.0), 1e-12);
  ExpectVecNear(RunOffset(grid, 24), Vec2(0.02, 0.02), 1e-12);
}

TEST(RunOffset, WrapsAroundAfterTheLastGridPoint) {
  const RunGrid grid;
  ExpectVecNear(RunOffset(grid, 25), RunOffset(grid, 0), 1e-15);
  ExpectVecNear(RunOffset(grid, 37), RunOffset(grid, 12), 1e-15);
}

TEST(RunOffset, HandlesNonSquareAndSinglePointGrids) {
  // 3 x 2 grid, 2 cm: x in {-0.02, 0, 0.02}, y in {-0.01, 0.01}; a 1 x 1 grid is the trajectory.
  const RunGrid grid{3, 2, 0.02};
  ExpectVecNear(RunOffset(grid, 0), Vec2(-0.02, -0.01), 1e-12);
  ExpectVecNear(RunOffset(grid, 5), Vec2(0.02, 0.01), 1e-12);
  ExpectVecNear(RunOffset(RunGrid{1, 1, 0.5}, 3), Vec2(0.0, 0.0), 1e-15);
}

TEST(RunMintExperiment, GivesIdenticalResultsOnOneAndTwoThreads) {
  // Arrange: 2 runs per trajectory, 4 jobs, so two threads really interleave.
  auto one = ShortSeminarRoom(2, 1.5, 1);
  auto two = ShortSeminarRoom(2, 1.5, 2);

  // Act
  const auto a = RunMintExperiment(one.mint);
  const auto b = RunMintExperiment(two.mint);

  // Assert: bit-identical estimates, covariances and SINR records.
  ASSERT_EQ(a.runs.size(), b.runs.size());
  for (std::size_t r = 0; r < a.runs.size(); ++r) {
    const auto& ra = a.runs[r];
    const auto& rb = b.runs[r];
    ASSERT_EQ(ra.steps.size(), rb.steps.size()) << "run " << r;
    EXPECT_EQ(ra.trajectory, rb.trajectory);
    EXPECT_EQ(ra.run, rb.run);
    EXPECT_EQ(ra.diverged, rb.diverged);
    for (std::size_t k = 0; k < ra.steps.size(); ++k) {
      EXPECT_EQ(ra.steps[k].estimate_m, rb.steps[k].estimate_m) << "run " << r << " step " << k;
      EXPECT_EQ(ra.steps[k].covariance_m2, rb.steps[k].covariance_m2) << "run " << r << " step " << k;
      EXPECT_EQ(ra.steps[k].associations, rb.steps[k].associations) << "run " << r << " step " << k;
    }
    ASSERT_EQ(ra.paths.size(), rb.paths.size()) << "run " << r;
    for (std::size_t i = 0; i < ra.paths.size(); ++i) {
      EXPECT_EQ(ra.paths[i].va_id, rb.paths[i].va_id);
      EXPECT_EQ(ra.paths[i].amplitude, rb.paths[i].amplitude);
      EXPECT_EQ(ra.paths[i].true_sinr_db, rb.paths[i].true_sinr_db);
      EXPECT_EQ(ra.paths[i].estimated_sinr_db, rb.paths[i].estimated_sinr_db);
    }
  }
}

TEST(RunMintExperiment, DependsOnTheSeed) {
  // Arrange: the determinism test above must not pass because nothing is random.
  auto first = ShortSeminarRoom(1, 1.0);
  auto second = ShortSeminarRoom(1, 1.0);
  second.mint.seed = first.mint.seed + 1;

  // Act
  const auto a = RunMintExperiment(first.mint);
  const auto b = RunMintExperiment(second.mint);

  // Assert
  ASSERT_FALSE(a.runs.empty());
  ASSERT_EQ(a.runs[0].steps.size(), b.runs[0].steps.size());
  EXPECT_NE(a.runs[0].steps.back().estimate_m, b.runs[0].steps.back().estimate_m);
}

TEST(RunMintExperiment, OrdersRunsByTrajectoryThenRunWithTheirGridOffsets) {
  // Arrange
  auto scenario = ShortSeminarRoom(3, 0.5);
  const auto& config = scenario.mint;
  int progress_calls = 0;
  int last_total = 0;

  // Act
  const auto result = RunMintExperiment(config, [&](int, int total) {
    ++progress_calls;
    last_total = total;
  });

  // Assert
  ASSERT_EQ(result.runs.size(), 6u);
  EXPECT_EQ(progress_calls, 6);
  EXPECT_EQ(last_total, 6);
  EXPECT_GT(result.known_vas.size(), 2);
  for (std::size_t i = 0; i < result.runs.size(); ++i) {
    const auto& run = result.runs[i];
    EXPECT_EQ(run.trajectory, static_cast<int>(i) / 3);
    EXPECT_EQ(run.run, static_cast<int>(i) % 3);
    ExpectVecNear(run.offset_m, RunOffset(config.run_grid, run.run), 1e-15);
    const auto& spec = config.trajectories[static_cast<std::size_t>(run.trajectory)];
    const auto samples = geometry::SampleTrajectory(spec.waypoints_m, spec.speed_mps, spec.dt_s, run.offset_m);
    ASSERT_EQ(run.steps.size(), samples.size());
    ASSERT_TRUE(run.steps.front().truth_m.has_value());
    ExpectVecNear(*run.steps.front().truth_m, spec.waypoints_m.front() + run.offset_m, 1e-12);
    for (const auto& s : run.steps) {
      ASSERT_TRUE(s.truth_m && s.error_m);  // simulations always have the truth
      EXPECT_NEAR(*s.error_m, (s.estimate_m - *s.truth_m).norm(), 1e-12);
    }
  }
}

TEST(RunMintExperiment, TracksTheShortSeminarRoomWithinTenCentimetresAtP90) {
  // Arrange: 1 run per trajectory, the first 2 m (40 steps) of each; seed from the file.
  auto scenario = ShortSeminarRoom(1, 2.0);

  // Act
  const auto result = RunMintExperiment(scenario.mint);
  const auto summary = Summarize(scenario.mint, result);

  // Assert: the full example reaches p90 of about 3 cm (examples/README.md).
  std::printf("short seminar room: p90 %.4f m, rmse %.4f m, %d steps, %.3f s\n", summary.overall.error.p90,
              summary.overall.error.rmse, summary.overall.steps, result.wall_s);
  EXPECT_GE(summary.overall.steps, 2 * 40);
  EXPECT_LE(summary.overall.steps, 2 * 41);
  EXPECT_LT(summary.overall.error.p90, 0.1);
  EXPECT_EQ(summary.overall.diverged_runs, 0);
}

TEST(RunMintExperiment, StartsAtAPerturbedPositionWhenAsked) {
  // Arrange
  auto exact = ShortSeminarRoom(1, 0.5);
  auto perturbed = ShortSeminarRoom(1, 0.5);
  perturbed.mint.perturb_initial_position = true;

  // Act
  const auto a = RunMintExperiment(exact.mint);
  const auto b = RunMintExperiment(perturbed.mint);

  // Assert: the very first estimate is the start point after one update; a draw with
  // sigma_i = 10 cm moves it (the data pull it back later).
  EXPECT_NE(a.runs[0].steps.front().estimate_m, b.runs[0].steps.front().estimate_m);
}

TEST(RunMintExperiment, DrawsTheSlamStartWithTheSlamInitialSigma) {
  // Arrange: SLAM with a 0.1 mm start sigma, MINT's left at 0.5 m. A start drawn with MINT's sigma
  // would be decimetres off, and a tracker that trusts its start to 0.1 mm keeps it there.
  auto scenario = ShortSeminarRoom(2, 0.5);
  scenario.mint.method = Method::kSlam;
  scenario.mint.perturb_initial_position = true;
  scenario.mint.mint.initial_position_sigma_m = 0.5;
  scenario.mint.slam.initial_position_sigma_m = 1e-4;

  // Act
  const auto result = RunMintExperiment(scenario.mint);

  // Assert: every run's first estimate is within 1 cm of the truth (5 sigma of the SLAM draw
  // plus the first step's update).
  for (const auto& run : result.runs) {
    ASSERT_FALSE(run.steps.empty());
    EXPECT_LT(*run.steps.front().error_m, 0.01) << "trajectory " << run.trajectory << " run " << run.run;
  }
}

TEST(RunMintExperiment, RangeLevelRunsRecordTheSamePathTruthAndPebAsCirRuns) {
  // Both models see the same specular paths in the same window with the same true SINR
  // (Eq. 3.25), so every step's path records and PEB must agree; only the measurements differ.
  auto cir = ShortSeminarRoom(1, 1.0);
  auto ranges = ShortSeminarRoom(1, 1.0);
  ranges.mint.measurement_model = MeasurementModel::kRangeLevel;

  const auto a = RunMintExperiment(cir.mint);
  const auto b = RunMintExperiment(ranges.mint);

  ASSERT_EQ(a.runs.size(), b.runs.size());
  for (std::size_t r = 0; r < a.runs.size(); ++r) {
    ASSERT_EQ(a.runs[r].paths.size(), b.runs[r].paths.size()) << "run " << r;
    for (std::size_t i = 0; i < a.runs[r].paths.size(); ++i) {
      EXPECT_EQ(a.runs[r].paths[i].step, b.runs[r].paths[i].step);
      EXPECT_EQ(a.runs[r].paths[i].va_id, b.runs[r].paths[i].va_id);
      EXPECT_DOUBLE_EQ(a.runs[r].paths[i].true_sinr_db, b.runs[r].paths[i].true_sinr_db);
    }
    for (std::size_t k = 0; k < a.runs[r].steps.size(); ++k) {
      ASSERT_EQ(a.runs[r].steps[k].peb_m.has_value(), b.runs[r].steps[k].peb_m.has_value());
      if (a.runs[r].steps[k].peb_m) {
        EXPECT_DOUBLE_EQ(*a.runs[r].steps[k].peb_m, *b.runs[r].steps[k].peb_m);
      }
    }
  }
}

}  // namespace
}  // namespace mirage::pipeline
