// SPDX-License-Identifier: MIT
#include "mirage/geometry/feasible_region.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace mirage::geometry {
namespace {

constexpr double kTol = 1e-12;

std::vector<Wall> SquareWalls() {
  return {{Vec2(0, 0), Vec2(4, 0), 0.5, "south"},
          {Vec2(4, 0), Vec2(4, 4), 0.5, "east"},
          {Vec2(4, 4), Vec2(0, 4), 0.5, "north"},
          {Vec2(0, 4), Vec2(0, 0), 0.5, "west"}};
}

TEST(ConstrainMove, LeavesAFeasibleMoveUntouched) {
  const FloorPlan plan(SquareWalls(), {{Vec2(3, 1), 0.3, "pillar"}});

  EXPECT_EQ(ConstrainMove(plan, Vec2(1, 1), Vec2(2, 2)), Vec2(2, 2));
}

TEST(ConstrainMove, StopsAMoveOneCentimetreBeforeTheWallItCrosses) {
  // (3,2) -> (5,2) crosses x = 4 at t = 1/2; length 2 m, so t = 0.5 - 0.01/2 -> (3.99, 2).
  const FloorPlan plan(SquareWalls(), {});

  EXPECT_TRUE(ConstrainMove(plan, Vec2(3, 2), Vec2(5, 2)).isApprox(Vec2(3.99, 2), kTol));
}

TEST(ConstrainMove, StopsAnObliqueMoveTheMarginBeforeTheCrossingAlongTheMove) {
  // (3,3) -> (5,4) crosses x = 4 at (4, 3.5), t = 1/2; length sqrt(5). The result lies on the
  // move, 1 cm before the crossing point.
  const FloorPlan plan(SquareWalls(), {});

  const Vec2 result = ConstrainMove(plan, Vec2(3, 3), Vec2(5, 4));

  const Vec2 expected = Vec2(3, 3) + (0.5 - 0.01 / std::sqrt(5.0)) * Vec2(2, 1);
  EXPECT_TRUE(result.isApprox(expected, kTol));
  EXPECT_NEAR((Vec2(4, 3.5) - result).norm(), 0.01, 1e-12);
}

TEST(ConstrainMove, StopsBeforeTheFirstOfSeveralWalls) {
  // (1,2) -> (9,2) crosses x = 4 at t = 3/8 (an outer wall x = 8 at t = 7/8 is second).
  std::vector<Wall> walls = SquareWalls();
  walls.push_back({Vec2(8, -1), Vec2(8, 5), 0.5, "outer"});
  const FloorPlan plan(walls, {});

  EXPECT_TRUE(ConstrainMove(plan, Vec2(1, 2), Vec2(9, 2)).isApprox(Vec2(3.99, 2), kTol));
}

TEST(ConstrainMove, StopsAMoveThroughAnInteriorWallStub) {
  // The stub y = 1, x in [2,3]; (2.5,0.5) -> (2.5,1.5) is stopped at y = 0.99.
  std::vector<Wall> walls = SquareWalls();
  walls.push_back({Vec2(2, 1), Vec2(3, 1), 0.5, "stub"});
  const FloorPlan plan(walls, {});

  EXPECT_TRUE(ConstrainMove(plan, Vec2(2.5, 0.5), Vec2(2.5, 1.5)).isApprox(Vec2(2.5, 0.99), kTol));
}

TEST(ConstrainMove, StaysAtTheStartWhenTheWallIsCloserThanTheMargin) {
  // From 5 mm before the east wall the margin would need a step backwards; clamped to t = 0.
  const FloorPlan plan(SquareWalls(), {});

  EXPECT_EQ(ConstrainMove(plan, Vec2(3.995, 2), Vec2(4.5, 2)), Vec2(3.995, 2));
}

TEST(ConstrainMove, UsesTheGivenMargin) {
  const FloorPlan plan(SquareWalls(), {});

  EXPECT_TRUE(ConstrainMove(plan, Vec2(3, 2), Vec2(5, 2), 0.1).isApprox(Vec2(3.9, 2), kTol));
}

TEST(ConstrainMove, StopsAMoveTheMarginBeforeItEntersAnObstacle) {
  // Pillar (2,2) r 0.5. The move (0.5,2) -> (2,2) enters the disc at x = 1.5; stopping 1 cm
  // before gives (1.49, 2).
  const FloorPlan plan(SquareWalls(), {{Vec2(2, 2), 0.5, "pillar"}});

  EXPECT_TRUE(ConstrainMove(plan, Vec2(0.5, 2), Vec2(2, 2)).isApprox(Vec2(1.49, 2), kTol));
}

TEST(ConstrainMove, StopsAnObliqueMoveAtTheEntryPointOfTheObstacle) {
  // Pillar (2,2) r 0.5, move from (3.5,3.5) towards (2.15,2.2): direction (-1.35,-1.3), length
  // 1.8742. Entry: |(3.5,3.5) + t d - (2,2)| = 0.5 -> f = (1.5,1.5), a = 3.5125, b = -7.95,
  // c = 4.25; t = (7.95 - sqrt(63.2025 - 59.7125)) / 7.025 = (7.95 - 1.86815) / 7.025 = 0.865744.
  // Stopping 1 cm earlier: t - 0.01 / 1.8742 = 0.860408 -> (3.5 - 1.35 t, 3.5 - 1.3 t).
  const FloorPlan plan(SquareWalls(), {{Vec2(2, 2), 0.5, "pillar"}});

  const Vec2 result = ConstrainMove(plan, Vec2(3.5, 3.5), Vec2(2.15, 2.2));

  EXPECT_TRUE(result.isApprox(Vec2(3.5 - 1.35 * 0.860408, 3.5 - 1.3 * 0.860408), 1e-5));
  EXPECT_NEAR((result - Vec2(2, 2)).norm(), 0.51, 1e-4);
}

TEST(ConstrainMove, StopsAMoveThatWouldCrossAnObstacle) {
  // The whole move counts, not only its end: (1,2) -> (3,2) passes through the pillar and is
  // stopped 1 cm before it enters at x = 1.5.
  const FloorPlan plan(SquareWalls(), {{Vec2(2, 2), 0.5, "pillar"}});

  EXPECT_TRUE(ConstrainMove(plan, Vec2(1, 2), Vec2(3, 2)).isApprox(Vec2(1.49, 2), kTol));
}

TEST(ConstrainMove, DoesNotPushAnAgentOutOfAnObstacleThroughAWall) {
  // Pillar centre (3.8, 2), radius 0.3, protruding 0.1 m through the east wall x = 4. The move
  // (3,2) -> (3.9,2) enters the pillar at x = 3.5 and stops at 3.49, inside the room.
  const FloorPlan plan(SquareWalls(), {{Vec2(3.8, 2), 0.3, "half column"}});

  const Vec2 result = ConstrainMove(plan, Vec2(3, 2), Vec2(3.9, 2));

  EXPECT_TRUE(plan.Encloses(result)) << "result (" << result.x() << ", " << result.y() << ")";
  EXPECT_FALSE(plan.InsideObstacle(result));
  EXPECT_TRUE(result.isApprox(Vec2(3.49, 2), kTol));
}

}  // namespace
}  // namespace mirage::geometry
