// SPDX-License-Identifier: MIT
// Golden visibility of virtual anchors in a 4 m x 4 m square room, in the style of
// pyroomacoustics's tests/test_visibility_shoebox2d.py (STYLE.md Sec. 7).
#include "mirage/geometry/visibility.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace mirage::geometry {
namespace {

// Walls counter-clockwise from (0,0): 0 south y = 0, 1 east x = 4, 2 north y = 4, 3 west x = 0.
std::vector<Wall> SquareWalls() {
  return {{Vec2(0, 0), Vec2(4, 0), 0.9, "south"},
          {Vec2(4, 0), Vec2(4, 4), 0.8, "east"},
          {Vec2(4, 4), Vec2(0, 4), 0.5, "north"},
          {Vec2(0, 4), Vec2(0, 0), 0.3, "west"}};
}

const Vec2 kAnchor(1.0, 1.5);
// The agent position of most golden values.
const Vec2 kAgent(3.0, 3.0);

VirtualAnchorSet Generate(const FloorPlan& plan, int max_order) {
  const std::vector<Vec2> anchors{kAnchor};
  return VirtualAnchorSet::Generate(anchors, plan, max_order);
}

// Id of the VA of anchor 0 with exactly this wall sequence; fails the test if there is none.
int IdOf(const VirtualAnchorSet& vas, const std::vector<int>& walls) {
  for (const auto& va : vas.all()) {
    if (va.anchor_index == 0 && va.walls == walls) return va.id;
  }
  ADD_FAILURE() << "no VA with the given walls";
  return 0;
}

std::vector<int> SortedIds(const VirtualAnchorSet& vas, const std::vector<std::vector<int>>& wall_sequences) {
  std::vector<int> ids;
  for (const auto& walls : wall_sequences) ids.push_back(IdOf(vas, walls));
  std::sort(ids.begin(), ids.end());
  return ids;
}

void ExpectPointsNear(const std::vector<Vec2>& actual, const std::vector<Vec2>& expected, double tol) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR((actual[i] - expected[i]).norm(), 0.0, tol)
        << "point " << i << ": (" << actual[i].x() << ", " << actual[i].y() << ") instead of (" << expected[i].x()
        << ", " << expected[i].y() << ")";
  }
}

double PolylineLengthOf(const std::vector<Vec2>& points) {
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
  return length;
}

// ---------------------------------------------------------------------------------------------
// Empty square room
// ---------------------------------------------------------------------------------------------

TEST(Visibility, SeesTheAnchorAndEveryFirstOrderVaFromEveryInteriorPointOfAnEmptySquare) {
  // A convex empty room: the straight line from an interior agent to an order-1 VA always leaves
  // through the VA's wall, and the leg from there to the anchor stays inside.
  const FloorPlan plan(SquareWalls(), {});
  const auto vas = Generate(plan, 1);
  const std::vector<int> all{0, 1, 2, 3, 4};

  for (double x = 0.25; x < 4.0; x += 0.5) {
    for (double y = 0.25; y < 4.0; y += 0.5) {
      EXPECT_EQ(VisibleVirtualAnchors(vas, 0, plan, Vec2(x, y)), all) << "agent (" << x << ", " << y << ")";
    }
  }
}

TEST(Visibility, SeesExactlyEightSecondOrderVasFromEveryGenericInteriorPointOfAnEmptySquare) {
  // The 4 double bounces between parallel walls ({0,2}, {2,0}, {1,3}, {3,1}) are always visible:
  // the line agent -> VA crosses the far wall between the agent's and the VA's x (or y), both in
  // [0,4]. Of the two images of a corner ({0,1} and {1,0} both at (7,-1.5)) exactly one is
  // visible: the line agent -> image leaves through one of the two walls, and only the sequence
  // whose last wall it is traces back. So 1 + 4 + (4 + 4) = 13 VAs; no grid point lies on a line
  // from a corner to its image (which would make both visible).
  const FloorPlan plan(SquareWalls(), {});
  const auto vas = Generate(plan, 2);

  for (double x = 0.25; x < 4.0; x += 0.5) {
    for (double y = 0.25; y < 4.0; y += 0.5) {
      const Vec2 agent(x, y);
      EXPECT_EQ(VisibleVirtualAnchors(vas, 0, plan, agent).size(), 13u) << "agent (" << x << ", " << y << ")";
      for (const auto& walls : {std::vector<int>{0, 2}, {2, 0}, {1, 3}, {3, 1}}) {
        EXPECT_TRUE(IsVisible(vas, IdOf(vas, walls), plan, agent));
      }
      EXPECT_NE(IsVisible(vas, IdOf(vas, {0, 1}), plan, agent), IsVisible(vas, IdOf(vas, {1, 0}), plan, agent));
      EXPECT_NE(IsVisible(vas, IdOf(vas, {2, 3}), plan, agent), IsVisible(vas, IdOf(vas, {3, 2}), plan, agent));
    }
  }
}

