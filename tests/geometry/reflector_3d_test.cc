// SPDX-License-Identifier: MIT
// 3-D reflectors: mirroring (involution, distance to the plane, independent of the normal's
// sign); hand-computed shoebox path lengths of orders 1 and 2 and the count of shoebox paths; a
// floor echo's reflection point and the law of reflection at every vertex; partitions that
// block, reflect only inside their rectangle and let a ceiling echo pass over them; repeated
// surfaces; the reflectors of a rectangle plan; the enumeration against tracing each sequence.
#include "mirage/geometry/reflector_3d.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/core/rng.h"
#include "rng_vectors.h"

namespace mirage::geometry {
namespace {

constexpr double kTol = 1e-9;

// Shoebox 10 x 8 x 4 m: floor 0, ceiling 1, y=0 2, x=max 3, y=max 4, x=0 5.
constexpr int kFloor = 0, kCeiling = 1, kWallY0 = 2, kWallXMax = 3, kWallX0 = 5;

Vec3 RandomUnit(core::Rng& rng) {
  return testing::NormalVec3(rng).normalized();
}

// The law of reflection at vertex k of a path: incoming and outgoing directions make equal
// angles with the normal, lie in one plane with it, and the vertex lies on its rectangle.
void ExpectSpecularAt(const Reflector3& r, const Vec3& prev_m, const Vec3& point_m, const Vec3& next_m) {
  const Vec3 n = r.normal();
  const Vec3 to_prev = (prev_m - point_m).normalized();
  const Vec3 to_next = (next_m - point_m).normalized();
  EXPECT_NEAR(std::abs((point_m - r.origin_m).dot(n)), 0.0, 1e-9) << r.name;
  EXPECT_LE(std::abs((point_m - r.origin_m).dot(r.u)), r.u_half_m + 1e-9) << r.name;
  EXPECT_LE(std::abs((point_m - r.origin_m).dot(r.v)), r.v_half_m + 1e-9) << r.name;
  EXPECT_NEAR(to_prev.dot(n), to_next.dot(n), 1e-9) << r.name;                 // equal angles, same side
  EXPECT_NEAR((to_prev - to_prev.dot(n) * n + to_next - to_next.dot(n) * n).norm(), 0.0, 1e-9)  // mirrored
      << r.name;
}

void ExpectSpecularPath(std::span<const Reflector3> reflectors, const SpecularPath3& path) {
  ASSERT_EQ(path.vertices_m.size(), path.surfaces.size() + 2);
  double legs_m = 0.0;
  for (std::size_t k = 0; k + 1 < path.vertices_m.size(); ++k) {
    legs_m += (path.vertices_m[k + 1] - path.vertices_m[k]).norm();
  }
  EXPECT_NEAR(legs_m, path.length_m, 1e-9);
  for (std::size_t k = 0; k < path.surfaces.size(); ++k) {
    ExpectSpecularAt(reflectors[static_cast<std::size_t>(path.surfaces[k])], path.vertices_m[k],
                     path.vertices_m[k + 1], path.vertices_m[k + 2]);
  }
}

TEST(MirrorAtPlane, IsAnInvolutionThatPreservesTheDistanceToThePlane) {
  core::Rng rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    Reflector3 r;
    r.u = RandomUnit(rng);
    r.v = r.u.cross(RandomUnit(rng)).normalized();
    r.origin_m = testing::UniformVec3(rng, Vec3(-5, -5, -5), Vec3(5, 5, 5));
    r.u_half_m = r.v_half_m = 1.0;
    const Vec3 x = testing::UniformVec3(rng, Vec3(-5, -5, -5), Vec3(5, 5, 5));
    const Vec3 image = MirrorAtPlane(r, x);
    const Vec3 n = r.normal();

    EXPECT_NEAR((MirrorAtPlane(r, image) - x).norm(), 0.0, 1e-12);
    EXPECT_NEAR((image - r.origin_m).dot(n), -(x - r.origin_m).dot(n), 1e-12);
    EXPECT_NEAR((0.5 * (x + image) - r.origin_m).dot(n), 0.0, 1e-12);  // the midpoint is on the plane
    EXPECT_NEAR((image - x).cross(n).norm(), 0.0, 1e-12);              // moved along the normal only
    Reflector3 flipped = r;                                             // the normal's sign does not matter
    flipped.v = -r.v;
    EXPECT_NEAR((MirrorAtPlane(flipped, x) - image).norm(), 0.0, 1e-12);
  }
}

TEST(ShoeboxReflectors, ListsFloorCeilingAndTheFourWallsWithOutwardIndependentGeometry) {
  const auto box = ShoeboxReflectors(10, 8, 4, 0.9);
  ASSERT_EQ(box.size(), 6u);
  const std::vector<std::string> names{"floor", "ceiling", "y=0", "x=max", "y=max", "x=0"};
  for (std::size_t i = 0; i < box.size(); ++i) {
    EXPECT_EQ(box[i].name, names[i]);
    EXPECT_DOUBLE_EQ(box[i].reflection_coeff, 0.9);
    EXPECT_NEAR(box[i].u.dot(box[i].v), 0.0, 1e-15);
  }
  EXPECT_NEAR(std::abs(box[kCeiling].normal().z()), 1.0, 1e-15);
  EXPECT_NEAR(box[kCeiling].origin_m.z(), 4.0, 1e-15);
  EXPECT_NEAR(std::abs(box[kWallXMax].normal().x()), 1.0, 1e-15);
  EXPECT_NEAR(box[kWallXMax].origin_m.x(), 10.0, 1e-15);
  EXPECT_NEAR(box[kWallXMax].u_half_m, 4.0, 1e-15);  // along y
  EXPECT_NEAR(box[kWallXMax].v_half_m, 2.0, 1e-15);  // along z
}

TEST(TraceSpecularPath, ShoeboxFirstOrderLengthsEqualTheDistanceToTheMirroredSource) {
  const auto box = ShoeboxReflectors(10, 8, 4);
  const Vec3 tx(2, 3, 1.5), rx(7, 5, 2);
  // Images by hand: floor (2,3,-1.5), ceiling (2,3,6.5), y=0 (2,-3,1.5), x=max (18,3,1.5),
  // y=max (2,13,1.5), x=0 (-2,3,1.5).
  const std::vector<double> squared{41.25, 49.25, 89.25, 125.25, 89.25, 85.25};
  for (int s = 0; s < 6; ++s) {
    const std::vector<int> seq{s};
    const auto path = TraceSpecularPath(box, seq, tx, rx);
    ASSERT_TRUE(path.has_value()) << box[static_cast<std::size_t>(s)].name;
    EXPECT_NEAR(path->length_m, std::sqrt(squared[static_cast<std::size_t>(s)]), kTol);
    EXPECT_NEAR(path->length_m, (rx - MirrorAtPlane(box[static_cast<std::size_t>(s)], tx)).norm(), kTol);
    EXPECT_NEAR((path->image_m - MirrorAtPlane(box[static_cast<std::size_t>(s)], tx)).norm(), 0.0, kTol);
    ExpectSpecularPath(box, *path);
  }
  const auto direct = TraceSpecularPath(box, std::vector<int>{}, tx, rx);
  ASSERT_TRUE(direct.has_value());
  EXPECT_NEAR(direct->length_m, std::sqrt(29.25), kTol);
  EXPECT_EQ(direct->vertices_m.size(), 2u);
}

TEST(TraceSpecularPath, FloorEchoReflectsOnTheFloorAtEqualAngles) {
  const auto box = ShoeboxReflectors(10, 8, 4);
  const Vec3 tx(2, 3, 1.5), rx(7, 5, 2);
  const auto path = TraceSpecularPath(box, std::vector<int>{kFloor}, tx, rx);
  ASSERT_TRUE(path.has_value());
  const Vec3 p = path->vertices_m[1];
  // Similar triangles: the point splits the horizontal run in the ratio 1.5 : 2.
  const Vec3 expected = tx + (1.5 / 3.5) * (rx - tx);
  EXPECT_NEAR(p.z(), 0.0, kTol);
  EXPECT_NEAR(p.x(), expected.x(), kTol);
  EXPECT_NEAR(p.y(), expected.y(), kTol);
  const double in = std::atan2((tx - p).head<2>().norm(), tx.z() - p.z());
  const double out = std::atan2((rx - p).head<2>().norm(), rx.z() - p.z());
  EXPECT_NEAR(in, out, 1e-12);
  EXPECT_EQ(path->vertices_m.front(), tx);
  EXPECT_EQ(path->vertices_m.back(), rx);
}

TEST(TraceSpecularPath, FloorThenWallHasTheLengthOfTheSecondImage) {
  auto box = ShoeboxReflectors(10, 8, 4);
  box[kFloor].reflection_coeff = 0.8;
  box[kWallXMax].reflection_coeff = 0.5;
  const Vec3 tx(2, 3, 1.5), rx(7, 5, 2);
  // floor: (2,3,-1.5); then x=max: (18,3,-1.5); rx - image = (-11, 2, 3.5).
  const auto path = TraceSpecularPath(box, std::vector<int>{kFloor, kWallXMax}, tx, rx);
  ASSERT_TRUE(path.has_value());
  EXPECT_NEAR(path->length_m, std::sqrt(137.25), kTol);
  EXPECT_NEAR((path->image_m - Vec3(18, 3, -1.5)).norm(), 0.0, kTol);
  EXPECT_NEAR(path->vertices_m[1].z(), 0.0, kTol);
  EXPECT_NEAR(path->vertices_m[2].x(), 10.0, kTol);
  EXPECT_DOUBLE_EQ(path->reflection_gain, 0.4);
  ExpectSpecularPath(box, *path);

  // The orthogonal planes commute, so the wall first gives the same image; but the line from rx to
  // it meets z = 0 at x = 7 + 11 * 2 / 3.5 = 13.3, beyond the floor: only one order is physical.
  EXPECT_FALSE(TraceSpecularPath(box, std::vector<int>{kWallXMax, kFloor}, tx, rx).has_value());
  // From a receiver just above the floor, the line meets z = 0 before x = 10: the wall comes first.
  const Vec3 rx_low(5, 5, 0.2);
  EXPECT_FALSE(TraceSpecularPath(box, std::vector<int>{kFloor, kWallXMax}, tx, rx_low).has_value());
  const auto reverse = TraceSpecularPath(box, std::vector<int>{kWallXMax, kFloor}, tx, rx_low);
  ASSERT_TRUE(reverse.has_value());
  EXPECT_NEAR(reverse->length_m, (rx_low - Vec3(18, 3, -1.5)).norm(), kTol);
  EXPECT_NEAR(reverse->vertices_m[1].x(), 10.0, kTol);
  EXPECT_NEAR(reverse->vertices_m[2].z(), 0.0, kTol);
  ExpectSpecularPath(box, *reverse);
}

TEST(TraceSpecularPath, RejectsTheSameSurfaceBackToBackButNotWithOneInBetween) {
  const auto box = ShoeboxReflectors(10, 8, 4);
  const Vec3 tx(2, 3, 1.5), rx(7, 5, 2);
  EXPECT_FALSE(TraceSpecularPath(box, std::vector<int>{kFloor, kFloor}, tx, rx).has_value());
  EXPECT_FALSE(TraceSpecularPath(box, std::vector<int>{kWallX0, kCeiling, kCeiling}, tx, rx).has_value());
  const auto floor_ceiling_floor = TraceSpecularPath(box, std::vector<int>{kFloor, kCeiling, kFloor}, tx, rx);
  ASSERT_TRUE(floor_ceiling_floor.has_value());
  // z: 1.5 -> -1.5 -> 9.5 -> -9.5; rx - image = (5, 2, 11.5).
  EXPECT_NEAR(floor_ceiling_floor->length_m, std::sqrt(25 + 4 + 11.5 * 11.5), kTol);
  ExpectSpecularPath(box, *floor_ceiling_floor);
}

TEST(TraceSpecularPath, APartitionBlocksTheDirectPathAndTheFloorEchoButNotTheCeilingEcho) {
  auto room = ShoeboxReflectors(10, 8, 4);
  room.push_back(VerticalReflector("partition", Vec2(5, 0), Vec2(5, 8), 0.0, 2.0));
  const int partition = 6;
  const Vec3 tx(2, 4, 1), rx(8.5, 4.5, 1.2);
  EXPECT_FALSE(TraceSpecularPath(room, std::vector<int>{}, tx, rx).has_value());
  EXPECT_FALSE(TraceSpecularPath(room, std::vector<int>{kFloor}, tx, rx).has_value());
  const auto ceiling = TraceSpecularPath(room, std::vector<int>{kCeiling}, tx, rx);
  ASSERT_TRUE(ceiling.has_value());
  EXPECT_NEAR(ceiling->length_m, (rx - Vec3(2, 4, 7)).norm(), kTol);
  ExpectSpecularPath(room, *ceiling);
  // Both sides reflect: tx sees its own echo off the partition.
  const auto echo = TraceSpecularPath(room, std::vector<int>{partition}, tx, Vec3(3, 5, 1.5));
  ASSERT_TRUE(echo.has_value());
  EXPECT_NEAR(echo->length_m, (Vec3(3, 5, 1.5) - Vec3(8, 4, 1)).norm(), kTol);
  // Without blocking, the same partition lets the direct path through.
  room[static_cast<std::size_t>(partition)].blocks = false;
  EXPECT_TRUE(TraceSpecularPath(room, std::vector<int>{}, tx, rx).has_value());
}

TEST(TraceSpecularPath, NoPathWhenTheReflectionPointMissesAFinitePartition) {
  // A partition 2 m wide (y in [3, 5]) and 2 m high, alone.
  const std::vector<Reflector3> partition{VerticalReflector("p", Vec2(5, 3), Vec2(5, 5), 0.0, 2.0)};
  const std::vector<int> seq{0};
  const auto inside = TraceSpecularPath(partition, seq, Vec3(3, 4, 1), Vec3(3, 4.5, 1));
  ASSERT_TRUE(inside.has_value());
  EXPECT_NEAR((inside->vertices_m[1] - Vec3(5, 4.25, 1)).norm(), 0.0, kTol);
  EXPECT_FALSE(TraceSpecularPath(partition, seq, Vec3(3, 2, 1), Vec3(3, 2.5, 1)).has_value());      // beside it
  EXPECT_FALSE(TraceSpecularPath(partition, seq, Vec3(3, 4, 2.5), Vec3(3, 4.5, 2.5)).has_value());  // over it
  EXPECT_FALSE(TraceSpecularPath(partition, seq, Vec3(3, 4, 1), Vec3(7, 4.5, 1)).has_value());      // opposite sides
  EXPECT_FALSE(TraceSpecularPath(partition, seq, Vec3(5, 4, 1), Vec3(3, 4.5, 1)).has_value());      // tx on the plane
}

TEST(CrossingFraction, FindsTheCrossingInsideTheRectangleOnly) {
  const Reflector3 table = HorizontalReflector("table", Vec2(2, 2), 0.5, 0.4, 0.75);
  const auto t = CrossingFraction(table, Vec3(2.2, 2.1, 1.75), Vec3(2.2, 2.1, -0.25));
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 0.5, 1e-15);
  EXPECT_FALSE(CrossingFraction(table, Vec3(2.2, 2.5, 1.75), Vec3(2.2, 2.5, -0.25)).has_value());  // y beyond 0.4
  EXPECT_FALSE(CrossingFraction(table, Vec3(2.2, 2.1, 1.75), Vec3(2.2, 2.1, 1.0)).has_value());    // ends above
  EXPECT_FALSE(CrossingFraction(table, Vec3(1, 2, 0.75), Vec3(3, 2, 0.75)).has_value());           // in the plane
  EXPECT_FALSE(CrossingFraction(table, Vec3(2, 2, 0.75), Vec3(2, 2, 0.0)).has_value());            // starts on it
}

