// SPDX-License-Identifier: MIT
// Track-loss recovery for SLAM: the LOS-circle candidates, the match count, and the restart rule
// (a lost estimate on the mirror image of the two-anchor geometry is restarted at the truth after
// lost_steps steps, unless the candidates move faster than a walker; a correct estimate is never
// restarted, clutter or not).
#include "mirage/methods/slam/track_recovery.h"

#include <algorithm>
#include <functional>
#include <vector>

#include <gtest/gtest.h>

#include "core/options_descriptor_expectations.h"
#include "mirage/core/rng.h"
#include "rng_vectors.h"

namespace mirage::methods::slam {
namespace {

const std::vector<MapPoint> kAnchors{{0, Vec2(0.0, 0.0)}, {1, Vec2(4.0, 0.0)}};

// Anchors plus two VAs of each (mirror images of the anchors in walls y = 3 and x = -1).
std::vector<MapPoint> Map() {
  std::vector<MapPoint> map = kAnchors;
  map.push_back({0, Vec2(0.0, 6.0)});
  map.push_back({0, Vec2(-2.0, 0.0)});
  map.push_back({1, Vec2(4.0, 6.0)});
  map.push_back({1, Vec2(-6.0, 0.0)});
  return map;
}

// The score the tracker gives without a floor plan: the map points matched at p (the default
// 5 cm tolerance). The measurements must outlive the returned function (a temporary cannot be
// passed).
std::function<int(const Vec2&)> ScoreOnTheMap(std::vector<core::RangeSet>&& measured) = delete;
std::function<int(const Vec2&)> ScoreOnTheMap(const std::vector<core::RangeSet>& measured) {
  return [&measured](const Vec2& p_m) {
    return CountMatches(p_m, Map(), measured, TrackRecoveryOptions{}.match_tolerance_m);
  };
}

// Exact ranges of every map point from p_m, plus `clutter` weak ranges per anchor, uniform
// between the LOS range and 12 m (diffuse multipath follows the LOS), and one early false peak
// per anchor when clutter > 0 (the LOS is then the second range).
std::vector<core::RangeSet> Measure(const Vec2& p_m, int clutter, core::Rng& rng) {
  std::vector<core::RangeSet> out(2);
  for (int a = 0; a < 2; ++a) out[static_cast<std::size_t>(a)].anchor_index = a;
  for (const MapPoint& point : Map()) {
    out[static_cast<std::size_t>(point.anchor_index)].ranges.push_back({(point.position_m - p_m).norm(), 1.0});
  }
  for (auto& anchor : out) {
    const double los_m = anchor.ranges.front().range_m;
    for (int k = 0; k < clutter; ++k) anchor.ranges.push_back({rng.Uniform(los_m, 12.0), 0.1});
    if (clutter > 0) anchor.ranges.push_back({rng.Uniform(0.0, los_m), 0.1});
  }
  return out;
}

TEST(LosCandidates, AreTheIntersectionsOfTheEarliestRangesCircles) {
  std::vector<core::RangeSet> m(2);
  m[0].anchor_index = 0;
  m[0].ranges = {{9.0, {}}, {2.5, {}}, {7.0, {}}};  // the earliest: 2.5 m
  m[1].anchor_index = 1;
  m[1].ranges = {{2.5, {}}};
  const auto c = LosCandidates(kAnchors, m, 1);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_NEAR(c[0].x(), 2.0, 1e-12);
  EXPECT_NEAR(std::abs(c[0].y()), 1.5, 1e-12);
  EXPECT_NEAR(c[1].y(), -c[0].y(), 1e-12);
  // With two LOS candidates per anchor, (2.5, 2.5) and (7.0, 2.5) give points; 7 + 2.5 > 4 but
  // 7 - 2.5 > 4 puts A2's circle inside A1's: no intersection, and the gap is 0.5 m, no slack.
  EXPECT_EQ(LosCandidates(kAnchors, m, 2).size(), 2u);
}

TEST(LosCandidates, CirclesMissingByLessThanTheSlackTouchBetweenThem) {
  std::vector<core::RangeSet> m(2);
  m[0].anchor_index = 0;
  m[0].ranges = {{1.98, {}}};
  m[1].anchor_index = 1;
  m[1].ranges = {{1.98, {}}};  // 4 cm short of touching
  const auto c = LosCandidates(kAnchors, m, 1);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].x(), 2.0, 1e-12);
  EXPECT_NEAR(c[0].y(), 0.0, 1e-12);
  m[0].ranges[0].range_m = 1.9;  // 12 cm short: no candidate
  EXPECT_TRUE(LosCandidates(kAnchors, m, 1).empty());
}

TEST(CountMatches, CountsEachMapPointOnceWithinTheTolerance) {
  const Vec2 p(1.0, 1.0);
  core::Rng rng(1, 0);
  auto m = Measure(p, 0, rng);
  EXPECT_EQ(CountMatches(p, Map(), m, 0.05), 6);
  m[0].ranges.push_back(m[0].ranges[0]);  // a duplicate range does not count twice
  EXPECT_EQ(CountMatches(p, Map(), m, 0.05), 6);
  for (auto& r : m[1].ranges) r.range_m += 0.06;  // anchor 1's ranges all just outside
  EXPECT_EQ(CountMatches(p, Map(), m, 0.05), 3);
}