TEST(Visibility, ListsTheGoldenSecondOrderVasVisibleFromThreeThree) {
  // Hand trace from (3,3) (ray to the VA, its intersection with the last wall, then towards the
  // parent):
  //   {0,1} (7,-1.5): x = 4 at y = 1.875, then to (1,-1.5): y = 0 at x = 7/3    -> visible
  //   {1,0} (7,-1.5): y = 0 at x = 17/3 > 4                                     -> hidden
  //   {0,2} (1, 9.5): y = 4 at x = 35/13, then y = 0 at x = 19/13               -> visible
  //   {0,3} (-1,-1.5): x = 0 at y = -0.375 < 0                                  -> hidden
  //   {3,0} (-1,-1.5): y = 0 at x = 1/3, then x = 0 at y = 0.375                -> visible
  //   {1,2} (7, 6.5): y = 4 at x = 4.14 > 4                                     -> hidden
  //   {2,1} (7, 6.5): x = 4 at y = 3.875, then y = 4 at x = 3.857               -> visible
  //   {1,3} (-7,1.5): x = 0 at y = 2.55, then x = 4 at y = 1.95                 -> visible
  //   {3,1} (9, 1.5): x = 4 at y = 2.75, then x = 0 at y = 1.75                 -> visible
  //   {2,0} (1,-6.5): y = 0 at x = 2.368, then y = 4 at x = 1.526               -> visible
  //   {2,3} (-1,6.5): x = 0 at y = 5.625 > 4                                    -> hidden
  //   {3,2} (-1,6.5): y = 4 at x = 13/7, then x = 0 at y = 2.375                -> visible
  const FloorPlan plan(SquareWalls(), {});
  const auto vas = Generate(plan, 2);
  const auto expected = SortedIds(vas, {{}, {0}, {1}, {2}, {3}, {0, 1}, {0, 2}, {3, 0}, {2, 1}, {1, 3}, {3, 1}, {2, 0}, {3, 2}});

  const auto visible = VisibleVirtualAnchors(vas, 0, plan, kAgent);

  EXPECT_EQ(visible, expected);
  for (const auto& hidden : {std::vector<int>{1, 0}, {0, 3}, {1, 2}, {2, 3}}) {
    EXPECT_FALSE(IsVisible(vas, IdOf(vas, hidden), plan, kAgent));
    EXPECT_FALSE(TraceVirtualAnchor(vas, IdOf(vas, hidden), plan, kAgent).has_value());
  }
}

TEST(Visibility, SwapsWhichCornerImageIsVisibleWhenTheAgentMoves) {
  // From (2, 0.2) the line to (7,-1.5) leaves through the south wall at x = 44/17, so {1,0} is
  // visible and {0,1} (x = 4 reached at y = -0.48) is hidden, the reverse of (3,3).
  const FloorPlan plan(SquareWalls(), {});
  const auto vas = Generate(plan, 2);
  const Vec2 agent(2.0, 0.2);

  EXPECT_TRUE(IsVisible(vas, IdOf(vas, {1, 0}), plan, agent));
  EXPECT_FALSE(IsVisible(vas, IdOf(vas, {0, 1}), plan, agent));
  EXPECT_FALSE(IsVisible(vas, IdOf(vas, {1, 0}), plan, kAgent));
  EXPECT_TRUE(IsVisible(vas, IdOf(vas, {0, 1}), plan, kAgent));
}

