// SPDX-License-Identifier: MIT
// The image-source engine: mirroring and the generation rules; the trace against an independent
// check (reflection points on their segments obeying the law of reflection, the single-bounce
// point from similar triangles) at seeded random points; the enumeration against brute force;
// the analytic derivatives (2-D and 3-D, wall offsets included) against central differences at
// generic, near-degenerate and seeded random points; the closed forms of Kulmer App. C and
// reciprocity (Eq. 22); heights in 3-D (interpolation, floor, ceiling).
#include "mirage/geometry/image_source.h"

#include <cmath>
#include <functional>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/core/rng.h"
#include "mirage/geometry/segment.h"
#include "rng_vectors.h"

namespace mirage::geometry {
namespace {

// A pentagon with no parallel walls, so that no path is degenerate.
FloorPlan Pentagon(std::vector<CircleObstacle> obstacles = {}) {
  const std::vector<Vec2> corners{Vec2(0, 0), Vec2(6, -0.5), Vec2(7, 4), Vec2(3, 6.5), Vec2(-0.5, 4)};
  std::vector<Wall> walls;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    walls.push_back({corners[i], corners[(i + 1) % corners.size()], 0.5, "wall"});
  }
  return FloorPlan(walls, std::move(obstacles));
}

FloorPlan Rectangle(double width_m, double height_m, double floor_z_m = 0.0, double ceiling_z_m = kNoCeiling_m) {
  return FloorPlan({{Vec2(0, 0), Vec2(width_m, 0), 0.5, "south"},
                    {Vec2(width_m, 0), Vec2(width_m, height_m), 0.5, "east"},
                    {Vec2(width_m, height_m), Vec2(0, height_m), 0.5, "north"},
                    {Vec2(0, height_m), Vec2(0, 0), 0.5, "west"}},
                   {}, floor_z_m, ceiling_z_m);
}

// The plan with wall w moved by delta_m along its normal n = U e.
FloorPlan Shifted(const FloorPlan& plan, int w, double delta_m) {
  auto walls = plan.walls();
  auto& wall = walls[static_cast<std::size_t>(w)];
  const Vec2 e = (wall.end_m - wall.start_m).normalized();
  const Vec2 n(-e.y(), e.x());
  wall.start_m += delta_m * n;
  wall.end_m += delta_m * n;
  return FloorPlan(walls, plan.obstacles(), plan.floor_z_m(), plan.ceiling_z_m());
}

Vec3 At(const Vec2& xy, double z) { return Vec3(xy.x(), xy.y(), z); }

// Every sequence of 0 .. max_order walls without an immediate repeat, in the enumeration's order.
std::vector<WallSequence> AllSequences(int walls, int max_order) {
  std::vector<WallSequence> out{{}};
  std::vector<WallSequence> level{{}};
  for (int order = 1; order <= max_order; ++order) {
    std::vector<WallSequence> next;
    for (const auto& s : level) {
      for (int w = 0; w < walls; ++w) {
        if (!s.empty() && s.back() == w) continue;
        WallSequence t = s;
        t.push_back(w);
        next.push_back(t);
      }
    }
    out.insert(out.end(), next.begin(), next.end());
    level = next;
  }
  return out;
}

// Central differences of a scalar function of a point, coordinate by coordinate.
template <typename Point>
Point Gradient(const std::function<double(const Point&)>& f, const Point& x, double h) {
  Point g = Point::Zero();
  for (int c = 0; c < x.size(); ++c) {
    const Point e = Point::Unit(c) * h;
    g(c) = (f(x + e) - f(x - e)) / (2 * h);
  }
  return g;
}

// d length / d c_w by central differences, for every wall; the analytic value sums the entries of
// the sequence that are w.
template <typename Point, typename Path>
void ExpectOffsetDerivativesMatch(const FloorPlan& plan, const WallSequence& s, const Point& tx, const Point& rx,
                                  const Path& path, double h, double tol) {
  for (int w = 0; w < static_cast<int>(plan.walls().size()); ++w) {
    double analytic = 0.0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (s[i] == w) analytic += path.d_offset[i];
    }
    const double fd = (ComputeImagePath(Shifted(plan, w, h), s, tx, rx).length_m -
                       ComputeImagePath(Shifted(plan, w, -h), s, tx, rx).length_m) /
                      (2 * h);
    EXPECT_NEAR(analytic, fd, tol) << "wall " << w;
  }
}

