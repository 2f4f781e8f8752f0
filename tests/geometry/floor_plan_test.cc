// SPDX-License-Identifier: MIT
#include "mirage/geometry/floor_plan.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace mirage::geometry {
namespace {

// 4 m x 4 m room, walls counter-clockwise from (0,0): 0 south, 1 east, 2 north, 3 west.
std::vector<Wall> SquareWalls() {
  return {{Vec2(0, 0), Vec2(4, 0), 0.5, "south"},
          {Vec2(4, 0), Vec2(4, 4), 0.5, "east"},
          {Vec2(4, 4), Vec2(0, 4), 0.5, "north"},
          {Vec2(0, 4), Vec2(0, 0), 0.5, "west"}};
}

FloorPlan SquareRoom(std::vector<CircleObstacle> obstacles = {}) { return FloorPlan(SquareWalls(), std::move(obstacles)); }

// ---------------------------------------------------------------------------------------------
// IsLegClear
// ---------------------------------------------------------------------------------------------

TEST(FloorPlanIsLegClear, ClearsALegInsideAnEmptyRoom) {
  EXPECT_TRUE(SquareRoom().IsLegClear(Vec2(1, 1), Vec2(3, 3)));
}

TEST(FloorPlanIsLegClear, BlocksALegThatCrossesAWall) {
  // (1,1)->(5,1) crosses the east wall x = 4 at t = 3/4.
  EXPECT_FALSE(SquareRoom().IsLegClear(Vec2(1, 1), Vec2(5, 1)));
}

TEST(FloorPlanIsLegClear, IgnoresTheSkippedWallsOnly) {
  const FloorPlan plan = SquareRoom();

  // Skipping the east wall (index 1) as either end's wall clears the leg (1,1)->(5,1).
  EXPECT_TRUE(plan.IsLegClear(Vec2(1, 1), Vec2(5, 1), 1, -1));
  EXPECT_TRUE(plan.IsLegClear(Vec2(1, 1), Vec2(5, 1), -1, 1));
  // Skipping other walls does not.
  EXPECT_FALSE(plan.IsLegClear(Vec2(1, 1), Vec2(5, 1), 0, 2));
  // (1,1)->(5,6) leaves through the north wall at t = 3/5, (3.4, 4) (it meets x = 4 only at
  // y = 4.75, beyond the east wall), so skipping the east wall does not clear it.
  EXPECT_FALSE(plan.IsLegClear(Vec2(1, 1), Vec2(5, 6), 1, -1));
  EXPECT_TRUE(plan.IsLegClear(Vec2(1, 1), Vec2(5, 6), 2, -1));
}

TEST(FloorPlanIsLegClear, ClearsALegEndingOnAWallWithoutSkippingIt) {
  // The leg ends at a reflection point (2,0) on the south wall: crossing at t = 1, inside the
  // 1 nm end tolerance.
  EXPECT_TRUE(SquareRoom().IsLegClear(Vec2(1, 1), Vec2(2, 0)));
  EXPECT_TRUE(SquareRoom().IsLegClear(Vec2(2, 0), Vec2(1, 1)));
}

TEST(FloorPlanIsLegClear, DoesNotBlockALegFromACornerReflectionPointByTheNeighbouringWall) {
  // A reflection on the south wall (index 0) exactly at the corner (4,0): the east wall touches
  // the leg at t = 0, which the end tolerance ignores.
  EXPECT_TRUE(SquareRoom().IsLegClear(Vec2(4, 0), Vec2(2, 2), 0, -1));
}

TEST(FloorPlanIsLegClear, IgnoresACrossingWithin1NanometreOfTheEndsOnly) {
  const FloorPlan plan = SquareRoom();

  // Leg (2,1)->(2,-e): crosses y = 0 at t = 1 / (1 + e), i.e. e (relative) before the end. The
  // leg is ~1 m long, so the tolerance is ~1e-9 in t.
  EXPECT_TRUE(plan.IsLegClear(Vec2(2, 1), Vec2(2, -0.5e-9)));
  EXPECT_FALSE(plan.IsLegClear(Vec2(2, 1), Vec2(2, -3e-9)));
  // The same at the start of the leg: (2,-e)->(2,1) crosses at t = e / (1 + e).
  EXPECT_TRUE(plan.IsLegClear(Vec2(2, -0.5e-9), Vec2(2, 1)));
  EXPECT_FALSE(plan.IsLegClear(Vec2(2, -3e-9), Vec2(2, 1)));
}

TEST(FloorPlanIsLegClear, ScalesTheEndToleranceToMetresNotToTheLegFraction) {
  // A 100 m leg ending 0.5 nm past a wall line: t deficit 5e-12 < 1e-9/100 = 1e-11 -> clear;
  // 3 nm past: 3e-11 > 1e-11 -> blocked. A fixed fraction of 1e-9 would clear both.
  const FloorPlan plan({{Vec2(-1, 0), Vec2(1, 0), 0.5, "line"}}, {});
  EXPECT_TRUE(plan.IsLegClear(Vec2(0, 100), Vec2(0, -0.5e-9)));
  EXPECT_FALSE(plan.IsLegClear(Vec2(0, 100), Vec2(0, -3e-9)));
}

TEST(FloorPlanIsLegClear, BlocksALegThroughAnObstacleEvenWhenWallsAreSkipped) {
  const FloorPlan plan = SquareRoom({{Vec2(2, 2), 0.5, "pillar"}});

  // (1,1)->(3,3) passes through the centre.
  EXPECT_FALSE(plan.IsLegClear(Vec2(1, 1), Vec2(3, 3)));
  EXPECT_FALSE(plan.IsLegClear(Vec2(1, 1), Vec2(3, 3), 0, 1));
  // y = 2.4 passes 0.4 m < 0.5 m from the centre; y = 3 passes 1 m away.
  EXPECT_FALSE(plan.IsLegClear(Vec2(0.5, 2.4), Vec2(3.5, 2.4)));
  EXPECT_TRUE(plan.IsLegClear(Vec2(1, 3), Vec2(3, 3)));
}

TEST(FloorPlanIsLegClear, BlocksALegThroughAnInteriorWallStub) {
  FloorPlan plan({{Vec2(2, 1), Vec2(3, 1), 0.5, "stub"}}, {});

  // (2.5,0.5)->(2.5,1.5) crosses the stub at its middle; (1.5,0.5)->(1.5,1.5) passes beside it.
  EXPECT_FALSE(plan.IsLegClear(Vec2(2.5, 0.5), Vec2(2.5, 1.5)));
  EXPECT_TRUE(plan.IsLegClear(Vec2(1.5, 0.5), Vec2(1.5, 1.5)));
}

// ---------------------------------------------------------------------------------------------
// Encloses
// ---------------------------------------------------------------------------------------------

TEST(FloorPlanEncloses, EnclosesPointsInsideAClosedSquareRoom) {
  const FloorPlan plan = SquareRoom();

  EXPECT_TRUE(plan.Encloses(Vec2(2, 2)));
  EXPECT_TRUE(plan.Encloses(Vec2(0.1, 3.9)));
  EXPECT_TRUE(plan.Encloses(Vec2(3.99, 0.01)));
}

TEST(FloorPlanEncloses, DoesNotEnclosePointsOutsideTheRoom) {
  const FloorPlan plan = SquareRoom();

  EXPECT_FALSE(plan.Encloses(Vec2(5, 2)));
  EXPECT_FALSE(plan.Encloses(Vec2(-1, -1)));
  EXPECT_FALSE(plan.Encloses(Vec2(2, 4.01)));
}

TEST(FloorPlanEncloses, DoesNotEncloseAPointThatSeesOutThroughAGap) {
  // North wall with a 1 m door from x = 1.5 to x = 2.5.
  std::vector<Wall> walls = SquareWalls();
  walls[2] = {Vec2(4, 4), Vec2(2.5, 4), 0.5, "north east part"};
  walls.push_back({Vec2(1.5, 4), Vec2(0, 4), 0.5, "north west part"});
  const FloorPlan plan(walls, {});

  // Close to the door, half the directions escape.
  EXPECT_FALSE(plan.Encloses(Vec2(2, 3.5)));
  // From (2, 0.5) the door spans angles atan2(3.5, +-0.5) = 81.9 ... 98.1 deg; the ray at
  // 2 pi (8 + 0.2371) / 32 = 92.7 deg escapes through it.
  EXPECT_FALSE(plan.Encloses(Vec2(2, 0.5)));
}

TEST(FloorPlanEncloses, EnclosesNothingWithoutWalls) {
  EXPECT_FALSE(FloorPlan().Encloses(Vec2(0, 0)));
}

// ---------------------------------------------------------------------------------------------
// InsideObstacle
// ---------------------------------------------------------------------------------------------

TEST(FloorPlanInsideObstacle, DetectsPointsInsideOrOnAnyObstacle) {
  const FloorPlan plan = SquareRoom({{Vec2(2, 2), 0.5, "pillar"}, {Vec2(1, 3), 0.25, "column"}});

  EXPECT_TRUE(plan.InsideObstacle(Vec2(2, 2)));
  EXPECT_TRUE(plan.InsideObstacle(Vec2(2.5, 2)));  // on the boundary: distance exactly 0.5
  EXPECT_TRUE(plan.InsideObstacle(Vec2(1, 3.2)));  // inside the second obstacle
  EXPECT_FALSE(plan.InsideObstacle(Vec2(2.6, 2)));
  EXPECT_FALSE(plan.InsideObstacle(Vec2(1, 3.3)));
  EXPECT_FALSE(SquareRoom().InsideObstacle(Vec2(2, 2)));
}

// ---------------------------------------------------------------------------------------------
// Heights
// ---------------------------------------------------------------------------------------------

TEST(FloorPlanHeights, DefaultToAFloorAtZeroAndNoCeilingSoThat2DPlansKeepWorking) {
  EXPECT_EQ(SquareRoom().floor_z_m(), 0.0);
  EXPECT_EQ(SquareRoom().ceiling_z_m(), kNoCeiling_m);
  EXPECT_TRUE(std::isinf(FloorPlan().ceiling_z_m()));
}

TEST(FloorPlanHeights, KeepTheGivenFloorAndCeiling) {
  const FloorPlan plan(SquareWalls(), {}, -0.2, 2.8);

  EXPECT_EQ(plan.floor_z_m(), -0.2);
  EXPECT_EQ(plan.ceiling_z_m(), 2.8);
  EXPECT_EQ(plan.walls().size(), 4u);
}

// ---------------------------------------------------------------------------------------------
// Bounds
// ---------------------------------------------------------------------------------------------

TEST(FloorPlanBounds, SpansAllWallEndPointsOfAnLShapedRoom) {
  // L-shaped room shifted by (-1, -2): x in [-1, 5], y in [-2, 5].
  const FloorPlan plan({{Vec2(-1, -2), Vec2(5, -2), 0.5, ""},
                        {Vec2(5, -2), Vec2(5, 1), 0.5, ""},
                        {Vec2(5, 1), Vec2(2, 1), 0.5, ""},
                        {Vec2(2, 1), Vec2(2, 5), 0.5, ""},
                        {Vec2(2, 5), Vec2(-1, 5), 0.5, ""},
                        {Vec2(-1, 5), Vec2(-1, -2), 0.5, ""}},
                       {});

  const auto [lo, hi] = plan.Bounds();

  EXPECT_EQ(lo, Vec2(-1, -2));
  EXPECT_EQ(hi, Vec2(5, 5));
}

TEST(FloorPlanBounds, IgnoresObstacles) {
  const FloorPlan plan = SquareRoom({{Vec2(6, 6), 1.0, "outside pillar"}});

  const auto [lo, hi] = plan.Bounds();

  EXPECT_EQ(lo, Vec2(0, 0));
  EXPECT_EQ(hi, Vec2(4, 4));
}

}  // namespace
}  // namespace mirage::geometry
