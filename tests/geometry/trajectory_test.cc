// SPDX-License-Identifier: MIT
#include "mirage/geometry/trajectory.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace mirage::geometry {
namespace {

constexpr double kTol = 1e-12;

// A U-shaped walk (0,0) -> (1,0) -> (1,1) -> (0,1), 3 m long.
const std::vector<Vec2> kUShape{Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};

TEST(PolylineLength, SumsTheSegmentLengths) {
  const std::vector<Vec2> points{Vec2(0, 0), Vec2(3, 4), Vec2(3, 0)};  // 5 + 4
  EXPECT_DOUBLE_EQ(PolylineLength(points), 9.0);
  EXPECT_DOUBLE_EQ(PolylineLength(kUShape), 3.0);
}

TEST(PolylineLength, IsZeroForASinglePointOrNone) {
  const std::vector<Vec2> one{Vec2(2, 3)};
  EXPECT_EQ(PolylineLength(one), 0.0);
  EXPECT_EQ(PolylineLength(std::vector<Vec2>{}), 0.0);
}

TEST(SampleTrajectory, TakesOneSamplePerStepIncludingBothEndsWhenTheLengthIsAMultiple) {
  // 3 m at 1 m/s, dt 0.3 s: step 0.3 m, 3 / 0.3 = 10 steps -> 11 samples, the last at (0,1).
  const auto samples = SampleTrajectory(kUShape, 1.0, 0.3);

  ASSERT_EQ(samples.size(), 11u);
  EXPECT_TRUE(samples.front().position_m.isApprox(Vec2(0, 0), kTol));
  EXPECT_NEAR((samples.back().position_m - Vec2(0, 1)).norm(), 0.0, 1e-9);
  for (std::size_t n = 0; n < samples.size(); ++n) EXPECT_NEAR(samples[n].t_s, 0.3 * static_cast<double>(n), kTol);
}

TEST(SampleTrajectory, StopsAtTheLastSampleBeforeTheFinalWaypoint) {
  // Step 0.4 m: 3 / 0.4 = 7.5 -> samples at 0, 0.4, ..., 2.8 m (8 samples). Arc length 2.8 is
  // 0.8 m along the last segment (1,1) -> (0,1): (0.2, 1).
  const auto samples = SampleTrajectory(kUShape, 0.5, 0.8);

  ASSERT_EQ(samples.size(), 8u);
  EXPECT_NEAR((samples.back().position_m - Vec2(0.2, 1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(samples.back().t_s, 5.6, kTol);
}

TEST(SampleTrajectory, PutsASampleJustAfterACornerOnTheNextSegmentAtTheRightArcLength) {
  // The walker turns instantly: arc length 1.2 m is 0.2 m up the second segment, (1, 0.2);
  // 2.1 m is 0.1 m along the third, (0.9, 1).
  const auto samples = SampleTrajectory(kUShape, 1.0, 0.3);

  ASSERT_EQ(samples.size(), 11u);
  EXPECT_NEAR((samples[3].position_m - Vec2(0.9, 0)).norm(), 0.0, 1e-12);  // 0.9 m, before the corner
  EXPECT_NEAR((samples[4].position_m - Vec2(1, 0.2)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((samples[7].position_m - Vec2(0.9, 1)).norm(), 0.0, 1e-12);
}

TEST(SampleTrajectory, GivesEachSampleTheVelocityOfItsSegment) {
  const auto samples = SampleTrajectory(kUShape, 1.0, 0.3);

  EXPECT_TRUE(samples[1].velocity_mps.isApprox(Vec2(1, 0), kTol));
  EXPECT_TRUE(samples[4].velocity_mps.isApprox(Vec2(0, 1), kTol));
  EXPECT_TRUE(samples[7].velocity_mps.isApprox(Vec2(-1, 0), kTol));
}

TEST(SampleTrajectory, WalksADiagonalAtTheGivenSpeed) {
  // (0,0) -> (3,4) at 0.5 m/s, dt 2 s: 1 m per step along (0.6, 0.8); 5 steps -> 6 samples.
  const std::vector<Vec2> line{Vec2(0, 0), Vec2(3, 4)};

  const auto samples = SampleTrajectory(line, 0.5, 2.0);

  ASSERT_EQ(samples.size(), 6u);
  EXPECT_TRUE(samples[1].position_m.isApprox(Vec2(0.6, 0.8), kTol));
  EXPECT_TRUE(samples[3].position_m.isApprox(Vec2(1.8, 2.4), kTol));
  EXPECT_TRUE(samples[2].velocity_mps.isApprox(Vec2(0.3, 0.4), kTol));
  EXPECT_NEAR(samples[5].t_s, 10.0, kTol);
}

TEST(SampleTrajectory, ShiftsPositionsButNotVelocitiesByTheOffset) {
  const Vec2 offset(0.01, -0.02);

  const auto plain = SampleTrajectory(kUShape, 1.0, 0.3);
  const auto shifted = SampleTrajectory(kUShape, 1.0, 0.3, offset);

  ASSERT_EQ(shifted.size(), plain.size());
  for (std::size_t n = 0; n < plain.size(); ++n) {
    EXPECT_TRUE((shifted[n].position_m - plain[n].position_m).isApprox(offset, 1e-12));
    EXPECT_EQ(shifted[n].velocity_mps, plain[n].velocity_mps);
    EXPECT_EQ(shifted[n].t_s, plain[n].t_s);
  }
  EXPECT_TRUE(shifted[4].position_m.isApprox(Vec2(1.01, 0.18), 1e-12));
}

TEST(SampleTrajectory, SkipsZeroLengthSegments) {
  // A repeated waypoint at (1,0); step 0.5 m: arc length 1.5 m is (1, 0.5) moving north.
  const std::vector<Vec2> points{Vec2(0, 0), Vec2(1, 0), Vec2(1, 0), Vec2(1, 1)};

  const auto samples = SampleTrajectory(points, 0.5, 1.0);

  ASSERT_EQ(samples.size(), 5u);
  EXPECT_TRUE(samples[3].position_m.isApprox(Vec2(1, 0.5), kTol));
  EXPECT_TRUE(samples[3].velocity_mps.isApprox(Vec2(0, 0.5), kTol));
  EXPECT_TRUE(samples[4].position_m.isApprox(Vec2(1, 1), kTol));
}

TEST(SampleTrajectory, MatchesTheThesisStepOf5cmAt0Point1s) {
  // 0.5 m/s at 0.1 s -> 5 cm per step (Lafer 2014 Sec. 3.7); a 3 m walk has 61 samples.
  const auto samples = SampleTrajectory(kUShape, 0.5, 0.1);

  ASSERT_EQ(samples.size(), 61u);
  EXPECT_NEAR((samples[21].position_m - Vec2(1, 0.05)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((samples[60].position_m - Vec2(0, 1)).norm(), 0.0, 1e-9);
}

TEST(SampleTrajectory, WithZeroTurnRadiusTurnsInstantlyAsBefore) {
  const auto instant = SampleTrajectory(kUShape, 0.5, 0.1);
  const auto zero = SampleTrajectory(kUShape, 0.5, 0.1, Vec2::Zero(), 0.0);
  ASSERT_EQ(instant.size(), zero.size());
  for (std::size_t n = 0; n < zero.size(); ++n) EXPECT_EQ(instant[n].position_m, zero[n].position_m);
}

TEST(SampleTrajectory, RoundedCornersKeepTheSpeedAndTurnWithLateralAccelerationSpeedSquaredOverRadius) {
  // An L of 4 m legs with a 0.5 m turn radius: steps of 5 cm, every step walks 5 cm of path, and
  // on the arc the velocity turns by v dt / r per step, i.e. |dv/dt| = v^2 / r.
  const std::vector<Vec2> l_shape{Vec2(0, 0), Vec2(4, 0), Vec2(4, 4)};
  const double speed_mps = 0.5, dt_s = 0.1, radius_m = 0.5;
  const auto samples = SampleTrajectory(l_shape, speed_mps, dt_s, Vec2::Zero(), radius_m);

  // Path length: two legs minus two tangent lengths r plus the quarter arc pi r / 2.
  const double length_m = 8.0 - 2.0 * radius_m + 0.5 * std::acos(-1.0) * radius_m;
  ASSERT_EQ(samples.size(), static_cast<std::size_t>(std::floor(length_m / (speed_mps * dt_s))) + 1);
  double max_accel_mps2 = 0.0;
  for (std::size_t n = 1; n < samples.size(); ++n) {
    EXPECT_NEAR(samples[n].velocity_mps.norm(), speed_mps, 1e-12);
    // A chord of the arc is shorter than the arc walked; never longer than the step.
    const double chord_m = (samples[n].position_m - samples[n - 1].position_m).norm();
    EXPECT_LE(chord_m, speed_mps * dt_s + 1e-12);
    EXPECT_GT(chord_m, speed_mps * dt_s * 0.99);
    max_accel_mps2 = std::max(max_accel_mps2, (samples[n].velocity_mps - samples[n - 1].velocity_mps).norm() / dt_s);
  }
  EXPECT_NEAR(max_accel_mps2, speed_mps * speed_mps / radius_m, 0.01);
  // The corner itself is cut: the closest sample stays r (sqrt(2) - 1) away from (4, 0).
  double closest_m = 1e9;
  for (const auto& s : samples) closest_m = std::min(closest_m, (s.position_m - Vec2(4, 0)).norm());
  EXPECT_NEAR(closest_m, radius_m * (std::sqrt(2.0) - 1.0), 0.01);
  EXPECT_TRUE(samples.front().position_m.isApprox(Vec2(0, 0), kTol));
  EXPECT_LT((samples.back().position_m - Vec2(4, 4)).norm(), speed_mps * dt_s);
}

TEST(SampleTrajectory, ShrinksTheArcWhereALegIsTooShortToHoldIt) {
  // The U's 1 m legs hold a tangent length of at most 0.5 m: a 2 m radius shrinks to 0.5 m,
  // and the path stays continuous (no step longer than speed * dt).
  const auto samples = SampleTrajectory(kUShape, 0.5, 0.1, Vec2::Zero(), 2.0);
  for (std::size_t n = 1; n < samples.size(); ++n) {
    EXPECT_LE((samples[n].position_m - samples[n - 1].position_m).norm(), 0.05 + 1e-12);
  }
  double max_accel_mps2 = 0.0;
  for (std::size_t n = 1; n < samples.size(); ++n) {
    max_accel_mps2 = std::max(max_accel_mps2, (samples[n].velocity_mps - samples[n - 1].velocity_mps).norm() / 0.1);
  }
  EXPECT_NEAR(max_accel_mps2, 0.5 * 0.5 / 0.5, 0.01);
}

TEST(SampleTrajectory, TurnsInPlaceAtAReversalEvenWithATurnRadius) {
  // Out and back: no arc fits a 180-degree turn, so the walk reverses at (2, 0) without a jump.
  const std::vector<Vec2> back{Vec2(0, 0), Vec2(2, 0), Vec2(0, 0)};
  const auto samples = SampleTrajectory(back, 0.5, 0.1, Vec2::Zero(), 0.5);
  ASSERT_EQ(samples.size(), 81u);
  for (std::size_t n = 1; n < samples.size(); ++n) {
    EXPECT_LE((samples[n].position_m - samples[n - 1].position_m).norm(), 0.05 + 1e-12);
  }
  EXPECT_TRUE(samples[40].position_m.isApprox(Vec2(2, 0), 1e-9));
}

TEST(SampleTrajectory, AStopHoldsThePositionWithZeroVelocityAndTheWalkResumesWhereItStopped) {
  // 10 m at 1 m/s, 0.5 s steps; a 2 s stop from 3 s: slowing over [2.5, 3] s (0.25 m lost), standing
  // at 2.75 m until 5 s, back to speed over [5, 5.5] s. The walk ends 2.5 s later: 5 more samples.
  const std::vector<Vec2> wps = {Vec2(0.0, 0.0), Vec2(10.0, 0.0)};
  const std::vector<Stop> stops = {{3.0, 2.0}};
  const auto plain = SampleTrajectory(wps, 1.0, 0.5);
  for (const double radius_m : {0.0, 0.5}) {
    SCOPED_TRACE(radius_m);
    const auto samples = SampleTrajectory(wps, 1.0, 0.5, Vec2::Zero(), radius_m, stops);
    ASSERT_EQ(samples.size(), plain.size() + 5);
    for (const auto& s : samples) {
      const bool standing = s.t_s >= 3.0 && s.t_s < 5.0;
      if (standing) {
        EXPECT_NEAR(s.position_m.x(), 2.75, 1e-9) << "t " << s.t_s;
        EXPECT_NEAR(s.velocity_mps.norm(), 0.0, 1e-12) << "t " << s.t_s;
      }
      if (s.t_s <= 2.5) {
        EXPECT_NEAR(s.position_m.x(), s.t_s, 1e-9);
      }
      if (s.t_s >= 5.5) {
        EXPECT_NEAR(s.position_m.x(), s.t_s - 2.5, 1e-9);
      }
      if (s.t_s <= 2.5 || s.t_s >= 5.5) {
        EXPECT_NEAR(s.velocity_mps.norm(), 1.0, 1e-12) << "t " << s.t_s;
      }
    }
    EXPECT_NEAR(samples.back().position_m.x(), 10.0, 1e-9);
  }
  // Without stops the samples are those of before (bit for bit: the examples' hashes rely on it).
  const auto none = SampleTrajectory(wps, 1.0, 0.5, Vec2::Zero(), 0.0, {});
  ASSERT_EQ(none.size(), plain.size());
  for (std::size_t i = 0; i < none.size(); ++i) EXPECT_EQ(none[i].position_m, plain[i].position_m);
}

TEST(WalkedTime, LosesHalfARampSlowingDownTheStopAndHalfARampSpeedingUp) {
  // A 2 s stop from 3 s, ramps of kStopRamp_s = 0.5 s.
  ASSERT_DOUBLE_EQ(kStopRamp_s, 0.5);
  const std::vector<Stop> stops = {{3.0, 2.0}, {8.0, 1.0}};
  EXPECT_DOUBLE_EQ(WalkedTime(2.5, stops), 2.5);
  EXPECT_DOUBLE_EQ(WalkedTime(2.75, stops), 2.75 - 0.0625);  // 0.25^2 / (2 * 0.5) lost
  EXPECT_DOUBLE_EQ(WalkedTime(3.0, stops), 2.75);
  EXPECT_DOUBLE_EQ(WalkedTime(4.0, stops), 2.75);            // standing
  EXPECT_DOUBLE_EQ(WalkedTime(5.25, stops), 2.8125);
  EXPECT_DOUBLE_EQ(WalkedTime(5.5, stops), 3.0);             // 2.5 s lost in all
  EXPECT_DOUBLE_EQ(WalkedTime(7.5, stops), 5.0);
  EXPECT_DOUBLE_EQ(WalkedTime(8.5, stops), 5.25);            // inside the second stop
  EXPECT_DOUBLE_EQ(WalkedTime(10.0, stops), 6.0);            // 4 s lost in all
}

}  // namespace
}  // namespace mirage::geometry