template <typename Point>
void ExpectDerivativesMatchFiniteDifferences(const FloorPlan& plan, const WallSequence& s, const Point& tx,
                                             const Point& rx, double h = 1e-6, double tol = 1e-6) {
  const auto path = ComputeImagePath(plan, s, tx, rx);
  const std::function<double(const Point&)> of_rx = [&](const Point& r) { return ComputeImagePath(plan, s, tx, r).length_m; };
  const std::function<double(const Point&)> of_tx = [&](const Point& t) { return ComputeImagePath(plan, s, t, rx).length_m; };
  EXPECT_NEAR((path.d_rx - Gradient(of_rx, rx, h)).norm(), 0.0, tol) << "d/d rx, order " << s.size();
  EXPECT_NEAR((path.d_tx - Gradient(of_tx, tx, h)).norm(), 0.0, tol) << "d/d tx, order " << s.size();
  ExpectOffsetDerivativesMatch(plan, s, tx, rx, path, h, tol);
}

// One agent at both ends (self channel): the total derivative d_rx + d_tx.
void ExpectSelfDerivativeMatches(const FloorPlan& plan, const WallSequence& s, const Vec2& p) {
  const ImagePath path = ComputeImagePath(plan, s, p, p);
  const std::function<double(const Vec2&)> length = [&](const Vec2& q) { return ComputeImagePath(plan, s, q, q).length_m; };
  EXPECT_NEAR((path.d_rx + path.d_tx - Gradient(length, p, 1e-6)).norm(), 0.0, 1e-6) << "self, order " << s.size();
}

// ---------------------------------------------------------------------------------------------
// Mirror and generation rules
// ---------------------------------------------------------------------------------------------

TEST(MirrorAtWall, UsesTheOneMirrorFormulaOfMirrorPointBitForBit) {
  const FloorPlan plan = Pentagon();
  core::Rng rng(7, 0);
  for (int trial = 0; trial < 20; ++trial) {
    const Vec2 x = testing::UniformVec2(rng, Vec2(-3.0, -3.0), Vec2(9.0, 9.0));
    for (const Wall& wall : plan.walls()) EXPECT_EQ(MirrorAtWall(wall, x), MirrorPoint(x, wall.start_m, wall.end_m));
  }
}

TEST(MirrorAtWall, MirrorsTheOriginAtTheLine3xPlus4yEquals12AndKeepsTheHeight) {
  // Foot point of the origin on 3x + 4y = 12 is (1.44, 1.92), so the image is (2.88, 3.84).
  const Wall wall{Vec2(4, 0), Vec2(0, 3), 0.5, "oblique"};

  EXPECT_NEAR((MirrorAtWall(wall, Vec2(0, 0)) - Vec2(2.88, 3.84)).norm(), 0.0, 1e-14);
  const Vec3 image = MirrorAtWall(wall, Vec3(0, 0, 1.7));
  EXPECT_NEAR((image - Vec3(2.88, 3.84, 1.7)).norm(), 0.0, 1e-14);
  EXPECT_EQ(image.z(), 1.7);
}

TEST(CanMirror, RejectsTheSameWallACollinearWallAndAPointOnTheWallLine) {
  // South wall split into two collinear pieces 0 and 1, east wall 2, and a stub 3 on y = 1.5.
  const FloorPlan plan({{Vec2(0, 0), Vec2(2, 0), 0.9, "south a"},
                        {Vec2(2, 0), Vec2(4, 0), 0.9, "south b"},
                        {Vec2(4, 0), Vec2(4, 4), 0.8, "east"},
                        {Vec2(2, 1.5), Vec2(3, 1.5), 0.7, "stub"}},
                       {});
  const Vec2 image(1.0, -1.5);  // the anchor (1, 1.5) mirrored at wall 0

  EXPECT_TRUE(CanMirror(plan, -1, 0, Vec2(1.0, 1.5)));
  EXPECT_FALSE(CanMirror(plan, 0, 0, image));  // back to the parent
  EXPECT_FALSE(CanMirror(plan, 0, 1, image));  // collinear: back to the grandparent
  EXPECT_TRUE(CanMirror(plan, 0, 2, image));
  EXPECT_FALSE(CanMirror(plan, -1, 3, Vec2(1.0, 1.5)));         // on the stub's line
  EXPECT_FALSE(CanMirror(plan, -1, 3, Vec2(1.0, 1.5 + 5e-10)));  // within 1 nm of it
  EXPECT_TRUE(CanMirror(plan, -1, 3, Vec2(1.0, 1.5 + 2e-9)));
}

