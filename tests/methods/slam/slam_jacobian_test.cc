// SPDX-License-Identifier: MIT
// The H that SLAM stacks for its update (Leitinger et al. Eq. 16, current rows: u^T in the
// agent's position columns, -u^T in the columns of the VA when it is in the state, zero
// elsewhere) against central differences of the range written out as plain geometry: the
// distance from the state's agent position to the state's VA position, or to the fixed anchor.
// Both maps: the floor plan's VAs (the known-VA baseline) and VAs discovered from the anchors; at
// the tracker's state after a walk and at random states near it.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "estimation/jacobian_check.h"
#include "methods/mint/square_room.h"
#include "mirage/geometry/trajectory.h"
#include "mirage/methods/slam/slam_tracker.h"

namespace mirage::methods::slam {
namespace {

namespace blocks = estimation::blocks;

// Walks `steps` steps of a loop with three corners on ranges of the VAs up to order 2, then checks
// the rows of the last step's associations at the tracker's state.
void ExpectAssembledHMatches(const SlamOptions& options, int known_order, int steps) {
  const auto plan = mint::testing::SquareRoomWithPillar();
  const auto known = mint::testing::SquareRoomVas(plan, known_order);
  const auto truth = mint::testing::SquareRoomVas(plan, 2);
  mint::testing::MeasurementModel model;
  model.max_order = 2;
  SlamTracker tracker(options, known, plan, 0.01 * std::sqrt(10.0));
  const std::vector<Vec2> waypoints{Vec2(1.5, 1.5), Vec2(4.0, 1.5), Vec2(4.0, 4.5), Vec2(1.5, 4.5)};
  const auto samples = geometry::SampleTrajectory(waypoints, 0.5, 0.1);
  tracker.Initialize(samples.front().t_s, samples.front().position_m);
  core::Rng rng(12, 0);
  SlamStepResult step;
  for (std::size_t k = 1; k <= static_cast<std::size_t>(steps); ++k) {
    step = tracker.Step(samples[k].t_s, mint::testing::MeasureRanges(truth, plan, samples[k].position_m, model, rng));
  }
  const estimation::State& state = tracker.state();
  std::vector<int> va_ids;
  std::vector<double> variances_m2;
  int in_state = 0;
  for (const auto& a : step.associations) {
    va_ids.push_back(a.va_id);
    variances_m2.push_back(a.variance_m2);
    if (state.layout().Find(estimation::BlockKey(blocks::kVirtualAnchor, a.va_id))) ++in_state;
  }
  ASSERT_GE(in_state, 4) << "rows with VA columns";
  ASSERT_GT(va_ids.size(), static_cast<std::size_t>(in_state)) << "and the anchors' LOS rows without";
  ASSERT_GE(step.state_vas, in_state);

  const auto predict = [&](const estimation::State& s, std::size_t i) {
    const Vec2 p_m = s.Mean(estimation::BlockKey(blocks::kPosition, 0));
    const estimation::BlockKey va_key(blocks::kVirtualAnchor, va_ids[i]);
    if (s.layout().Find(va_key)) return (p_m - Vec2(s.Mean(va_key))).norm();
    // Not in the state: a physical anchor (an order-0 VA of the known set), exact and fixed.
    EXPECT_EQ(known[va_ids[i]].order, 0) << "VA " << va_ids[i] << " is neither in the state nor an anchor";
    return (p_m - mint::testing::TwoAnchors()[static_cast<std::size_t>(known[va_ids[i]].anchor_index)]).norm();
  };
  // The rows of the last step's associations, as Linearize builds them for both stages, at the
  // tracker's state and at three random states within ~0.2 m (m/s) of it. The tolerance is
  // relative to the largest entry (direction cosines: |H_ij| <= 1). With h = 1e-6 the central
  // difference's truncation error is h^2/6 |d^3 r/dx^3| <= h^2 / d^2 (1e-12 at d = 1 m) and its
  // rounding error eps d / h (2e-9 at d = 10 m): 1e-7 leaves a margin of 50, while a wrong sign, a
  // VA column missing or in the wrong block is off by orders of magnitude more.
  constexpr double kStep = 1e-6;
  constexpr double kRelativeTolerance = 1e-7;
  constexpr double kLargestEntry = 1.0;
  core::Rng perturb(4, 0);
  for (int trial = 0; trial < 4; ++trial) {
    const estimation::State s = trial == 0 ? state : estimation::testing::RandomNearby(state, 0.2, perturb);
    std::vector<estimation::MeasurementRow> rows;
    for (std::size_t i = 0; i < va_ids.size(); ++i) rows.push_back(*tracker.VaRow(s, va_ids[i], variances_m2[i]));
    estimation::testing::ExpectRowsMatchCentralDifferences(s, rows, predict, kStep, kRelativeTolerance * kLargestEntry,
                                                           "state " + std::to_string(trial));
  }
}

TEST(SlamTracker, AssembledJacobianMatchesCentralDifferencesWithTheFloorPlansVas) {
  SlamOptions options;
  options.prior_max_order = 2;
  ExpectAssembledHMatches(options, 2, 40);
}

TEST(SlamTracker, AssembledJacobianMatchesCentralDifferencesWithDiscoveredVas) {
  SlamOptions options;  // the anchors alone at the start
  options.prior_visibility = false;
  ExpectAssembledHMatches(options, 0, 160);
}

}  // namespace
}  // namespace mirage::methods::slam