TEST(TrackRecovery, RestartsAnEstimateOnTheMirrorImageAfterLostSteps) {
  TrackRecoveryOptions options;
  TrackRecovery recovery(options);
  core::Rng rng(7, 0);
  const Vec2 velocity_mps(0.5, 0.0);
  std::optional<Restart> restart;
  int steps = 0;
  for (; steps < 10 && !restart; ++steps) {
    const double t_s = 0.1 * steps;
    const Vec2 truth_m = Vec2(1.0, 1.5) + velocity_mps * t_s;
    const Vec2 mirror_m(truth_m.x(), -truth_m.y());  // both LOS ranges fit here, no VA does
    const auto measured = Measure(truth_m, 15, rng);
    restart = recovery.Check(t_s, mirror_m, kAnchors, ScoreOnTheMap(measured), measured);
    if (restart) {
      EXPECT_LT((restart->position_m - truth_m).norm(), 1e-6);
      EXPECT_LT((restart->velocity_mps - velocity_mps).norm(), 1e-6);
    }
  }
  ASSERT_TRUE(restart.has_value());
  EXPECT_EQ(steps, options.lost_steps);
}

// The restart of an estimate that sits on the mirror image of a walker moving at velocity_mps,
// within 10 steps, if any (no clutter: the candidates' chain is never broken by chance).
std::optional<Restart> RestartOfAMirrorEstimate(const TrackRecoveryOptions& options, const Vec2& velocity_mps) {
  TrackRecovery recovery(options);
  core::Rng rng(7, 0);
  for (int steps = 0; steps < 10; ++steps) {
    const double t_s = 0.1 * steps;
    const Vec2 truth_m = Vec2(1.0, 1.5) + velocity_mps * t_s;
    const auto measured = Measure(truth_m, 0, rng);
    const Vec2 mirror_m(truth_m.x(), -truth_m.y());
    if (auto restart = recovery.Check(t_s, mirror_m, kAnchors, ScoreOnTheMap(measured), measured)) return restart;
  }
  return std::nullopt;
}

TEST(TrackRecovery, AChainFasterThanAWalkerRestartsNothing) {
  // 2 m/s: 0.2 m per step, inside follow_gate_m, so only the speed limit tells it from a walker.
  const Vec2 fast_mps(2.0, 0.0);
  ASSERT_LT(0.1 * fast_mps.norm(), TrackRecoveryOptions{}.follow_gate_m);
  EXPECT_FALSE(RestartOfAMirrorEstimate(TrackRecoveryOptions{}, fast_mps).has_value());
  TrackRecoveryOptions unlimited;
  unlimited.max_speed_mps = 10.0;
  EXPECT_TRUE(RestartOfAMirrorEstimate(unlimited, fast_mps).has_value());
  EXPECT_TRUE(RestartOfAMirrorEstimate(TrackRecoveryOptions{}, Vec2(1.3, 0.0)).has_value()) << "a 1.3 m/s walk";
}

TEST(TrackRecovery, NeverRestartsACorrectEstimate) {
  TrackRecovery recovery(TrackRecoveryOptions{});
  core::Rng rng(11, 0);
  for (int k = 0; k < 500; ++k) {
    const Vec2 truth_m = testing::UniformVec2(rng, Vec2(0.5, 0.5), Vec2(3.5, 2.5));
    auto m = Measure(truth_m, 15, rng);
    for (auto& anchor : m) {
      for (auto& r : anchor.ranges) r.range_m += rng.Normal(0.0, 0.01);
    }
    ASSERT_FALSE(recovery.Check(0.1 * k, truth_m, kAnchors, ScoreOnTheMap(m), m).has_value()) << "step " << k;
  }
}

TEST(TrackRecovery, DisabledNeverRestarts) {
  TrackRecoveryOptions options;
  options.enabled = false;
  TrackRecovery recovery(options);
  core::Rng rng(3, 0);
  for (int k = 0; k < 10; ++k) {
    const auto measured = Measure(Vec2(1.0, 1.5), 0, rng);
    EXPECT_FALSE(recovery.Check(0.1 * k, Vec2(1.0, -1.5), kAnchors, ScoreOnTheMap(measured), measured));
  }
}

TEST(TrackRecoveryOptions, ValidateNamesEachBadValue) {
  TrackRecoveryOptions o;
  EXPECT_TRUE(Validate(o).empty());
  o.match_tolerance_m = 0.0;
  o.los_candidates = 0;
  o.min_margin = 0;
  o.lost_steps = 0;
  o.follow_gate_m = -1.0;
  o.max_jump_m = 0.0;
  o.min_margin_floor_plan = 0;
  o.floor_plan_watch_s = -1.0;
  o.max_speed_mps = 0.0;
  o.circle_slack_m = 0.0;
  EXPECT_EQ(Validate(o).size(), 10u);
}

TEST(TrackRecoveryOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMember) {
  test::ExpectDescribesEveryMember(TrackRecoveryOptionsDescriptor(),
                                   {"enabled", "match_tolerance_m", "circle_slack_m", "los_candidates", "min_margin",
                                    "min_margin_floor_plan", "floor_plan_watch_s", "lost_steps", "follow_gate_m",
                                    "max_jump_m", "max_speed_mps"});
}

}  // namespace
}  // namespace mirage::methods::slam
