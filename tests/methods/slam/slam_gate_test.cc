// SPDX-License-Identifier: MIT
// SLAM's default-on innovation gate (SlamOptions::innovation_gate_chi2, a mirage addition to the
// cut-off assignment of Leitinger et al. Eq. 10-11), with default options and the floor plan's VAs
// known: a range inside d_c but far outside its innovation variance (agent, VA and range parts) is
// never associated, so the estimate is what it would be without that range, while the nominal
// range is associated; with the gate off the outlier is associated and pulls the agent and the VA.
#include <cmath>

#include <gtest/gtest.h>

#include "methods/mint/square_room.h"
#include "mirage/methods/slam/slam_tracker.h"

namespace mirage::methods::slam {
namespace {

Vec2 MapPosition(const SlamTracker& tracker, int va_id) {
  for (const auto& va : tracker.Map()) {
    if (va.id == va_id) return va.position_m;
  }
  return Vec2::Constant(1e9);
}

TEST(SlamTracker, DefaultInnovationGateKeepsARangeInsideTheCutoffOutOfTheUpdate) {
  // The known-VA baseline (the first-order VAs in the map, no discovery) with default options
  // otherwise, 1 cm ranges: after 20 steps the VA is in the state and its range known to a few
  // cm. At step 21 its range is offset_m long; it has no other range within 0.3 m, so only its own
  // range competes for it. A gross error (3 m) lies beyond d_c = 15 cm and never reaches the gate
  // (the cut-off assignment drops it); 10 cm is inside d_c and far outside the 3-sigma gate, so
  // only the gate can reject it.
  const auto plan = mint::testing::EmptySquareRoom();
  const auto vas = mint::testing::SquareRoomVas(plan, 1);
  const int va = mint::testing::IsolatedReflection(vas, plan, 0, Vec2(2.55, 2.0), 0.3);
  ASSERT_GE(va, 0);
  struct Outcome {
    SlamStepResult with, without;   // the epoch with the outlier, and without its range
    Vec2 va_with_m, va_without_m;  // the outlier's VA after each
  };
  const auto run = [&](double gate_chi2, double offset_m) {
    SlamOptions options;
    options.prior_max_order = 1;
    options.discovery.enabled = false;
    options.innovation_gate_chi2 = gate_chi2;
    SlamTracker tracker(options, vas, plan, 0.01 * std::sqrt(10.0));
    SlamTracker twin = tracker;
    const auto [with, without] = mint::testing::StepWithAndWithoutOutlier(tracker, twin, vas, plan, va, offset_m);
    return Outcome{with, without, MapPosition(tracker, va), MapPosition(twin, va)};
  };
  const double default_gate = SlamOptions{}.innovation_gate_chi2;
  ASSERT_GT(default_gate, 0.0) << "the gate is on by default";

  EXPECT_TRUE(mint::testing::Associated(run(default_gate, 0.0).with, va)) << "the gate keeps the nominal range";

  const Outcome gated = run(default_gate, 0.10);
  EXPECT_FALSE(mint::testing::Associated(gated.with, va));
  EXPECT_LT((gated.with.position_m - gated.without.position_m).norm(), 1e-9) << "the gated range changed the estimate";
  EXPECT_LT((gated.va_with_m - gated.va_without_m).norm(), 1e-9) << "the gated range moved its VA";

  const Outcome gross = run(default_gate, 3.0);
  EXPECT_FALSE(mint::testing::Associated(gross.with, va));
  EXPECT_LT((gross.with.position_m - gross.without.position_m).norm(), 1e-9) << "the 3 m range changed the estimate";

  // Without the gate the 10 cm innovation is associated and, through the gains, moves the agent
  // by 1.4 cm and the VA by 3.1 cm; the bounds are a third of that, far from the gated 1e-9.
  const Outcome open = run(0.0, 0.10);
  EXPECT_TRUE(mint::testing::Associated(open.with, va));
  EXPECT_GT((open.with.position_m - open.without.position_m).norm(), 0.005)
      << "without the gate the 10 cm range pulls the estimate";
  EXPECT_GT((open.va_with_m - open.va_without_m).norm(), 0.01) << "and its VA";
}

}  // namespace
}  // namespace mirage::methods::slam