TEST(IsSegmentClear, IgnoresSkippedAndNonBlockingReflectors) {
  std::vector<Reflector3> rs{HorizontalReflector("table", Vec2(2, 2), 0.5, 0.5, 0.75),
                             VerticalReflector("p", Vec2(3, 0), Vec2(3, 4), 0.0, 2.0)};
  const Vec3 a(2, 2, 1.5), b(2, 2, 0.2);
  EXPECT_FALSE(IsSegmentClear(rs, a, b));
  EXPECT_TRUE(IsSegmentClear(rs, a, b, 0));
  EXPECT_TRUE(IsSegmentClear(rs, a, b, -1, 0));
  EXPECT_FALSE(IsSegmentClear(rs, Vec3(2, 2, 1), Vec3(4, 2, 1), 0));
  rs[0].blocks = false;
  EXPECT_TRUE(IsSegmentClear(rs, a, b));
}

TEST(SpecularPaths3, ShoeboxHasEveryPathOfOrdersZeroToTwoInOrder) {
  const auto box = ShoeboxReflectors(10, 8, 4);
  const Vec3 tx(2, 3, 1.5), rx(7, 5, 2);
  // In a box, every sequence without a back-to-back repeat gives an image; an image of two
  // parallel surfaces has one path (6), one of two orthogonal surfaces has one path for one of
  // its two orders (12 of 24): 1 + 6 + 6 + 12.
  const auto paths = SpecularPaths3(box, tx, rx, 2);
  ASSERT_EQ(paths.size(), 25u);
  EXPECT_TRUE(paths[0].surfaces.empty());
  EXPECT_EQ(paths[1].surfaces, std::vector<int>{kFloor});
  EXPECT_EQ(paths[7].surfaces, (std::vector<int>{kFloor, kCeiling}));
  auto parallel = [&](int i, int j) {
    return std::abs(box[static_cast<std::size_t>(i)].normal().dot(box[static_cast<std::size_t>(j)].normal())) > 0.5;
  };
  const auto n_parallel = std::count_if(paths.begin(), paths.end(), [&](const SpecularPath3& p) {
    return p.surfaces.size() == 2 && parallel(p.surfaces[0], p.surfaces[1]);
  });
  EXPECT_EQ(n_parallel, 6);
  // Each image of two orthogonal surfaces is reached in exactly one of the two orders.
  for (int a = 0; a < 6; ++a) {
    for (int b = a + 1; b < 6; ++b) {
      if (parallel(a, b)) continue;
      const bool ab = TraceSpecularPath(box, std::vector<int>{a, b}, tx, rx).has_value();
      const bool ba = TraceSpecularPath(box, std::vector<int>{b, a}, tx, rx).has_value();
      EXPECT_NE(ab, ba) << a << " " << b;
    }
  }
  for (std::size_t i = 1; i < paths.size(); ++i) {
    const auto& a = paths[i - 1].surfaces;
    const auto& b = paths[i].surfaces;
    EXPECT_TRUE(a.size() < b.size() || (a.size() == b.size() && a < b));
  }
  EXPECT_EQ(SpecularPaths3(box, tx, rx, 0).size(), 1u);
  EXPECT_EQ(SpecularPaths3(box, tx, rx, 1).size(), 7u);
}

