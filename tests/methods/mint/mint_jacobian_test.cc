// SPDX-License-Identifier: MIT
// The H that MINT stacks for its update (Lafer 2014 Eq. 3.19: one row per associated range,
// (p - a_i)^T / d_i in the position columns, zero in the velocity columns) against central
// differences of the range written out as plain geometry: the agent's distance to the anchor
// mirrored at the VA's walls. At the tracker's state after a walk and at random states near it.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "estimation/jacobian_check.h"
#include "methods/mint/square_room.h"
#include "methods/plane_mirror.h"
#include "mirage/geometry/trajectory.h"
#include "mirage/methods/mint/mint_tracker.h"

namespace mirage::methods::mint {
namespace {

// The VA's position from its definition: its anchor mirrored at its walls, first bounce first.
Vec2 MirroredVa(const geometry::VirtualAnchor& va) {
  const std::vector<geometry::Wall> walls = testing::SquareWalls();
  std::vector<methods::testing::MirrorLine> lines;
  for (const int w : va.walls) {
    const geometry::Wall& wall = walls[static_cast<std::size_t>(w)];
    lines.push_back({wall.start_m, wall.end_m, 0.0});
  }
  return methods::testing::ImageOf(testing::TwoAnchors()[static_cast<std::size_t>(va.anchor_index)], lines);
}

TEST(MintTracker, AssembledJacobianMatchesCentralDifferences) {
  // A realistic state: 30 steps of a walk with first- and second-order VAs, so the velocity is
  // non-zero and the last step associated ranges of all orders.
  const auto plan = testing::SquareRoomWithPillar();
  const auto vas = testing::SquareRoomVas(plan, 2);
  testing::MeasurementModel model;
  model.max_order = 2;
  MintTracker tracker(MintOptions{}, vas, plan, 0.01 * std::sqrt(10.0));
  const std::vector<Vec2> waypoints{Vec2(1.5, 1.5), Vec2(4.0, 1.5), Vec2(4.0, 4.5)};
  const auto samples = geometry::SampleTrajectory(waypoints, 0.5, 0.1);
  tracker.Initialize(samples.front().t_s, samples.front().position_m);
  core::Rng rng(11, 0);
  MintStepResult step;
  for (std::size_t k = 1; k <= 30; ++k) {
    step = tracker.Step(samples[k].t_s, testing::MeasureRanges(vas, plan, samples[k].position_m, model, rng));
  }
  const estimation::State& state = tracker.state();
  std::vector<int> va_ids;
  std::vector<double> variances_m2;
  std::vector<Vec2> va_m;
  bool second_order = false;
  for (const auto& a : step.associations) {
    va_ids.push_back(a.va_id);
    variances_m2.push_back(a.variance_m2);
    va_m.push_back(MirroredVa(vas[a.va_id]));
    second_order = second_order || vas[a.va_id].order == 2;
  }
  ASSERT_GE(va_ids.size(), 8u);
  ASSERT_TRUE(second_order);
  ASSERT_GT(state.Mean(estimation::BlockKey(estimation::blocks::kVelocity, 0)).norm(), 0.1);

  const auto predict = [&](const estimation::State& s, std::size_t i) {
    const Vec2 p_m = s.Mean(estimation::BlockKey(estimation::blocks::kPosition, 0));
    return (p_m - va_m[i]).norm();
  };
  // The rows of the last step's associations, as Update builds them, at the tracker's state and at
  // three random states within ~0.2 m (m/s) of it. The tolerance is relative to the largest entry
  // (direction cosines: |H_ij| <= 1). With h = 1e-6 the central difference's truncation error is
  // h^2/6 |d^3 r/dx^3| <= h^2 / d^2 (1e-12 at d = 1 m) and its rounding error eps d / h (2e-9 at
  // d = 10 m): 1e-7 leaves a margin of 50, while a wrong sign, a wrong VA or a velocity column not
  // zero is off by orders of magnitude more.
  constexpr double kStep = 1e-6;
  constexpr double kRelativeTolerance = 1e-7;
  constexpr double kLargestEntry = 1.0;
  core::Rng perturb(3, 0);
  for (int trial = 0; trial < 4; ++trial) {
    const estimation::State s = trial == 0 ? state : estimation::testing::RandomNearby(state, 0.2, perturb);
    std::vector<estimation::MeasurementRow> rows;
    for (std::size_t i = 0; i < va_ids.size(); ++i) rows.push_back(*tracker.VaRow(s, va_ids[i], variances_m2[i]));
    estimation::testing::ExpectRowsMatchCentralDifferences(s, rows, predict, kStep, kRelativeTolerance * kLargestEntry,
                                                           "state " + std::to_string(trial));
  }
}

}  // namespace
}  // namespace mirage::methods::mint