TEST(Visibility, TracesTheLineOfSightFromAgentToAnchor) {
  const FloorPlan plan(SquareWalls(), {});
  const auto vas = Generate(plan, 2);

  const auto path = TraceVirtualAnchor(vas, 0, plan, kAgent);

  ASSERT_TRUE(path.has_value());
  ExpectPointsNear(path->points_m, {kAgent, kAnchor}, 1e-12);
  EXPECT_NEAR(path->length_m, 2.5, 1e-12);  // |(2, 1.5)| = 2.5
}

TEST(Visibility, TracesGoldenFirstOrderReflectionPoints) {
  // From (3,3) to each order-1 VA, intersected with its wall:
  //   south (1,-1.5): y = 0 at t = 2/3 -> (5/3, 0);   east (7,1.5): x = 4 at t = 1/4 -> (4, 2.625)
  //   north (1, 6.5): y = 4 at t = 2/7 -> (17/7, 4);  west (-1,1.5): x = 0 at t = 3/4 -> (0, 1.875)
  const FloorPlan plan(SquareWalls(), {});
  const auto vas = Generate(plan, 1);
  struct Case {
    int wall;
    Vec2 reflection;
    double length;
  };
  const std::vector<Case> cases{{0, Vec2(5.0 / 3.0, 0), std::sqrt(4.0 + 20.25)},
                                {1, Vec2(4, 2.625), std::sqrt(16.0 + 2.25)},
                                {2, Vec2(17.0 / 7.0, 4), std::sqrt(4.0 + 12.25)},
                                {3, Vec2(0, 1.875), std::sqrt(16.0 + 2.25)}};

  for (const auto& c : cases) {
    const auto path = TraceVirtualAnchor(vas, IdOf(vas, {c.wall}), plan, kAgent);
    ASSERT_TRUE(path.has_value()) << "wall " << c.wall;
    ExpectPointsNear(path->points_m, {kAgent, c.reflection, kAnchor}, 1e-12);
    EXPECT_NEAR(path->length_m, c.length, 1e-12) << "wall " << c.wall;
    EXPECT_NEAR(PolylineLengthOf(path->points_m), path->length_m, 1e-12) << "wall " << c.wall;
  }
}

TEST(Visibility, TracesGoldenSecondOrderReflectionPointsFromTheAgentBackToTheAnchor) {
  // {0,1} from (3,3): bounce on the east wall (last) at (4, 1.875), then on the south wall at
  // (7/3, 0). Points run agent, w_k = east, w_1 = south, anchor. Length |(3,3) - (7,-1.5)| =
  // sqrt(16 + 20.25).
  const FloorPlan plan(SquareWalls(), {});
  const auto vas = Generate(plan, 2);

  const auto path = TraceVirtualAnchor(vas, IdOf(vas, {0, 1}), plan, kAgent);

  ASSERT_TRUE(path.has_value());
  ExpectPointsNear(path->points_m, {kAgent, Vec2(4, 1.875), Vec2(7.0 / 3.0, 0), kAnchor}, 1e-12);
  EXPECT_NEAR(path->length_m, std::sqrt(36.25), 1e-12);
  EXPECT_NEAR(PolylineLengthOf(path->points_m), path->length_m, 1e-12);
}

TEST(Visibility, TracesTheOtherCornerImageFromAnotherAgent) {
  // {1,0} from (2, 0.2): south wall at t = 0.2/1.7 -> (44/17, 0); then towards (7, 1.5): x = 4 at
  // t = 24/75 -> (4, 0.48). Length |(2,0.2) - (7,-1.5)| = sqrt(25 + 2.89).
  const FloorPlan plan(SquareWalls(), {});
  const auto vas = Generate(plan, 2);
  const Vec2 agent(2.0, 0.2);

  const auto path = TraceVirtualAnchor(vas, IdOf(vas, {1, 0}), plan, agent);

  ASSERT_TRUE(path.has_value());
  ExpectPointsNear(path->points_m, {agent, Vec2(44.0 / 17.0, 0), Vec2(4, 0.48), kAnchor}, 1e-12);
  EXPECT_NEAR(path->length_m, std::sqrt(27.89), 1e-12);
  EXPECT_NEAR(PolylineLengthOf(path->points_m), path->length_m, 1e-12);
}