TEST(SpecularPaths3, EqualsTracingEverySequenceInARoomWithPartitionsAndATable) {
  auto room = ShoeboxReflectors(12, 9, 4.5);
  room.push_back(VerticalReflector("partition 1", Vec2(4, 0), Vec2(4, 5), 0.0, 2.0, 0.7));
  room.push_back(VerticalReflector("partition 2", Vec2(8, 9), Vec2(8.5, 5), 0.0, 1.8, 0.7));
  room.push_back(HorizontalReflector("table", Vec2(6, 3), 0.8, 0.5, 0.75, 0.6));
  const int n = static_cast<int>(room.size());
  core::Rng rng(5);
  int found = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3 tx = testing::UniformVec3(rng, Vec3(0.5, 0.5, 0.9), Vec3(11.5, 8.5, 2.5));
    const Vec3 rx = testing::UniformVec3(rng, Vec3(0.5, 0.5, 3.0), Vec3(11.5, 8.5, 4.4));
    const auto paths = SpecularPaths3(room, tx, rx, 3);
    std::vector<SpecularPath3> expected;
    std::vector<int> seq;
    auto push = [&](const std::vector<int>& s) {
      if (auto p = TraceSpecularPath(room, s, tx, rx)) expected.push_back(*p);
    };
    push({});
    for (int a = 0; a < n; ++a) push({a});
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) push({a, b});
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        for (int c = 0; c < n; ++c) push({a, b, c});
    ASSERT_EQ(paths.size(), expected.size());
    for (std::size_t i = 0; i < paths.size(); ++i) {
      EXPECT_EQ(paths[i].surfaces, expected[i].surfaces);
      EXPECT_NEAR(paths[i].length_m, expected[i].length_m, 1e-12);
      double gain = 1.0;
      for (const int s : paths[i].surfaces) gain *= room[static_cast<std::size_t>(s)].reflection_coeff;
      EXPECT_DOUBLE_EQ(paths[i].reflection_gain, gain);
      ExpectSpecularPath(room, paths[i]);
      // Every leg is clear of the blocking reflectors it does not touch.
      for (std::size_t k = 0; k + 1 < paths[i].vertices_m.size(); ++k) {
        const int skip_a = k == 0 ? -1 : paths[i].surfaces[k - 1];
        const int skip_b = k == paths[i].surfaces.size() ? -1 : paths[i].surfaces[k];
        EXPECT_TRUE(IsSegmentClear(room, paths[i].vertices_m[k], paths[i].vertices_m[k + 1], skip_a, skip_b));
      }
    }
    found += static_cast<int>(paths.size());
  }
  EXPECT_GT(found, 20 * 50);  // the partitions leave most of the box's paths
}

