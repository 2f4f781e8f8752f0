// SPDX-License-Identifier: MIT
#include "mirage/channel/specular_path.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/core/constants.h"
#include "mirage/geometry/visibility.h"

namespace mirage::channel {
namespace {

using core::kPi;
using core::kSpeedOfLight_mps;

constexpr double kCarrier_hz = 7e9;

// 4 m x 4 m room, walls counter-clockwise from (0,0) with coefficients 0.9, 0.8, 0.5, 0.3.
geometry::FloorPlan SquareRoom(std::vector<geometry::CircleObstacle> obstacles = {}) {
  return geometry::FloorPlan({{Vec2(0, 0), Vec2(4, 0), 0.9, "south"},
                              {Vec2(4, 0), Vec2(4, 4), 0.8, "east"},
                              {Vec2(4, 4), Vec2(0, 4), 0.5, "north"},
                              {Vec2(0, 4), Vec2(0, 0), 0.3, "west"}},
                             std::move(obstacles));
}

const Vec2 kAnchor(1.0, 1.5);
const Vec2 kAgent(3.0, 3.0);

// Carrier phase -2 pi f_c tau reduced to (-pi, pi].
double WrappedPhase(double delay_s) {
  return std::remainder(-2.0 * kPi * kCarrier_hz * delay_s, 2.0 * kPi);
}

TEST(ComputeSpecularPaths, ReturnsOnePathPerVisibleVaInIdOrder) {
  const auto plan = SquareRoom();
  const std::vector<Vec2> anchors{kAnchor};
  const auto vas = geometry::VirtualAnchorSet::Generate(anchors, plan, 2);

  const auto paths = ComputeSpecularPaths(vas, 0, plan, kAgent, kCarrier_hz, core::Medium::Radio());

  // From (3,3) the LOS, all 4 order-1 VAs and 8 of the 12 order-2 VAs are visible (hand traced in
  // tests/geometry/visibility_test.cc).
  const auto visible = geometry::VisibleVirtualAnchors(vas, 0, plan, kAgent);
  ASSERT_EQ(visible.size(), 13u);
  ASSERT_EQ(paths.size(), visible.size());
  for (std::size_t i = 0; i < paths.size(); ++i) {
    EXPECT_EQ(paths[i].va_id, visible[i]);
    EXPECT_EQ(paths[i].order, vas[visible[i]].order);
  }
}

TEST(ComputeSpecularPaths, GivesTheLosAFreeSpaceAmplitudeAndCarrierPhase) {
  // LOS distance |(2, 1.5)| = 2.5 m: |alpha| = 1/2.5 = 0.4, tau = 2.5 m / c = 8.339 ns.
  const auto plan = SquareRoom();
  const std::vector<Vec2> anchors{kAnchor};
  const auto vas = geometry::VirtualAnchorSet::Generate(anchors, plan, 1);

  const auto paths = ComputeSpecularPaths(vas, 0, plan, kAgent, kCarrier_hz, core::Medium::Radio());

  ASSERT_FALSE(paths.empty());
  const SpecularPath& los = paths.front();
  EXPECT_EQ(los.va_id, 0);
  EXPECT_EQ(los.order, 0);
  EXPECT_NEAR(los.delay_s, 2.5 / kSpeedOfLight_mps, 1e-20);
  EXPECT_NEAR(los.delay_s, 8.3391e-9, 1e-13);
  EXPECT_NEAR(std::abs(los.amplitude), 0.4, 1e-14);
  EXPECT_NEAR(std::remainder(std::arg(los.amplitude) - WrappedPhase(los.delay_s), 2.0 * kPi), 0.0, 1e-9);
  // f_c tau = 7e9 * 2.5 / 299792458 = 58.373717 cycles -> phase -2 pi * 0.373717 = -2.348131 rad.
  EXPECT_NEAR(std::arg(los.amplitude), -2.348131, 1e-6);
}

TEST(ComputeSpecularPaths, DelaysEachPathByItsLengthOverTheSpeedOfTheMedium) {
  // LOS 2.5 m in air at 343 m/s: 7.289 ms; the south-wall reflection sqrt(24.25) m likewise.
  const auto plan = SquareRoom();
  const std::vector<Vec2> anchors{kAnchor};
  const auto vas = geometry::VirtualAnchorSet::Generate(anchors, plan, 1);
  const core::Medium air{core::MediumKind::kSound, 343.0};

  const auto paths = ComputeSpecularPaths(vas, 0, plan, kAgent, kCarrier_hz, air);

  ASSERT_EQ(paths.size(), 5u);
  EXPECT_DOUBLE_EQ(paths[0].delay_s, 2.5 / 343.0);
  for (const auto& path : paths) {
    EXPECT_DOUBLE_EQ(path.delay_s, (vas[path.va_id].position_m - kAgent).norm() / 343.0) << "VA " << path.va_id;
  }
}

TEST(ComputeSpecularPaths, ScalesReflectedAmplitudesByTheWallGainsOverTheDistance) {
  // South wall (0.9): VA (1,-1.5), d = |(2, 4.5)| = sqrt(24.25) -> |alpha| = 0.9 / 4.9244 = 0.18276.
  // {0,1} (0.9 * 0.8): VA (7,-1.5), d = sqrt(36.25) = 6.0208 -> |alpha| = 0.72 / 6.0208 = 0.11958.
  const auto plan = SquareRoom();
  const std::vector<Vec2> anchors{kAnchor};
  const auto vas = geometry::VirtualAnchorSet::Generate(anchors, plan, 2);
  struct Case {
    std::vector<int> walls;
    double distance_m;
    double gain;
  };
  const std::vector<Case> cases{{{0}, std::sqrt(24.25), 0.9}, {{0, 1}, std::sqrt(36.25), 0.72}};

  const auto paths = ComputeSpecularPaths(vas, 0, plan, kAgent, kCarrier_hz, core::Medium::Radio());

  for (const auto& c : cases) {
    const SpecularPath* found = nullptr;
    for (const auto& path : paths) {
      if (vas[path.va_id].walls == c.walls) found = &path;
    }
    ASSERT_NE(found, nullptr);
    EXPECT_NEAR(found->delay_s * kSpeedOfLight_mps, c.distance_m, 1e-12);
    EXPECT_NEAR(std::abs(found->amplitude), c.gain / c.distance_m, 1e-14);
    EXPECT_NEAR(std::remainder(std::arg(found->amplitude) - WrappedPhase(found->delay_s), 2.0 * kPi), 0.0, 1e-9);
  }
  EXPECT_NEAR(std::abs(paths[1].amplitude), 0.18276, 1e-5);
}

TEST(ComputeSpecularPaths, OmitsPathsBlockedByAPillar) {
  // Pillar (2, 2.25) r 0.4 blocks the LOS, the east and the west reflection from (3,3) (see
  // tests/geometry/visibility_test.cc); the south and north reflections remain.
  const auto plan = SquareRoom({{Vec2(2.0, 2.25), 0.4, "pillar"}});
  const std::vector<Vec2> anchors{kAnchor};
  const auto vas = geometry::VirtualAnchorSet::Generate(anchors, plan, 1);

  const auto paths = ComputeSpecularPaths(vas, 0, plan, kAgent, kCarrier_hz, core::Medium::Radio());

  ASSERT_EQ(paths.size(), 2u);
  EXPECT_EQ(vas[paths[0].va_id].walls, std::vector<int>{0});
  EXPECT_EQ(vas[paths[1].va_id].walls, std::vector<int>{2});
}

TEST(ComputeSpecularPaths, ClampsTheDistanceOfANearFieldPathTo1Centimetre) {
  // Agent 1 mm from the anchor: the LOS distance is clamped to 0.01 m, |alpha| = 100.
  const auto plan = SquareRoom();
  const std::vector<Vec2> anchors{kAnchor};
  const auto vas = geometry::VirtualAnchorSet::Generate(anchors, plan, 0);

  const auto paths = ComputeSpecularPaths(vas, 0, plan, kAnchor + Vec2(0.001, 0.0), kCarrier_hz, core::Medium::Radio());

  ASSERT_EQ(paths.size(), 1u);
  EXPECT_NEAR(std::abs(paths[0].amplitude), 100.0, 1e-10);
  EXPECT_NEAR(paths[0].delay_s, 0.01 / kSpeedOfLight_mps, 1e-22);
}

TEST(ComputeSpecularPaths, GivesAnAgentOnTopOfTheAnchorNoLineOfSight) {
  // A zero-length path is outside every model here (image_source.h: kOnLineTolerance_m).
  const auto plan = SquareRoom();
  const std::vector<Vec2> anchors{kAnchor};
  const auto vas = geometry::VirtualAnchorSet::Generate(anchors, plan, 1);

  const auto paths = ComputeSpecularPaths(vas, 0, plan, kAnchor, kCarrier_hz, core::Medium::Radio());

  ASSERT_EQ(paths.size(), 4u);
  for (const auto& path : paths) EXPECT_EQ(path.order, 1);
}

TEST(ComputeSpecularPaths, ScalesThePhaseWithTheCarrier) {
  // Doubling f_c doubles the phase: arg(alpha_2f) = 2 arg(alpha_f) (mod 2 pi).
  const auto plan = SquareRoom();
  const std::vector<Vec2> anchors{kAnchor};
  const auto vas = geometry::VirtualAnchorSet::Generate(anchors, plan, 0);

  const auto at_f = ComputeSpecularPaths(vas, 0, plan, kAgent, 3.5e9, core::Medium::Radio());
  const auto at_2f = ComputeSpecularPaths(vas, 0, plan, kAgent, 7e9, core::Medium::Radio());

  ASSERT_EQ(at_f.size(), 1u);
  ASSERT_EQ(at_2f.size(), 1u);
  EXPECT_NEAR(std::remainder(std::arg(at_2f[0].amplitude) - 2.0 * std::arg(at_f[0].amplitude), 2.0 * kPi), 0.0, 1e-9);
  EXPECT_EQ(at_f[0].delay_s, at_2f[0].delay_s);
}

}  // namespace
}  // namespace mirage::channel