TEST(Visibility, TracesAThirdOrderPathOverThreeWalls) {
  // {0,1,2} at (7, 9.5) from (2,3): north wall at t = 1/6.5 -> (36/13, 4); towards (7,-1.5): east
  // wall at t = 16/55 -> (4, 2.4); towards (1,-1.5): south wall at t = 8/13 -> (28/13, 0).
  // Length |(2,3) - (7,9.5)| = sqrt(25 + 42.25).
  const FloorPlan plan(SquareWalls(), {});
  const auto vas = Generate(plan, 3);
  const Vec2 agent(2.0, 3.0);
  const int id = IdOf(vas, {0, 1, 2});

  const auto path = TraceVirtualAnchor(vas, id, plan, agent);

  ASSERT_TRUE(path.has_value());
  ExpectPointsNear(path->points_m, {agent, Vec2(36.0 / 13.0, 4), Vec2(4, 2.4), Vec2(28.0 / 13.0, 0), kAnchor}, 1e-12);
  EXPECT_NEAR(path->length_m, std::sqrt(67.25), 1e-12);
  EXPECT_NEAR(PolylineLengthOf(path->points_m), path->length_m, 1e-12);
  EXPECT_TRUE(IsVisible(vas, id, plan, agent));
  // Order 3 is cut off below it.
  const auto up_to_2 = VisibleVirtualAnchors(vas, 0, plan, agent, 2);
  EXPECT_EQ(std::count(up_to_2.begin(), up_to_2.end(), id), 0);
  const auto up_to_3 = VisibleVirtualAnchors(vas, 0, plan, agent, 3);
  EXPECT_EQ(std::count(up_to_3.begin(), up_to_3.end(), id), 1);
}

TEST(Visibility, TracesAThirdOrderPathOverEastNorthAndWest) {
  // {1,2,3}: anchor -> east (7,1.5) -> north (7,6.5) -> west (-7,6.5). From (2,3) towards
  // (-7,6.5): x = 0 at t = 2/9, y = 3 + 3.5 * 2/9 = 34/9. Towards (7,6.5): y = 4 at t = 4/49,
  // x = 4/7. Towards (7,1.5): x = 4 at t = 8/15, y = 4 - 2.5 * 8/15 = 8/3.
  // Length |(2,3) - (-7,6.5)| = sqrt(81 + 12.25).
  const FloorPlan plan(SquareWalls(), {});
  const auto vas = Generate(plan, 3);
  const Vec2 agent(2.0, 3.0);
  const int id = IdOf(vas, {1, 2, 3});
  ASSERT_NEAR((vas[id].position_m - Vec2(-7, 6.5)).norm(), 0.0, 1e-12);

  const auto path = TraceVirtualAnchor(vas, id, plan, agent);

  ASSERT_TRUE(path.has_value());
  ExpectPointsNear(path->points_m, {agent, Vec2(0, 34.0 / 9.0), Vec2(4.0 / 7.0, 4), Vec2(4, 8.0 / 3.0), kAnchor},
                   1e-12);
  EXPECT_NEAR(path->length_m, std::sqrt(93.25), 1e-12);
  EXPECT_NEAR(PolylineLengthOf(path->points_m), path->length_m, 1e-12);
}

TEST(Visibility, HidesAThirdOrderVaWhoseRayNeverReachesItsLastWall) {
  // {0,1,0}: (7,-1.5) mirrored back at y = 0 -> (7, 1.5). From (2,3) the ray towards (7,1.5)
  // would reach y = 0 only at t = 2 > 1, so it never meets the south wall.
  const FloorPlan plan(SquareWalls(), {});
  const auto vas = Generate(plan, 3);
  const int id = IdOf(vas, {0, 1, 0});

  EXPECT_FALSE(IsVisible(vas, id, plan, Vec2(2.0, 3.0)));
  EXPECT_FALSE(TraceVirtualAnchor(vas, id, plan, Vec2(2.0, 3.0)).has_value());
}

