// SPDX-License-Identifier: MIT
// Image-source paths of moving transmitters (Kulmer et al. Sec. II-B, App. B-C): the analytic
// derivatives against central finite differences for orders 0-3 (relative and self channels),
// the closed forms of App. C, reciprocity (Eq. 22), and the ray tracing of finite walls,
// occlusion and obstacles.
#include "mirage/geometry/image_path.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/core/rng.h"

namespace mirage::geometry {
namespace {

// A pentagon with no parallel walls, so that no path is degenerate.
FloorPlan Pentagon() {
  const std::vector<Vec2> corners{Vec2(0, 0), Vec2(6, -0.5), Vec2(7, 4), Vec2(3, 6.5), Vec2(-0.5, 4)};
  std::vector<Wall> walls;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    walls.push_back({corners[i], corners[(i + 1) % corners.size()], 0.5, "wall"});
  }
  return FloorPlan(walls, {});
}

FloorPlan Rectangle(double width_m, double height_m) {
  return FloorPlan({{Vec2(0, 0), Vec2(width_m, 0), 0.5, "south"},
                    {Vec2(width_m, 0), Vec2(width_m, height_m), 0.5, "east"},
                    {Vec2(width_m, height_m), Vec2(0, height_m), 0.5, "north"},
                    {Vec2(0, height_m), Vec2(0, 0), 0.5, "west"}},
                   {});
}

// The plan with wall w moved by delta_m along its normal n = U e.
FloorPlan Shifted(const FloorPlan& plan, int w, double delta_m) {
  auto walls = plan.walls();
  auto& wall = walls[static_cast<std::size_t>(w)];
  const Vec2 e = (wall.end_m - wall.start_m).normalized();
  const Vec2 n(-e.y(), e.x());
  wall.start_m += delta_m * n;
  wall.end_m += delta_m * n;
  return FloorPlan(walls, plan.obstacles());
}

void ExpectDerivativesMatchFiniteDifferences(const FloorPlan& plan, const WallSequence& s, const Vec2& tx,
                                             const Vec2& rx, bool self) {
  const double h = 1e-6;
  const ImagePath path = ComputeImagePath(plan, s, tx, rx);
  const auto length = [&](const FloorPlan& p, const Vec2& t, const Vec2& r) { return ComputeImagePath(p, s, t, r).length_m; };
  for (int c = 0; c < 2; ++c) {
    const Vec2 e = Vec2::Unit(c) * h;
    if (self) {
      // One agent is both ends: the total derivative.
      const double fd = (length(plan, tx + e, rx + e) - length(plan, tx - e, rx - e)) / (2 * h);
      EXPECT_NEAR(path.d_rx(c) + path.d_tx(c), fd, 1e-6) << "self, coordinate " << c;
    } else {
      EXPECT_NEAR(path.d_rx(c), (length(plan, tx, rx + e) - length(plan, tx, rx - e)) / (2 * h), 1e-6);
      EXPECT_NEAR(path.d_tx(c), (length(plan, tx + e, rx) - length(plan, tx - e, rx)) / (2 * h), 1e-6);
    }
  }
  // Wall offsets: a wall met several times gets the sum of its entries.
  for (int w = 0; w < static_cast<int>(plan.walls().size()); ++w) {
    double analytic = 0.0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (s[i] == w) analytic += path.d_offset[i];
    }
    const double fd = (length(Shifted(plan, w, h), tx, rx) - length(Shifted(plan, w, -h), tx, rx)) / (2 * h);
    EXPECT_NEAR(analytic, fd, 1e-6) << "wall " << w;
  }
}

TEST(ImagePath, DerivativesMatchFiniteDifferencesUpToThirdOrder) {
  const FloorPlan plan = Pentagon();
  core::Rng rng(1, 0);
  const std::vector<WallSequence> sequences{{}, {0}, {3}, {0, 2}, {4, 1}, {1, 3, 0}, {2, 0, 2}};
  for (int trial = 0; trial < 5; ++trial) {
    const Vec2 tx(rng.Uniform(1.0, 5.0), rng.Uniform(1.0, 4.0));
    const Vec2 rx(rng.Uniform(1.0, 5.0), rng.Uniform(1.0, 4.0));
    for (const auto& s : sequences) {
      ExpectDerivativesMatchFiniteDifferences(plan, s, tx, rx, false);
      if (!s.empty()) ExpectDerivativesMatchFiniteDifferences(plan, s, tx, tx, true);
    }
  }
}

TEST(ImagePath, SelfSingleBounceIsTwiceTheWallDistanceWithGradientTwoU) {
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

TEST(ImagePath, SelfBounceBetweenParallelWallsDoesNotDependOnThePosition) {
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

TEST(ImagePath, RelativeLosGradientsAreOppositeUnitVectors) {
  // Eq. (29).
  const FloorPlan room = Rectangle(5.0, 4.0);
  const ImagePath los = ComputeImagePath(room, WallSequence{}, Vec2(1, 1), Vec2(4, 5));
  EXPECT_NEAR(los.length_m, 5.0, 1e-12);
  EXPECT_NEAR((los.d_rx - Vec2(0.6, 0.8)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((los.d_tx + los.d_rx).norm(), 0.0, 1e-12);
}

TEST(ImagePath, ReciprocityReversesTheSequence) {
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

TEST(ImagePath, TracingRespectsFiniteWallsOcclusionAndObstacles) {
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

TEST(ImagePath, VisiblePathsOfASelfChannelInARectangle) {
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

TEST(ImagePath, VisiblePathsRejectAnUnsupportedOrder) {
  const FloorPlan room = Rectangle(5.0, 4.0);
  EXPECT_THROW(VisibleImagePaths(room, Vec2(1.0, 1.0), Vec2(4.0, 3.0), 4), std::invalid_argument);
  EXPECT_THROW(VisibleImagePaths(room, Vec2(1.0, 1.0), Vec2(4.0, 3.0), -1), std::invalid_argument);
}

}  // namespace
}  // namespace mirage::geometry