TEST(ReflectorsFromPlan, ARectanglePlanGivesFourWallsAFloorAndACeiling) {
  const FloorPlan plan({{Vec2(0, 0), Vec2(10, 0), 0.5, "south"},
                        {Vec2(10, 0), Vec2(10, 8), 0.6, "east"},
                        {Vec2(10, 8), Vec2(0, 8), 0.7, "north"},
                        {Vec2(0, 8), Vec2(0, 0), 0.8, "west"}},
                       {}, 0.0, 4.0);
  const auto rs = ReflectorsFromPlan(plan, 0.9);
  ASSERT_EQ(rs.size(), 6u);
  const std::vector<std::string> names{"W1", "W2", "W3", "W4", "floor", "ceiling"};
  const std::vector<double> coeffs{0.5, 0.6, 0.7, 0.8, 0.9, 0.9};
  for (std::size_t i = 0; i < rs.size(); ++i) {
    EXPECT_EQ(rs[i].name, names[i]);
    EXPECT_DOUBLE_EQ(rs[i].reflection_coeff, coeffs[i]);
  }
  // The same hall as the shoebox: equal first- and second-order lengths, surface by surface.
  const auto box = ShoeboxReflectors(10, 8, 4);
  const std::vector<int> plan_to_box{kWallY0, kWallXMax, 4, kWallX0, kFloor, kCeiling};
  const Vec3 tx(2, 3, 1.5), rx(7, 5, 2);
  for (int a = 0; a < 6; ++a) {
    for (int b = -1; b < 6; ++b) {
      if (a == b) continue;
      std::vector<int> seq_plan{a}, seq_box{plan_to_box[static_cast<std::size_t>(a)]};
      if (b >= 0) {
        seq_plan.push_back(b);
        seq_box.push_back(plan_to_box[static_cast<std::size_t>(b)]);
      }
      const auto p = TraceSpecularPath(rs, seq_plan, tx, rx);
      const auto q = TraceSpecularPath(box, seq_box, tx, rx);
      ASSERT_EQ(p.has_value(), q.has_value());
      if (p) {
        EXPECT_NEAR(p->length_m, q->length_m, kTol);
      }
    }
  }
}

}  // namespace
}  // namespace mirage::geometry