TEST(Visibility, CutsTheVisibleListAtTheRequestedMaximumOrder) {
  const FloorPlan plan(SquareWalls(), {});
  const auto vas2 = Generate(plan, 2);
  const auto vas3 = Generate(plan, 3);

  EXPECT_EQ(VisibleVirtualAnchors(vas2, 0, plan, kAgent, 0), std::vector<int>{0});
  EXPECT_EQ(VisibleVirtualAnchors(vas2, 0, plan, kAgent, 1), (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(VisibleVirtualAnchors(vas2, 0, plan, kAgent, 2).size(), 13u);
  EXPECT_EQ(VisibleVirtualAnchors(vas2, 0, plan, kAgent).size(), 13u);
  // The same VAs in a set generated to order 3 and cut at 2.
  EXPECT_EQ(VisibleVirtualAnchors(vas3, 0, plan, kAgent, 2), VisibleVirtualAnchors(vas2, 0, plan, kAgent));
  EXPECT_GT(VisibleVirtualAnchors(vas3, 0, plan, kAgent).size(), 13u);
}

// ---------------------------------------------------------------------------------------------
// Obstructions
// ---------------------------------------------------------------------------------------------

TEST(Visibility, APillarBlocksTheLineOfSightAndTheReflectionsItsDiscCrosses) {
  // Pillar at (2, 2.25), the midpoint of the LOS (3,3)-(1,1.5), radius 0.4. Distances of the
  // centre from the legs (hand-computed, cross product over length):
  //   LOS 0; east leg (4,2.625)-(1,1.5): 1.125/3.204 = 0.351; west leg (3,3)-(0,1.875): 0.351
  //   -> blocked; north leg (17/7,4)-(1,1.5): (10/7)/2.879 = 0.496; south leg (3,3)-(5/3,0):
  //   2/3.283 = 0.609 -> clear.
  const FloorPlan plan(SquareWalls(), {{Vec2(2.0, 2.25), 0.4, "pillar"}});
  const auto vas = Generate(plan, 2);

  const auto visible = VisibleVirtualAnchors(vas, 0, plan, kAgent, 1);

  EXPECT_EQ(visible, SortedIds(vas, {{0}, {2}}));
  EXPECT_FALSE(TraceVirtualAnchor(vas, 0, plan, kAgent).has_value());
  // {0,1} keeps clear of the pillar (its legs pass >= 1.2 m away).
  EXPECT_TRUE(IsVisible(vas, IdOf(vas, {0, 1}), plan, kAgent));
}

TEST(Visibility, AnInteriorWallStubBlocksOneReflectionAndReflectsItself) {
  // Stub (2,1)-(3,1) (wall 4). From (3,3), the south leg (3,3)-(5/3,0) crosses y = 1 at
  // x = 3 - (4/3)(2/3) = 2.11, on the stub -> blocked. The LOS and the other legs stay at y >= 1.5.
  // The stub's own VA is (1, 0.5); from (3,3) its ray meets y = 1 at x = 1.4, off the stub.
  std::vector<Wall> walls = SquareWalls();
  walls.push_back({Vec2(2, 1), Vec2(3, 1), 0.6, "stub"});
  const FloorPlan plan(walls, {});
  const auto vas = Generate(plan, 1);

  EXPECT_EQ(VisibleVirtualAnchors(vas, 0, plan, kAgent), SortedIds(vas, {{}, {1}, {2}, {3}}));

  // From (3.5, 1.5) the stub reflection exists: towards (1, 0.5), y = 1 at t = 0.5, x = 2.25.
  const Vec2 agent(3.5, 1.5);
  const auto path = TraceVirtualAnchor(vas, IdOf(vas, {4}), plan, agent);
  ASSERT_TRUE(path.has_value());
  ExpectPointsNear(path->points_m, {agent, Vec2(2.25, 1), kAnchor}, 1e-12);
  EXPECT_NEAR(path->length_m, std::sqrt(7.25), 1e-12);
}

// ---------------------------------------------------------------------------------------------
// 3-D and degenerate cases
// ---------------------------------------------------------------------------------------------

// The anchor and the agent of the golden values, at 2.5 m and 1.0 m.
const Vec3 kTallAnchor(1.0, 1.5, 2.5);
const Vec3 kSeatedAgent(3.0, 3.0, 1.0);

VirtualAnchorSet GenerateTall(const FloorPlan& plan, int max_order) {
  const std::vector<Vec3> anchors{kTallAnchor};
  return VirtualAnchorSet::Generate(anchors, plan, max_order);
}

TEST(Visibility, TracesGoldenReflectionHeightsIn3D) {
  // South wall: the reflection (5/3, 0) lies 2/3 along the unfolded path, at 1.0 + 2/3 * 1.5 =
  // 2.0 m. {0,1}: (4, 1.875) at 1/4 and (7/3, 0) at 2/3 of it (hand traced above): 1.375 m and
  // 2.0 m. Lengths sqrt(24.25 + 2.25), sqrt(36.25 + 2.25).
  const FloorPlan plan(SquareWalls(), {}, 0.0, 3.0);
  const auto vas = GenerateTall(plan, 2);

  const auto south = TraceVirtualAnchor(vas, IdOf(vas, {0}), plan, kSeatedAgent);
  const auto corner = TraceVirtualAnchor(vas, IdOf(vas, {0, 1}), plan, kSeatedAgent);

  ASSERT_TRUE(south.has_value());
  ASSERT_EQ(south->points_m.size(), 3u);
  EXPECT_NEAR((south->points_m[1] - Vec3(5.0 / 3.0, 0, 2.0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(south->points_m[0], kSeatedAgent);
  EXPECT_EQ(south->points_m[2], kTallAnchor);
  EXPECT_NEAR(south->length_m, std::sqrt(26.5), 1e-12);
  ASSERT_TRUE(corner.has_value());
  ASSERT_EQ(corner->points_m.size(), 4u);
  EXPECT_NEAR((corner->points_m[1] - Vec3(4, 1.875, 1.375)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((corner->points_m[2] - Vec3(7.0 / 3.0, 0, 2.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(corner->length_m, std::sqrt(38.5), 1e-12);
}

TEST(Visibility, HidesA3DReflectionAboveTheCeilingButNotTheLineOfSight) {
  // The same paths under a 1.9 m ceiling: both reach 2.0 m, the LOS has no reflection point.
  const FloorPlan low(SquareWalls(), {}, 0.0, 1.9);
  const auto vas = GenerateTall(low, 2);

  EXPECT_FALSE(TraceVirtualAnchor(vas, IdOf(vas, {0}), low, kSeatedAgent).has_value());
  EXPECT_FALSE(TraceVirtualAnchor(vas, IdOf(vas, {0, 1}), low, kSeatedAgent).has_value());
  EXPECT_TRUE(TraceVirtualAnchor(vas, 0, low, kSeatedAgent).has_value());
  // The planar trace knows no heights.
  EXPECT_TRUE(IsVisible(vas, IdOf(vas, {0}), low, Vec2(3.0, 3.0)));
}

TEST(Visibility, Agrees3DWith2DOnWhichVasAreVisibleAndWhere) {
  // With no ceiling, 3-D visibility is planar visibility; the points project onto the 2-D ones.
  const FloorPlan plan(SquareWalls(), {{Vec2(2.0, 2.25), 0.4, "pillar"}});
  const auto vas = GenerateTall(plan, 3);
  for (const Vec2& agent : {kAgent, Vec2(2.0, 0.2), Vec2(3.5, 1.5), Vec2(0.4, 3.6)}) {
    for (int id = 0; id < vas.size(); ++id) {
      const auto flat = TraceVirtualAnchor(vas, id, plan, agent);
      const auto tall = TraceVirtualAnchor(vas, id, plan, Vec3(agent.x(), agent.y(), 0.9));
      ASSERT_EQ(flat.has_value(), tall.has_value()) << "VA " << id;
      if (!flat) continue;
      ASSERT_EQ(flat->points_m.size(), tall->points_m.size());
      for (std::size_t k = 0; k < flat->points_m.size(); ++k) EXPECT_EQ(tall->points_m[k].head<2>(), flat->points_m[k]);
    }
  }
}

TEST(Visibility, GivesAnAgentOnTopOfTheAnchorNoLineOfSight) {
  // A zero-length path does not exist (image_source.h, kOnLineTolerance_m); the reflections do.
  const FloorPlan plan(SquareWalls(), {});
  const auto vas = Generate(plan, 1);

  EXPECT_FALSE(IsVisible(vas, 0, plan, kAnchor));
  EXPECT_TRUE(IsVisible(vas, 0, plan, kAnchor + Vec2(1e-6, 0.0)));
  EXPECT_EQ(VisibleVirtualAnchors(vas, 0, plan, kAnchor), (std::vector<int>{1, 2, 3, 4}));
}

}  // namespace
}  // namespace mirage::geometry