TEST(ImageChain, MirrorsTheSourceWallByWallAndKeepsItsHeightIn3D) {
  // Square 4 m room: (1, 1.5) at the south wall (1, -1.5), then at the east wall (7, -1.5).
  const FloorPlan plan = Rectangle(4.0, 4.0);
  const WallSequence s{0, 1};

  const auto images = ImageChain(plan, s, Vec2(1.0, 1.5));
  const auto images3 = ImageChain(plan, s, Vec3(1.0, 1.5, 2.2));

  ASSERT_EQ(images.size(), 3u);
  EXPECT_EQ(images[0], Vec2(1.0, 1.5));
  EXPECT_NEAR((images[1] - Vec2(1.0, -1.5)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((images[2] - Vec2(7.0, -1.5)).norm(), 0.0, 1e-15);
  ASSERT_EQ(images3.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(images3[k].head<2>(), images[k]);
    EXPECT_EQ(images3[k].z(), 2.2);
  }
}

// ---------------------------------------------------------------------------------------------
// Path length and derivatives
// ---------------------------------------------------------------------------------------------

TEST(ComputeImagePath, DerivativesMatchCentralDifferencesAtSeededRandomPointsUpToThirdOrder) {
  const FloorPlan plan = Pentagon();
  core::Rng rng(1, 0);
  const std::vector<WallSequence> sequences{{}, {0}, {3}, {0, 2}, {4, 1}, {1, 3, 0}, {2, 0, 2}};
  for (int trial = 0; trial < 5; ++trial) {
    const Vec2 tx = testing::UniformVec2(rng, Vec2(1.0, 1.0), Vec2(5.0, 4.0));
    const Vec2 rx = testing::UniformVec2(rng, Vec2(1.0, 1.0), Vec2(5.0, 4.0));
    for (const auto& s : sequences) {
      ExpectDerivativesMatchFiniteDifferences(plan, s, tx, rx);
      if (!s.empty()) ExpectSelfDerivativeMatches(plan, s, tx);
    }
  }
}

TEST(ComputeImagePath, DerivativesMatchCentralDifferencesAtAGenericPoint) {
  const FloorPlan plan = Pentagon();
  for (const WallSequence& s : {WallSequence{}, WallSequence{1}, WallSequence{3, 0}, WallSequence{0, 4, 2}}) {
    ExpectDerivativesMatchFiniteDifferences(plan, s, Vec2(2.3, 1.7), Vec2(4.1, 3.2));
  }
}

TEST(ComputeImagePath, DerivativesMatchCentralDifferencesNearDegeneratePoints) {
  const FloorPlan plan = Pentagon();
  // Transmitter 1 mm from wall 0: its image almost coincides with it.
  const Vec2 near_wall = Vec2(3.0, -0.25) + 1e-3 * WallNormal(plan.walls()[0]);
  ExpectDerivativesMatchFiniteDifferences(plan, {0}, near_wall, Vec2(4.0, 3.0));
  ExpectDerivativesMatchFiniteDifferences(plan, {0, 2}, near_wall, Vec2(4.0, 3.0));
  // Receiver 1 mm from the image: a 1 mm path, where u turns fastest (smaller step).
  const Vec2 tx(2.0, 2.0);
  const Vec2 image = ImageChain(plan, WallSequence{1}, tx).back();
  ExpectDerivativesMatchFiniteDifferences(plan, {1}, tx, Vec2(image + Vec2(6e-4, 8e-4)), 1e-8, 1e-6);
  // 3-D: an almost vertical line of sight (0.1 mm across, 2 m up).
  ExpectDerivativesMatchFiniteDifferences(plan, {}, Vec3(2.0, 2.0, 0.5), Vec3(2.0001, 2.0, 2.5));
  ExpectDerivativesMatchFiniteDifferences(plan, {2}, Vec3(2.0, 2.0, 0.5), Vec3(2.0001, 2.0, 2.5));
}

TEST(ComputeImagePath, DerivativesMatchCentralDifferencesIn3DAtSeededRandomPoints) {
  const FloorPlan plan = Pentagon();
  core::Rng rng(3, 0);
  const std::vector<WallSequence> sequences{{}, {0}, {3}, {0, 2}, {4, 1}, {1, 3, 0}, {2, 0, 2}};
  for (int trial = 0; trial < 5; ++trial) {
    const Vec3 tx = testing::UniformVec3(rng, Vec3(1.0, 1.0, 0.0), Vec3(5.0, 4.0, 3.0));
    const Vec3 rx = testing::UniformVec3(rng, Vec3(1.0, 1.0, 0.0), Vec3(5.0, 4.0, 3.0));
    for (const auto& s : sequences) ExpectDerivativesMatchFiniteDifferences(plan, s, tx, rx);
  }
}

TEST(ComputeImagePath, Gives3DLengthSqrtOfPlanarLengthSquaredPlusHeightDifferenceSquared) {
  const FloorPlan plan = Pentagon();
  const WallSequence s{1, 3};
  const Vec2 tx(2.0, 1.5), rx(4.5, 3.0);
  const ImagePath flat = ComputeImagePath(plan, s, tx, rx);

  const ImagePath3 level = ComputeImagePath(plan, s, At(tx, 1.2), At(rx, 1.2));
  const ImagePath3 slanted = ComputeImagePath(plan, s, At(tx, 0.4), At(rx, 2.4));

  // Equal heights: the 3-D path is the planar one.
  EXPECT_DOUBLE_EQ(level.length_m, flat.length_m);
  EXPECT_EQ(level.image_m, At(flat.image_m, 1.2));
  EXPECT_NEAR((level.d_rx - At(flat.d_rx, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((level.d_tx - At(flat.d_tx, 0.0)).norm(), 0.0, 1e-15);
  for (std::size_t i = 0; i < s.size(); ++i) EXPECT_NEAR(level.d_offset[i], flat.d_offset[i], 1e-15);
  // A height difference of 2 m.
  EXPECT_NEAR(slanted.length_m, std::hypot(flat.length_m, 2.0), 1e-14);
  EXPECT_NEAR(slanted.d_rx.z(), 2.0 / slanted.length_m, 1e-15);
  EXPECT_NEAR(slanted.d_tx.z(), -2.0 / slanted.length_m, 1e-15);
}

TEST(ComputeImagePath, SelfSingleBounceIsTwiceTheWallDistanceWithGradientTwoU) {
  // Kulmer Eq. (26)-(27): tau = |2 T_s (p - p_s)| / c; d/dp = 2 xi, d/dp_s = -2 xi.
  const FloorPlan room = Rectangle(5.0, 4.0);
  const Vec2 p(1.2, 2.5);
  const ImagePath south = ComputeImagePath(room, WallSequence{0}, p, p);
  EXPECT_NEAR(south.length_m, 2 * 2.5, 1e-12);
  const Vec2 total = south.d_rx + south.d_tx;
  EXPECT_NEAR(total.x(), 0.0, 1e-12);
  EXPECT_NEAR(total.y(), 2.0, 1e-12);  // moving away from the south wall lengthens by 2 per metre
  // The south wall's normal U e = U (1, 0) = (0, 1) points into the room: moving the wall by +1
  // towards the agent shortens the path by 2.
  EXPECT_NEAR(south.d_offset[0], -2.0, 1e-12);
}

TEST(ComputeImagePath, SelfBounceBetweenParallelWallsDoesNotDependOnThePosition) {
  // App. C: tau_parallel = |2 T_1 p_1 - 2 T_j p_j| / c, independent of the agent: useless for
  // positioning, informative about the walls.
  const FloorPlan room = Rectangle(5.0, 4.0);
  for (const Vec2& p : {Vec2(1.0, 1.0), Vec2(3.7, 2.2)}) {
    const ImagePath path = ComputeImagePath(room, WallSequence{0, 2}, p, p);
    EXPECT_NEAR(path.length_m, 2 * 4.0, 1e-12);
    EXPECT_NEAR((path.d_rx + path.d_tx).norm(), 0.0, 1e-12);
    EXPECT_TRUE(TraceImagePath(room, WallSequence{0, 2}, p, p).has_value());
  }
}

TEST(ComputeImagePath, RelativeLosGradientsAreOppositeUnitVectors) {
  // Eq. (29).
  const FloorPlan room = Rectangle(5.0, 4.0);
  const ImagePath los = ComputeImagePath(room, WallSequence{}, Vec2(1, 1), Vec2(4, 5));
  EXPECT_NEAR(los.length_m, 5.0, 1e-12);
  EXPECT_NEAR((los.d_rx - Vec2(0.6, 0.8)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((los.d_tx + los.d_rx).norm(), 0.0, 1e-12);
}

TEST(ComputeImagePath, ReciprocityReversesTheSequence) {
  // App. B, Eq. (21)-(25).
  const FloorPlan plan = Pentagon();
  const Vec2 a(1.5, 1.0), b(4.5, 3.5);
  for (const WallSequence& s : {WallSequence{0, 2}, WallSequence{1, 3, 0}, WallSequence{4}}) {
    const ImagePath forward = ComputeImagePath(plan, s, a, b);
    const ImagePath backward = ComputeImagePath(plan, Reversed(s), b, a);
    EXPECT_NEAR(forward.length_m, backward.length_m, 1e-12);
    EXPECT_NEAR((forward.d_tx - backward.d_rx).norm(), 0.0, 1e-12);
    EXPECT_EQ(TraceImagePath(plan, s, a, b).has_value(), TraceImagePath(plan, Reversed(s), b, a).has_value());
  }
}

// ---------------------------------------------------------------------------------------------
// Trace
// ---------------------------------------------------------------------------------------------

TEST(TraceImagePath, PutsEveryReflectionPointOnItsSegmentObeyingTheLawOfReflection) {
  // Independent of the images: at each reflection point the outgoing direction is the incoming
  // one mirrored at the wall (d_out = d_in - 2 (n^T d_in) n), both neighbours lie on the same
  // side of the wall, and the polyline is as long as the image-source length. Seeded random
  // points in a pentagon with a pillar, every sequence up to order 3.
  const FloorPlan plan = Pentagon({{Vec2(3.5, 2.0), 0.3, "pillar"}});
  core::Rng rng(11, 0);
  int traced = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const Vec2 tx = testing::UniformVec2(rng, Vec2(0.5, 0.5), Vec2(6.0, 4.0));
    const Vec2 rx = testing::UniformVec2(rng, Vec2(0.5, 0.5), Vec2(6.0, 4.0));
    if (plan.InsideObstacle(tx) || plan.InsideObstacle(rx)) continue;
    for (const auto& s : AllSequences(5, 3)) {
      const auto points = TraceImagePath(plan, s, tx, rx);
      if (!points) continue;
      ++traced;
      ASSERT_EQ(points->size(), s.size() + 2);
      EXPECT_EQ(points->front(), tx);
      EXPECT_EQ(points->back(), rx);
      double polyline_m = 0.0;
      for (std::size_t k = 0; k + 1 < points->size(); ++k) polyline_m += ((*points)[k + 1] - (*points)[k]).norm();
      EXPECT_NEAR(polyline_m, ComputeImagePath(plan, s, tx, rx).length_m, 1e-9);
      for (std::size_t i = 0; i < s.size(); ++i) {
        const Wall& wall = plan.walls()[static_cast<std::size_t>(s[i])];
        const Vec2& before = (*points)[i];
        const Vec2& at = (*points)[i + 1];
        const Vec2& after = (*points)[i + 2];
        EXPECT_LT(DistanceToSegment(at, wall.start_m, wall.end_m), 1e-9);
        const Vec2 n = WallNormal(wall);
        const Vec2 d_in = (at - before).normalized();
        const Vec2 d_out = (after - at).normalized();
        EXPECT_NEAR((d_out - (d_in - 2.0 * n.dot(d_in) * n)).norm(), 0.0, 1e-9);
        EXPECT_GT(SignedDistanceToLine(before, wall.start_m, wall.end_m) * SignedDistanceToLine(after, wall.start_m, wall.end_m),
                  0.0);
      }
    }
  }
  EXPECT_GT(traced, 200);  // the check ran on many paths of every order
}

TEST(TraceImagePath, FindsTheSingleBounceOfSimilarTrianglesAndNothingElse) {
  // Independent of the images: a single bounce off a wall line reflects at the point that
  // divides the feet of tx and rx in the ratio of their distances to the line; in a convex empty
  // room the path exists exactly when that point lies on the segment.
  const FloorPlan plan = Pentagon();
  core::Rng rng(5, 0);
  int exists = 0, missing = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Vec2 tx = testing::UniformVec2(rng, Vec2(0.5, 0.5), Vec2(6.0, 4.0));
    const Vec2 rx = testing::UniformVec2(rng, Vec2(0.5, 0.5), Vec2(6.0, 4.0));
    if (!plan.Encloses(tx) || !plan.Encloses(rx)) continue;
    for (int w = 0; w < 5; ++w) {
      const Wall& wall = plan.walls()[static_cast<std::size_t>(w)];
      const Vec2 e = (wall.end_m - wall.start_m).normalized();
      const double d_tx = std::abs(SignedDistanceToLine(tx, wall.start_m, wall.end_m));
      const double d_rx = std::abs(SignedDistanceToLine(rx, wall.start_m, wall.end_m));
      const double s_tx = (tx - wall.start_m).dot(e);
      const double s_rx = (rx - wall.start_m).dot(e);
      const double s = s_tx + (s_rx - s_tx) * d_tx / (d_tx + d_rx);
      const bool on_segment = s > 1e-6 && s < (wall.end_m - wall.start_m).norm() - 1e-6;
      const bool near_an_end = std::abs(s) < 1e-6 || std::abs(s - (wall.end_m - wall.start_m).norm()) < 1e-6;
      if (near_an_end) continue;

      const auto points = TraceImagePath(plan, WallSequence{w}, tx, rx);

      EXPECT_EQ(points.has_value(), on_segment) << "wall " << w;
      if (points) {
        EXPECT_NEAR(((*points)[1] - (wall.start_m + s * e)).norm(), 0.0, 1e-9);
        ++exists;
      } else {
        ++missing;
      }
    }
  }
  EXPECT_GT(exists, 100);
  EXPECT_GT(missing, 5);
}

TEST(TraceImagePath, RespectsFiniteWallsOcclusionAndObstacles) {
  // A 6 m x 4 m room with a short interior wall (x = 3, y in [0, 1.5]) and a pillar.
  auto walls = Rectangle(6.0, 4.0).walls();
  walls.push_back({Vec2(3.0, 0.0), Vec2(3.0, 1.5), 0.5, "stub"});
  const FloorPlan room(walls, {{Vec2(5.0, 3.3), 0.3, "pillar"}});
  // The south wall reflection between agents on either side of the stub: reflection point at
  // x = 2.33, and the outgoing leg crosses the stub at y = 0.25.
  EXPECT_FALSE(TraceImagePath(room, WallSequence{0}, Vec2(1.0, 0.5), Vec2(5.0, 1.0)).has_value());
  // Higher up the legs pass above the stub's end.
  EXPECT_TRUE(TraceImagePath(room, WallSequence{2}, Vec2(1.0, 2.5), Vec2(5.0, 2.5)).has_value());
  // The stub's own reflection: its foot point from (2, 3) lies above its end, off the segment.
  EXPECT_FALSE(TraceImagePath(room, WallSequence{4}, Vec2(2.0, 3.0), Vec2(2.0, 3.0)).has_value());
  EXPECT_TRUE(TraceImagePath(room, WallSequence{4}, Vec2(2.0, 1.0), Vec2(2.0, 1.0)).has_value());
  // LOS through the pillar is blocked; no LOS of an agent to itself.
  EXPECT_FALSE(TraceImagePath(room, WallSequence{}, Vec2(5.0, 2.5), Vec2(5.0, 3.9)).has_value());
  EXPECT_FALSE(TraceImagePath(room, WallSequence{}, Vec2(1.0, 1.0), Vec2(1.0, 1.0)).has_value());
  // The vertices: tx, reflection point, rx.
  const auto points = TraceImagePath(room, WallSequence{2}, Vec2(1.0, 2.0), Vec2(5.0, 2.0));
  ASSERT_TRUE(points.has_value());
  ASSERT_EQ(points->size(), 3u);
  EXPECT_NEAR(((*points)[1] - Vec2(3.0, 4.0)).norm(), 0.0, 1e-12);
}

TEST(TraceImagePath, RejectsSequencesTheGenerationRulesExclude) {
  // [0, 0] would return to tx; the south wall of a 4 m square split in two collinear pieces
  // 0a = (0,0)-(2,0) and 0b = (2,0)-(4,0) gives no [0a, 0b].
  auto walls = Rectangle(4.0, 4.0).walls();
  walls[0].end_m = Vec2(2, 0);
  walls.insert(walls.begin() + 1, Wall{Vec2(2, 0), Vec2(4, 0), 0.5, "south b"});
  const FloorPlan plan(walls, {});
  EXPECT_FALSE(TraceImagePath(plan, WallSequence{0, 0}, Vec2(1, 1), Vec2(3, 2)).has_value());
  EXPECT_FALSE(TraceImagePath(plan, WallSequence{0, 1}, Vec2(1, 1), Vec2(3, 2)).has_value());
  // The single bounce reflects at x = 1 + 2 / 3 on piece 0a.
  EXPECT_TRUE(TraceImagePath(plan, WallSequence{0}, Vec2(1, 1), Vec2(3, 2)).has_value());
}

TEST(TraceImagePath, InterpolatesTheHeightsOfTheReflectionPointsAlongTheUnfoldedPath) {
  // 5 m x 4 m room; tx (1, 1, 0.5), rx (4, 3, 2.0), south then north wall. Images (1,-1), (1, 9).
  // Back from rx towards (1, 9): y = 4 at t = 1/6 -> (3.5, 4); towards (1,-1): y = 0 at t = 4/5
  // -> (1.5, 0). Fractions of the unfolded line: 1/6 and 1/6 + 4/5 * 5/6 = 5/6, so the heights
  // are 2.0 - 1.5/6 = 1.75 and 2.0 - 1.5 * 5/6 = 0.75.
  const FloorPlan room = Rectangle(5.0, 4.0, 0.0, 3.0);

  const auto points = TraceImagePath(room, WallSequence{0, 2}, Vec3(1, 1, 0.5), Vec3(4, 3, 2.0));

  ASSERT_TRUE(points.has_value());
  ASSERT_EQ(points->size(), 4u);
  const std::vector<Vec3> expected{Vec3(1, 1, 0.5), Vec3(1.5, 0, 0.75), Vec3(3.5, 4, 1.75), Vec3(4, 3, 2.0)};
  for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR(((*points)[k] - expected[k]).norm(), 0.0, 1e-12) << "vertex " << k;
  double polyline_m = 0.0;
  for (std::size_t k = 0; k < 3; ++k) polyline_m += ((*points)[k + 1] - (*points)[k]).norm();
  EXPECT_NEAR(polyline_m, std::hypot(std::sqrt(45.0), 1.5), 1e-12);
  EXPECT_NEAR(polyline_m, ComputeImagePath(room, WallSequence{0, 2}, Vec3(1, 1, 0.5), Vec3(4, 3, 2.0)).length_m, 1e-12);
}

TEST(TraceImagePath, RejectsAReflectionAboveTheCeilingOrBelowTheFloor) {
  // tx (1, 2), rx (4, 2) in a 5 m x 4 m room, south wall: reflection at (2.5, 0), halfway along
  // the unfolded path, so at the mean of the two heights.
  const WallSequence south{0};
  const Vec2 tx(1.0, 2.0), rx(4.0, 2.0);
  // Mean height 3.25 m: above a 3 m ceiling, below a 3.5 m one.
  EXPECT_FALSE(TraceImagePath(Rectangle(5.0, 4.0, 0.0, 3.0), south, At(tx, 4.5), At(rx, 2.0)).has_value());
  EXPECT_TRUE(TraceImagePath(Rectangle(5.0, 4.0, 0.0, 3.5), south, At(tx, 4.5), At(rx, 2.0)).has_value());
  // Mean height -0.25 m: below a floor at 0, above one at -0.5.
  EXPECT_FALSE(TraceImagePath(Rectangle(5.0, 4.0, 0.0, 3.0), south, At(tx, -1.0), At(rx, 0.5)).has_value());
  EXPECT_TRUE(TraceImagePath(Rectangle(5.0, 4.0, -0.5, 3.0), south, At(tx, -1.0), At(rx, 0.5)).has_value());
  // A plan without heights (floor 0, no ceiling) takes any height above the floor.
  EXPECT_TRUE(TraceImagePath(Rectangle(5.0, 4.0), south, At(tx, 40.0), At(rx, 2.0)).has_value());
  // The line of sight has no reflection point to test.
  EXPECT_TRUE(TraceImagePath(Rectangle(5.0, 4.0, 0.0, 3.0), WallSequence{}, At(tx, 4.5), At(rx, 2.0)).has_value());
}

TEST(TraceImagePath, AgreesWithThePlanarTraceWhenHeightsAreEqual) {
  const FloorPlan plan = Pentagon({{Vec2(3.5, 2.0), 0.3, "pillar"}});
  core::Rng rng(13, 0);
  for (int trial = 0; trial < 10; ++trial) {
    const Vec2 tx = testing::UniformVec2(rng, Vec2(0.5, 0.5), Vec2(6.0, 4.0));
    const Vec2 rx = testing::UniformVec2(rng, Vec2(0.5, 0.5), Vec2(6.0, 4.0));
    for (const auto& s : AllSequences(5, 2)) {
      const auto flat = TraceImagePath(plan, s, tx, rx);
      const auto level = TraceImagePath(plan, s, At(tx, 1.4), At(rx, 1.4));
      ASSERT_EQ(flat.has_value(), level.has_value());
      if (!flat) continue;
      for (std::size_t k = 0; k < flat->size(); ++k) {
        EXPECT_EQ((*level)[k].head<2>(), (*flat)[k]);
        EXPECT_NEAR((*level)[k].z(), 1.4, 1e-15);
      }
    }
  }
}

TEST(TraceImageChain, TracesAVerticalLineOfSightButNoZeroLengthOne) {
  // Straight up: no planar length, but a 3-D one.
  const FloorPlan room = Rectangle(5.0, 4.0, 0.0, 3.0);
  const std::vector<Vec3> images{Vec3(2, 2, 0.5)};
  std::vector<Vec3> vertices(2);

  EXPECT_TRUE(TraceImageChain(room, {}, images, Vec3(2, 2, 2.5), vertices));
  EXPECT_EQ(vertices[0], Vec3(2, 2, 2.5));
  EXPECT_EQ(vertices[1], Vec3(2, 2, 0.5));
  EXPECT_FALSE(TraceImageChain(room, {}, images, Vec3(2, 2, 0.5), vertices));
}

// ---------------------------------------------------------------------------------------------
// Enumeration
// ---------------------------------------------------------------------------------------------

TEST(VisibleImagePaths, ListsExactlyTheSequencesWhosePathsTraceInOrder) {
  // Brute force over every sequence without an immediate repeat, up to order 3, at seeded random
  // points of a pentagon with a pillar and a stub; in 3-D with transmitters up to 1.5 m above a
  // 2.5 m ceiling, so that the ceiling cuts some of the paths.
  auto walls = Pentagon().walls();
  walls.push_back({Vec2(2.0, 0.0), Vec2(2.5, 1.5), 0.5, "stub"});
  const FloorPlan plan(walls, {{Vec2(4.0, 2.5), 0.3, "pillar"}}, 0.0, 2.5);
  core::Rng rng(17, 0);
  int cut = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const Vec3 tx = testing::UniformVec3(rng, Vec3(0.5, 0.5, 0.0), Vec3(6.0, 4.0, 4.0));
    const Vec3 rx = testing::UniformVec3(rng, Vec3(0.5, 0.5, 0.0), Vec3(6.0, 4.0, 2.0));
    std::vector<WallSequence> expected2, expected3;
    for (const auto& s : AllSequences(6, 3)) {
      if (TraceImagePath(plan, s, Vec2(tx.head<2>()), Vec2(rx.head<2>()))) expected2.push_back(s);
      if (TraceImagePath(plan, s, tx, rx)) expected3.push_back(s);
    }

    EXPECT_EQ(VisibleImagePaths(plan, Vec2(tx.head<2>()), Vec2(rx.head<2>()), 3), expected2);
    EXPECT_EQ(VisibleImagePaths(plan, tx, rx, 3), expected3);
    cut += static_cast<int>(expected2.size() - expected3.size());
  }
  EXPECT_GT(cut, 0);
}

TEST(VisibleImagePaths, FindsTheSelfChannelPathsOfARectangle) {
  // Four single bounces and the two parallel-wall double bounces each way; a monostatic corner
  // path degenerates into the corner point and is not counted.
  const FloorPlan room = Rectangle(5.0, 4.0);
  const auto paths = VisibleImagePaths(room, Vec2(1.3, 2.1), Vec2(1.3, 2.1), 2);
  int first = 0, second = 0;
  for (const auto& s : paths) {
    if (s.size() == 1) ++first;
    if (s.size() == 2) {
      ++second;
      EXPECT_EQ((s[0] + 2) % 4, s[1]) << "only parallel pairs";
    }
    EXPECT_FALSE(s.empty()) << "no LOS on a self channel";
  }
  EXPECT_EQ(first, 4);
  EXPECT_EQ(second, 4);
  // Between two agents: the LOS and the 4 single bounces.
  const auto relative = VisibleImagePaths(room, Vec2(1.0, 1.0), Vec2(4.0, 3.0), 1);
  EXPECT_EQ(relative.size(), 5u);
  EXPECT_TRUE(relative.front().empty());
}

}  // namespace
}  // namespace mirage::geometry
