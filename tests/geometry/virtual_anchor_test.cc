// SPDX-License-Identifier: MIT
// Golden virtual anchors in a 4 m x 4 m square room, in the style of pyroomacoustics's
// tests/test_visibility_shoebox2d.py (STYLE.md Sec. 7).
#include "mirage/geometry/virtual_anchor.h"

#include <vector>

#include <gtest/gtest.h>

namespace mirage::geometry {
namespace {

// Walls counter-clockwise from (0,0), each with its own reflection coefficient:
//   0 south y = 0 (0.9), 1 east x = 4 (0.8), 2 north y = 4 (0.5), 3 west x = 0 (0.3).
constexpr double kGamma[4] = {0.9, 0.8, 0.5, 0.3};

std::vector<Wall> SquareWalls() {
  return {{Vec2(0, 0), Vec2(4, 0), kGamma[0], "south"},
          {Vec2(4, 0), Vec2(4, 4), kGamma[1], "east"},
          {Vec2(4, 4), Vec2(0, 4), kGamma[2], "north"},
          {Vec2(0, 4), Vec2(0, 0), kGamma[3], "west"}};
}

const Vec2 kAnchor(1.0, 1.5);

// The VA of anchor 0 with exactly this wall sequence, or nullptr.
const VirtualAnchor* FindByWalls(const VirtualAnchorSet& vas, const std::vector<int>& walls, int anchor = 0) {
  for (const auto& va : vas.all()) {
    if (va.anchor_index == anchor && va.walls == walls) return &va;
  }
  return nullptr;
}

int CountOrder(const VirtualAnchorSet& vas, int order) {
  int n = 0;
  for (const auto& va : vas.all()) n += va.order == order ? 1 : 0;
  return n;
}

struct Golden {
  std::vector<int> walls;
  Vec2 position_m;
  double gain;
};

TEST(VirtualAnchorSet, HasOnlyThePhysicalAnchorAtOrderZero) {
  const std::vector<Vec2> anchors{kAnchor};
  const auto vas = VirtualAnchorSet::Generate(anchors, FloorPlan(SquareWalls(), {}), 0);

  ASSERT_EQ(vas.size(), 1);
  EXPECT_EQ(vas[0].order, 0);
  EXPECT_EQ(vas[0].parent, -1);
  EXPECT_TRUE(vas[0].walls.empty());
  EXPECT_EQ(vas[0].position_m, kAnchor);
  EXPECT_DOUBLE_EQ(vas[0].reflection_gain, 1.0);
  EXPECT_EQ(vas.max_order(), 0);
}

TEST(VirtualAnchorSet, MirrorsTheAnchorAtEachWallOfASquareRoomAtOrderOne) {
  // Anchor (1, 1.5): y = 0 -> (1, -1.5); x = 4 -> (8 - 1, 1.5) = (7, 1.5);
  // y = 4 -> (1, 8 - 1.5) = (1, 6.5); x = 0 -> (-1, 1.5).
  const std::vector<Golden> golden{{{0}, Vec2(1, -1.5), 0.9},
                                   {{1}, Vec2(7, 1.5), 0.8},
                                   {{2}, Vec2(1, 6.5), 0.5},
                                   {{3}, Vec2(-1, 1.5), 0.3}};
  const std::vector<Vec2> anchors{kAnchor};

  const auto vas = VirtualAnchorSet::Generate(anchors, FloorPlan(SquareWalls(), {}), 1);

  ASSERT_EQ(vas.size(), 5);
  EXPECT_EQ(CountOrder(vas, 1), 4);
  for (const auto& g : golden) {
    const VirtualAnchor* va = FindByWalls(vas, g.walls);
    ASSERT_NE(va, nullptr) << "wall " << g.walls[0];
    EXPECT_EQ(va->order, 1);
    EXPECT_EQ(va->parent, 0);
    EXPECT_EQ(va->anchor_index, 0);
    EXPECT_NEAR((va->position_m - g.position_m).norm(), 0.0, 1e-12) << "wall " << g.walls[0];
    EXPECT_DOUBLE_EQ(va->reflection_gain, g.gain);
  }
}

TEST(VirtualAnchorSet, GeneratesTwelveSecondOrderVasInASquareRoom) {
  // Each of the 4 order-1 VAs is mirrored at the 3 other walls: 4 * 3 = 12. In a square no wall
  // is collinear with another (opposite walls are parallel, not collinear), so the collinearity
  // rule skips nothing, and no VA lies on a wall line (all VA coordinates are in {-7, -1, 1, 7, 9}
  // and {-6.5, -1.5, 1.5, 6.5, 9.5}), so the on-the-line rule skips nothing either.
  const std::vector<Vec2> anchors{kAnchor};

  const auto vas = VirtualAnchorSet::Generate(anchors, FloorPlan(SquareWalls(), {}), 2);

  EXPECT_EQ(vas.size(), 1 + 4 + 12);
  EXPECT_EQ(CountOrder(vas, 2), 12);
  EXPECT_EQ(vas.max_order(), 2);
}

TEST(VirtualAnchorSet, ComputesEverySecondOrderVaOfTheSquareRoom) {
  // walls[0] is the bounce next to the anchor: {0, 1} = mirror at y = 0 first, (1,-1.5), then at
  // x = 4: (7, -1.5). The corner images {0,1} and {1,0} coincide (a 180 deg rotation about the
  // corner) but are different paths.
  const std::vector<Golden> golden{
      {{0, 1}, Vec2(7, -1.5), 0.9 * 0.8},  {{0, 2}, Vec2(1, 9.5), 0.9 * 0.5},   // 8 - (-1.5)
      {{0, 3}, Vec2(-1, -1.5), 0.9 * 0.3}, {{1, 0}, Vec2(7, -1.5), 0.8 * 0.9},  //
      {{1, 2}, Vec2(7, 6.5), 0.8 * 0.5},   {{1, 3}, Vec2(-7, 1.5), 0.8 * 0.3},  // -(7)
      {{2, 0}, Vec2(1, -6.5), 0.5 * 0.9},  {{2, 1}, Vec2(7, 6.5), 0.5 * 0.8},   // -(6.5)
      {{2, 3}, Vec2(-1, 6.5), 0.5 * 0.3},  {{3, 0}, Vec2(-1, -1.5), 0.3 * 0.9},  //
      {{3, 1}, Vec2(9, 1.5), 0.3 * 0.8},   {{3, 2}, Vec2(-1, 6.5), 0.3 * 0.5}};  // 8 - (-1)
  const std::vector<Vec2> anchors{kAnchor};

  const auto vas = VirtualAnchorSet::Generate(anchors, FloorPlan(SquareWalls(), {}), 2);

  for (const auto& g : golden) {
    const VirtualAnchor* va = FindByWalls(vas, g.walls);
    ASSERT_NE(va, nullptr) << "walls " << g.walls[0] << "," << g.walls[1];
    EXPECT_EQ(va->order, 2);
    EXPECT_NEAR((va->position_m - g.position_m).norm(), 0.0, 1e-12) << "walls " << g.walls[0] << "," << g.walls[1];
    EXPECT_NEAR(va->reflection_gain, g.gain, 1e-15);
    // The parent is the order-1 VA of the first bounce.
    const VirtualAnchor* parent = FindByWalls(vas, {g.walls[0]});
    ASSERT_NE(parent, nullptr);
    EXPECT_EQ(va->parent, parent->id);
  }
}

TEST(VirtualAnchorSet, NumbersVasByIdSortedByOrderWithParentsBeforeChildren) {
  const std::vector<Vec2> anchors{kAnchor};

  const auto vas = VirtualAnchorSet::Generate(anchors, FloorPlan(SquareWalls(), {}), 3);

  for (int id = 0; id < vas.size(); ++id) {
    const VirtualAnchor& va = vas[id];
    EXPECT_EQ(va.id, id);
    EXPECT_EQ(static_cast<int>(va.walls.size()), va.order);
    if (id > 0) {
      EXPECT_GE(va.order, vas[id - 1].order);
      ASSERT_GE(va.parent, 0);
      ASSERT_LT(va.parent, id);
      const VirtualAnchor& parent = vas[va.parent];
      EXPECT_EQ(parent.order, va.order - 1);
      // The parent's walls are the child's without its last bounce.
      EXPECT_EQ(parent.walls, std::vector<int>(va.walls.begin(), va.walls.end() - 1));
      EXPECT_NE(va.walls.back(), parent.walls.empty() ? -1 : parent.walls.back());
    }
  }
}

TEST(VirtualAnchorSet, GeneratesThirtySixThirdOrderVasInASquareRoom) {
  // Each of the 12 order-2 VAs is mirrored at the 3 walls other than its last one: 36; total
  // 1 + 4 + 12 + 36 = 53.
  const std::vector<Vec2> anchors{kAnchor};

  const auto vas = VirtualAnchorSet::Generate(anchors, FloorPlan(SquareWalls(), {}), 3);

  EXPECT_EQ(vas.size(), 53);
  EXPECT_EQ(CountOrder(vas, 3), 36);
  // {0,1,2}: (7,-1.5) mirrored at y = 4 -> (7, 9.5), gain 0.9 * 0.8 * 0.5.
  const VirtualAnchor* va = FindByWalls(vas, {0, 1, 2});
  ASSERT_NE(va, nullptr);
  EXPECT_NEAR((va->position_m - Vec2(7, 9.5)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(va->reflection_gain, 0.36, 1e-15);
  // {0,1,0} is allowed (the last wall is 1): (7,-1.5) mirrored at y = 0 -> (7, 1.5).
  const VirtualAnchor* back = FindByWalls(vas, {0, 1, 0});
  ASSERT_NE(back, nullptr);
  EXPECT_NEAR((back->position_m - Vec2(7, 1.5)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(back->reflection_gain, 0.9 * 0.8 * 0.9, 1e-15);
  // {0,0} and {0,1,1} are never generated.
  EXPECT_EQ(FindByWalls(vas, {0, 0}), nullptr);
  EXPECT_EQ(FindByWalls(vas, {0, 1, 1}), nullptr);
}

TEST(VirtualAnchorSet, SkipsMirrorsAtAWallCollinearWithTheGeneratingWall) {
  // The south wall split into two collinear segments 0a = (0,0)-(2,0) and 0b = (2,0)-(4,0):
  // 5 walls. Order 1: 5 VAs (0a and 0b both give (1,-1.5)). Order 2: the VA of 0a is not mirrored
  // at 0b (the image would return to the anchor) and vice versa, so 0a and 0b get 3 children
  // each and east, north, west get 4 each: 3 + 3 + 4 * 3 = 18 instead of 5 * 4 = 20.
  const FloorPlan plan({{Vec2(0, 0), Vec2(2, 0), 0.9, "south a"},
                        {Vec2(2, 0), Vec2(4, 0), 0.9, "south b"},
                        {Vec2(4, 0), Vec2(4, 4), 0.8, "east"},
                        {Vec2(4, 4), Vec2(0, 4), 0.5, "north"},
                        {Vec2(0, 4), Vec2(0, 0), 0.3, "west"}},
                       {});
  const std::vector<Vec2> anchors{kAnchor};

  const auto vas = VirtualAnchorSet::Generate(anchors, plan, 2);

  EXPECT_EQ(CountOrder(vas, 1), 5);
  EXPECT_EQ(CountOrder(vas, 2), 18);
  EXPECT_EQ(FindByWalls(vas, {0, 1}), nullptr);
  EXPECT_EQ(FindByWalls(vas, {1, 0}), nullptr);
  EXPECT_NE(FindByWalls(vas, {0, 2}), nullptr);
  EXPECT_NE(FindByWalls(vas, {1, 3}), nullptr);
}

TEST(VirtualAnchorSet, SkipsMirroringAPointThatLiesOnTheWallLine) {
  // A stub wall (2,1.5)-(3,1.5) on the anchor's own horizontal line y = 1.5: mirroring the
  // anchor there would give the anchor itself, so only the 4 room walls yield order-1 VAs.
  std::vector<Wall> walls = SquareWalls();
  walls.push_back({Vec2(2, 1.5), Vec2(3, 1.5), 0.7, "stub"});
  const std::vector<Vec2> anchors{kAnchor};

  const auto vas = VirtualAnchorSet::Generate(anchors, FloorPlan(walls, {}), 1);

  EXPECT_EQ(CountOrder(vas, 1), 4);
  EXPECT_EQ(FindByWalls(vas, {4}), nullptr);
}

TEST(VirtualAnchorSet, KeepsTheVasOfEachAnchorContiguous) {
  // Two anchors, max order 2: 17 VAs each.
  const std::vector<Vec2> anchors{kAnchor, Vec2(3, 2.5)};

  const auto vas = VirtualAnchorSet::Generate(anchors, FloorPlan(SquareWalls(), {}), 2);

  ASSERT_EQ(vas.anchor_count(), 2);
  ASSERT_EQ(vas.size(), 34);
  const auto first = vas.ForAnchor(0);
  const auto second = vas.ForAnchor(1);
  ASSERT_EQ(first.size(), 17u);
  ASSERT_EQ(second.size(), 17u);
  for (std::size_t i = 0; i < 17; ++i) {
    EXPECT_EQ(first[i], static_cast<int>(i));
    EXPECT_EQ(second[i], static_cast<int>(17 + i));
    EXPECT_EQ(vas[second[i]].anchor_index, 1);
  }
  EXPECT_EQ(vas[second[0]].position_m, Vec2(3, 2.5));
  // Second anchor, west wall: (-3, 2.5); its parent is the second anchor, not the first.
  const VirtualAnchor* west = FindByWalls(vas, {3}, 1);
  ASSERT_NE(west, nullptr);
  EXPECT_NEAR((west->position_m - Vec2(-3, 2.5)).norm(), 0.0, 1e-12);
  EXPECT_EQ(west->parent, 17);
}

// ---------------------------------------------------------------------------------------------
// The VA set as a cache of the image-source engine
// ---------------------------------------------------------------------------------------------

// A pentagon (no parallel walls) with an interior stub collinear with nothing and a wall piece
// collinear with wall 0, so that every generation rule fires.
FloorPlan IrregularPlan() {
  const std::vector<Vec2> corners{Vec2(0, 0), Vec2(6, -0.5), Vec2(7, 4), Vec2(3, 6.5), Vec2(-0.5, 4)};
  std::vector<Wall> walls;
  for (std::size_t i = 0; i < corners.size(); ++i) walls.push_back({corners[i], corners[(i + 1) % corners.size()], 0.5, ""});
  walls.push_back({Vec2(2.0, 1.0), Vec2(3.0, 2.5), 0.6, "stub"});
  walls.push_back({Vec2(-6, 0.5), Vec2(-3, 0.25), 0.7, "collinear with wall 0"});
  return FloorPlan(walls, {});
}

TEST(VirtualAnchorSet, PlacesEveryVaAtTheEnginesImageOfItsAnchorBitForBit) {
  const FloorPlan plan = IrregularPlan();
  const std::vector<Vec2> anchors{Vec2(1.0, 1.5), Vec2(4.5, 3.0)};

  const auto vas = VirtualAnchorSet::Generate(anchors, plan, 3);

  for (const auto& va : vas.all()) {
    const auto images = ImageChain(plan, va.walls, anchors[static_cast<std::size_t>(va.anchor_index)]);
    EXPECT_EQ(images.back(), va.position_m) << "VA " << va.id;
    // Each ancestor is the chain's image of its order.
    const VirtualAnchor* ancestor = &va;
    for (int k = va.order; k > 0; --k) {
      EXPECT_EQ(images[static_cast<std::size_t>(k)], ancestor->position_m);
      ancestor = &vas[ancestor->parent];
    }
  }
}

TEST(VirtualAnchorSet, HoldsExactlyTheSequencesTheEnginesRulesAllow) {
  // Independent enumeration: every sequence up to order 3 whose every mirror passes CanMirror.
  const FloorPlan plan = IrregularPlan();
  const int walls = static_cast<int>(plan.walls().size());
  const std::vector<Vec2> anchors{Vec2(1.0, 1.5)};
  std::vector<std::vector<int>> allowed{{}};
  std::vector<std::pair<std::vector<int>, Vec2>> level{{{}, anchors[0]}};
  for (int order = 1; order <= 3; ++order) {
    std::vector<std::pair<std::vector<int>, Vec2>> next;
    for (const auto& [s, image] : level) {
      for (int w = 0; w < walls; ++w) {
        if (!CanMirror(plan, s.empty() ? -1 : s.back(), w, image)) continue;
        auto t = s;
        t.push_back(w);
        allowed.push_back(t);
        next.emplace_back(t, MirrorAtWall(plan.walls()[static_cast<std::size_t>(w)], image));
      }
    }
    level = next;
  }

  const auto vas = VirtualAnchorSet::Generate(anchors, plan, 3);

  ASSERT_EQ(vas.size(), static_cast<int>(allowed.size()));
  for (std::size_t i = 0; i < allowed.size(); ++i) EXPECT_EQ(vas[static_cast<int>(i)].walls, allowed[i]);
  // The rules did fire: 7 walls would give 1 + 7 + 42 + 252 sequences without immediate repeats.
  EXPECT_LT(vas.size(), 1 + 7 + 42 + 252);
}

TEST(VirtualAnchorSet, GivesEveryVaTheHeightOfItsAnchor) {
  // Vertical walls keep z: every VA of an anchor at 2.5 m is at 2.5 m, in the plane where the
  // planar set puts it.
  const std::vector<Vec3> anchors{Vec3(1.0, 1.5, 2.5), Vec3(3.0, 2.5, 0.8)};
  const std::vector<Vec2> planar{Vec2(1.0, 1.5), Vec2(3.0, 2.5)};

  const auto vas = VirtualAnchorSet::Generate(anchors, FloorPlan(SquareWalls(), {}), 2);
  const auto flat = VirtualAnchorSet::Generate(planar, FloorPlan(SquareWalls(), {}), 2);

  ASSERT_EQ(vas.size(), flat.size());
  for (int id = 0; id < vas.size(); ++id) {
    const double z = anchors[static_cast<std::size_t>(vas[id].anchor_index)].z();
    EXPECT_EQ(vas[id].height_m, z);
    EXPECT_EQ(vas[id].position_m, flat[id].position_m);
    EXPECT_EQ(vas[id].position3_m(), Vec3(flat[id].position_m.x(), flat[id].position_m.y(), z));
    EXPECT_EQ(flat[id].height_m, 0.0);
  }
}

}  // namespace
}  // namespace mirage::geometry
