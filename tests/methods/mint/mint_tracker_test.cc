// SPDX-License-Identifier: MIT
// The MINT tracker (Lafer 2014 ch. 3) on synthetic unlabeled ranges in the 6 m x 6 m square
// room of square_room.h: tracking accuracy with and without clutter, the variance options, the
// data association, a seeded Monte-Carlo NEES check, relocalization and the in-room constraint.
#include "mirage/methods/mint/mint_tracker.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "core/options_descriptor_expectations.h"
#include "methods/mint/square_room.h"
#include "mirage/geometry/trajectory.h"
#include "mirage/geometry/visibility.h"

namespace mirage::methods::mint {
namespace {

using testing::MeasureRanges;
using testing::MeasurementModel;

// sigma_1 = c / (sqrt(8) pi beta) chosen so that the CRLB variance at the amplitudes' K = 10
// (10 dB) equals the 1 cm range noise: sigma_1^2 / 10 = (1 cm)^2.
const double kSigma1M = 0.01 * std::sqrt(10.0);

// Straight along y = 1.5 m for 2.5 m, then a 90 degree corner and 3 m north: 110 steps of 5 cm.
std::vector<geometry::TrajectorySample> StraightThenCorner() {
  const std::vector<Vec2> waypoints{Vec2(1.5, 1.5), Vec2(4.0, 1.5), Vec2(4.0, 4.5)};
  return geometry::SampleTrajectory(waypoints, 0.5, 0.1);
}

struct TrackRun {
  std::vector<MintStepResult> steps;
  std::vector<Vec2> truth_m;
  std::vector<double> errors_m;
  [[nodiscard]] double max_error_m() const { return *std::max_element(errors_m.begin(), errors_m.end()); }
  [[nodiscard]] double rmse_m() const {
    double sum = 0.0;
    for (const double e : errors_m) sum += e * e;
    return std::sqrt(sum / static_cast<double>(errors_m.size()));
  }
};

// Runs the tracker along the trajectory, starting at truth + start_offset_m.
TrackRun Track(const MintOptions& options, const geometry::FloorPlan& plan, const geometry::VirtualAnchorSet& vas,
               const std::vector<geometry::TrajectorySample>& samples, const MeasurementModel& model, core::Rng& rng,
               const Vec2& start_offset_m = Vec2::Zero()) {
  MintTracker tracker(options, vas, plan, kSigma1M);
  tracker.Initialize(samples.front().t_s, samples.front().position_m + start_offset_m);
  TrackRun run;
  for (std::size_t k = 1; k < samples.size(); ++k) {
    const auto ranges = MeasureRanges(vas, plan, samples[k].position_m, model, rng);
    run.steps.push_back(tracker.Step(samples[k].t_s, ranges));
    run.truth_m.push_back(samples[k].position_m);
    run.errors_m.push_back((run.steps.back().position_m - samples[k].position_m).norm());
  }
  return run;
}

MintOptions TrackerOptions() {
  MintOptions options;
  options.max_order = 1;
  return options;
}

TEST(MintTracker, TracksCleanRangesWithinAFewCentimetres) {
  // Arrange
  const auto plan = testing::SquareRoomWithPillar();
  const auto vas = testing::SquareRoomVas(plan, 1);
  core::Rng rng(1, 0);

  // Act
  const TrackRun run = Track(TrackerOptions(), plan, vas, StraightThenCorner(), MeasurementModel{}, rng);

  // Assert: 1 cm ranges from up to 10 VAs; the corner is a 7-sigma acceleration for the motion
  // model, which the measurements absorb within a step or two.
  std::printf("clean: rmse %.4f m, max %.4f m\n", run.rmse_m(), run.max_error_m());
  EXPECT_LT(run.rmse_m(), 0.02);
  EXPECT_LT(run.max_error_m(), 0.05);
}

TEST(MintTracker, StillTracksWithUniformClutterRanges) {
  // Arrange: 8 extra ranges per anchor and step, uniform in [0, 10) m (as many as true ones).
  const auto plan = testing::SquareRoomWithPillar();
  const auto vas = testing::SquareRoomVas(plan, 1);
  MeasurementModel model;
  model.clutter_per_anchor = 8;
  core::Rng rng(2, 0);

  // Act
  const TrackRun run = Track(TrackerOptions(), plan, vas, StraightThenCorner(), model, rng);

  // Assert
  std::printf("clutter: rmse %.4f m, max %.4f m\n", run.rmse_m(), run.max_error_m());
  EXPECT_LT(run.rmse_m(), 0.03);
  EXPECT_LT(run.max_error_m(), 0.08);
}

TEST(MintTracker, UsesRangeSigmaForEveryAssociationWhenVarianceEstimationIsOff) {
  // Arrange
  const auto plan = testing::SquareRoomWithPillar();
  const auto vas = testing::SquareRoomVas(plan, 1);
  MintOptions options = TrackerOptions();
  options.variance.enabled = false;
  options.range_sigma_m = 0.03;
  core::Rng rng(3, 0);

  // Act
  const TrackRun run = Track(options, plan, vas, StraightThenCorner(), MeasurementModel{}, rng);

  // Assert
  int associations = 0;
  for (const auto& step : run.steps) {
    for (const auto& a : step.associations) {
      ++associations;
      EXPECT_DOUBLE_EQ(a.variance_m2, 0.03 * 0.03);
      EXPECT_FALSE(a.sinr.has_value());
    }
  }
  EXPECT_GT(associations, 5 * static_cast<int>(run.steps.size()));
  EXPECT_LT(run.max_error_m(), 0.05);
}

TEST(MintTracker, EstimatesPerVaVariancesWhenVarianceEstimationIsOn) {
  // Arrange
  const auto plan = testing::SquareRoomWithPillar();
  const auto vas = testing::SquareRoomVas(plan, 1);
  core::Rng rng(4, 0);

  // Act
  const TrackRun run = Track(TrackerOptions(), plan, vas, StraightThenCorner(), MeasurementModel{}, rng);

  // Assert: after 1 m of walking (20 steps) SINR estimates appear; at K = 10 their variances lie
  // well below the default sigma_VA^2 = 0.0049 m^2.
  int estimates = 0;
  for (std::size_t k = 0; k < run.steps.size(); ++k) {
    for (const auto& a : run.steps[k].associations) {
      if (k < 10) {
        EXPECT_FALSE(a.sinr.has_value()) << "step " << k;
      }
      if (!a.sinr) continue;
      ++estimates;
      EXPECT_LT(a.variance_m2, 0.0049);
    }
  }
  EXPECT_GT(estimates, 100);
}

TEST(MintTracker, AssociatesOnlyVisibleVasUpToMaxOrder) {
  // Arrange: ranges of every VA up to order 2, including those the pillar blocks (ghosts), and
  // a tracker that knows VAs up to order 2 but uses order 1.
  const auto plan = testing::SquareRoomWithPillar();
  const auto vas = testing::SquareRoomVas(plan, 2);
  MeasurementModel model;
  model.max_order = 2;
  model.only_visible = false;
  core::Rng rng(5, 0);
  const auto samples = StraightThenCorner();
  int blocked_steps = 0;
  for (const auto& s : samples) {
    const auto a0 = geometry::VisibleVirtualAnchors(vas, 0, plan, s.position_m, 1);
    const auto a1 = geometry::VisibleVirtualAnchors(vas, 1, plan, s.position_m, 1);
    if (a0.size() + a1.size() < 10) ++blocked_steps;
  }
  ASSERT_GT(blocked_steps, 5) << "the pillar must block some first-order paths for this test to mean anything";

  // Act
  const TrackRun run = Track(TrackerOptions(), plan, vas, samples, model, rng);

  // Assert: each associated VA is of order <= 1 and visible from the estimate or the truth
  // (they differ by millimetres; the association is made at a reference in between).
  for (std::size_t k = 0; k < run.steps.size(); ++k) {
    const auto& step = run.steps[k];
    EXPECT_LE(static_cast<int>(step.associations.size()), step.visible_count);
    for (const auto& a : step.associations) {
      EXPECT_LE(vas[a.va_id].order, 1) << "step " << k;
      const bool visible = geometry::IsVisible(vas, a.va_id, plan, step.position_m) ||
                           geometry::IsVisible(vas, a.va_id, plan, run.truth_m[k]);
      EXPECT_TRUE(visible) << "step " << k << " associated the invisible VA " << a.va_id;
      EXPECT_NEAR(a.expected_range_m, (vas[a.va_id].position_m - run.truth_m[k]).norm(), 0.1);
    }
  }
  EXPECT_LT(run.max_error_m(), 0.05);
}

TEST(MintTracker, HasAConsistentPositionCovarianceOnCleanRanges) {
  // Arrange: 40 seeded runs with variance estimation off and range_sigma_m equal to the true
  // range noise, so the filter's R is right. NEES_k = e^T P^-1 e of the position is chi^2(2)
  // distributed for a consistent filter, mean 2. We average over the straight part after the
  // first 10 steps (the start covariance is deliberately wide), i.e. 40 runs x 39 steps. The
  // steps of one run are correlated, so we treat each run's average as one sample: the mean of
  // 40 chi^2(2) variables lies in [1.4, 2.7] with 99 % probability (chi^2(80)/40); averaging
  // within a run only narrows that. The motion model's acceleration noise overstates the
  // straight walk's (zero) acceleration, which makes the filter slightly conservative, so we
  // widen the lower end and accept [1.2, 2.8] (observed: 1.9).
  const auto plan = testing::EmptySquareRoom();
  const auto vas = testing::SquareRoomVas(plan, 1);
  MintOptions options = TrackerOptions();
  options.variance.enabled = false;
  options.range_sigma_m = 0.01;
  options.relocalization.enabled = false;
  const std::vector<Vec2> waypoints{Vec2(1.5, 1.5), Vec2(4.0, 1.5)};
  const auto samples = geometry::SampleTrajectory(waypoints, 0.5, 0.1);
  double nees_sum = 0.0;
  int nees_count = 0;
  constexpr int kRuns = 40;

  // Act
  for (int r = 0; r < kRuns; ++r) {
    core::Rng rng(2024, static_cast<std::uint64_t>(r));
    const TrackRun run = Track(options, plan, vas, samples, MeasurementModel{}, rng);
    for (std::size_t k = 10; k < run.steps.size(); ++k) {
      const Vec2 e = run.steps[k].position_m - run.truth_m[k];
      nees_sum += e.dot(run.steps[k].position_covariance.ldlt().solve(e));
      ++nees_count;
    }
  }

  // Assert
  const double nees = nees_sum / nees_count;
  std::printf("average NEES %.3f over %d steps\n", nees, nees_count);
  EXPECT_GT(nees, 1.2);
  EXPECT_LT(nees, 2.8);
}

TEST(MintTracker, RelocalizesWhenStartedOneMetreFromTheTruth) {
  // Arrange: the tracker starts 1 m east of the true start, where almost no range associates
  // within the 15 cm cut-off.
  const auto plan = testing::SquareRoomWithPillar();
  const auto vas = testing::SquareRoomVas(plan, 1);
  core::Rng rng(6, 0);

  // Act
  const TrackRun run = Track(TrackerOptions(), plan, vas, StraightThenCorner(), MeasurementModel{}, rng, Vec2(1.0, 0.0));

  // Assert: lost_steps = 3 low-score steps trigger the search; the tracker is within 10 cm a
  // few steps later and stays there.
  std::size_t relocalized_at = run.steps.size();
  for (std::size_t k = 0; k < run.steps.size(); ++k) {
    if (run.steps[k].relocalized) {
      relocalized_at = k;
      break;
    }
  }
  ASSERT_LT(relocalized_at, 10u) << "never relocalized in the first 10 steps";
  EXPECT_GT(run.errors_m.front(), 0.5);
  for (std::size_t k = relocalized_at + 3; k < run.steps.size(); ++k) {
    EXPECT_LT(run.errors_m[k], 0.1) << "step " << k;
  }
}

TEST(MintTracker, StaysLostWithoutRelocalization) {
  // Arrange: the same start 1 m off, relocalization switched off (shows the test above can fail).
  const auto plan = testing::SquareRoomWithPillar();
  const auto vas = testing::SquareRoomVas(plan, 1);
  MintOptions options = TrackerOptions();
  options.relocalization.enabled = false;
  core::Rng rng(6, 0);

  // Act
  const TrackRun run = Track(options, plan, vas, StraightThenCorner(), MeasurementModel{}, rng, Vec2(1.0, 0.0));

  // Assert
  EXPECT_TRUE(std::none_of(run.steps.begin(), run.steps.end(), [](const auto& s) { return s.relocalized; }));
  EXPECT_GT(run.errors_m[10], 0.1);
}

// Ranges generated from a point 5 cm outside the west wall, the tracker starting 5 cm inside.
TrackRun PulledThroughTheWestWall(bool constrain) {
  const auto plan = testing::EmptySquareRoom();
  const auto vas = testing::SquareRoomVas(plan, 1);
  MintOptions options = TrackerOptions();
  options.constrain_to_room = constrain;
  options.relocalization.enabled = false;
  MintTracker tracker(options, vas, plan, kSigma1M);
  const Vec2 start(0.05, 3.0);
  const Vec2 outside(-0.05, 3.0);
  tracker.Initialize(0.0, start);
  core::Rng rng(7, 0);
  MeasurementModel model;
  model.range_sigma_m = 0.002;
  TrackRun run;
  for (int k = 1; k <= 20; ++k) {
    std::vector<core::RangeSet> ranges;
    for (int a = 0; a < vas.anchor_count(); ++a) {
      core::RangeSet anchor;
    anchor.anchor_index = a;
      // The VAs visible from inside, at the distances from the outside point.
      for (const int id : geometry::VisibleVirtualAnchors(vas, a, plan, start, 1)) {
        anchor.ranges.push_back({(vas[id].position_m - outside).norm() + rng.Normal(0.0, model.range_sigma_m), 1.0});
      }
      ranges.push_back(anchor);
    }
    run.steps.push_back(tracker.Step(0.1 * k, ranges));
    run.truth_m.push_back(outside);
    run.errors_m.push_back((run.steps.back().position_m - outside).norm());
  }
  return run;
}

TEST(MintTracker, KeepsTheEstimateInsideTheRoomWhenConstrained) {
  // Arrange / Act
  const TrackRun constrained = PulledThroughTheWestWall(true);
  const TrackRun free = PulledThroughTheWestWall(false);

  // Assert: unconstrained, the ranges pull the estimate through the wall at x = 0; constrained,
  // every estimate stays inside and some step reports the constraint.
  const auto min_x = [](const TrackRun& run) {
    double x = 1e9;
    for (const auto& s : run.steps) x = std::min(x, s.position_m.x());
    return x;
  };
  ASSERT_LT(min_x(free), 0.0) << "the ranges must pull the unconstrained estimate outside";
  EXPECT_GT(min_x(constrained), 0.0);
  EXPECT_TRUE(std::any_of(constrained.steps.begin(), constrained.steps.end(), [](const auto& s) { return s.constrained; }));
  EXPECT_TRUE(std::none_of(free.steps.begin(), free.steps.end(), [](const auto& s) { return s.constrained; }));
}

bool Mentions(const std::vector<std::string>& problems, const std::string& key) {
  return std::any_of(problems.begin(), problems.end(), [&](const std::string& p) { return p.find(key) != std::string::npos; });
}

TEST(MintOptions, AcceptsTheDefaultsAndPrefixesNestedProblems) {
  const auto with = [](auto change) {
    MintOptions o;
    change(o);
    return Validate(o);
  };
  EXPECT_TRUE(Validate(MintOptions{}).empty());
  EXPECT_TRUE(Mentions(with([](auto& o) { o.cutoff_m = 0.0; }), "cutoff_m"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.range_sigma_m = -1.0; }), "range_sigma_m"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.max_order = -1; }), "max_order"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.innovation_gate_chi2 = -1.0; }), "innovation_gate_chi2"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.variance.min_samples = 1; }), "variance.min_samples"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.relocalization.lost_steps = 0; }), "relocalization.lost_steps"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.motion.accel_sigma_mps2 = 0.0; }), "motion.accel_sigma_mps2"));
}

TEST(MintOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMember) {
  test::ExpectDescribesEveryMember(MintOptionsDescriptor(),
                                   {"cutoff_m", "range_sigma_m", "initial_position_sigma_m",
                                    "initial_velocity_sigma_mps", "max_order", "reassociate", "innovation_gate_chi2",
                                    "constrain_to_room", "motion", "variance", "relocalization"});
}

TEST(MintOptions, RejectsARelocalizationOrderAboveTheTrackersOnlyWhenRelocalizing) {
  MintOptions o;
  o.max_order = 1;
  o.relocalization.max_order = 2;

  EXPECT_EQ(Validate(o), std::vector<std::string>{"relocalization.max_order: 2 must be <= max_order (1): the "
                                                  "tracker knows no higher-order VAs"});
  o.relocalization.enabled = false;
  EXPECT_TRUE(Validate(o).empty());
}

}  // namespace
}  // namespace mirage::methods::mint
