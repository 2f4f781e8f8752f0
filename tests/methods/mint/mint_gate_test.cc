// SPDX-License-Identifier: MIT
// MINT's default-on innovation gate (MintOptions::innovation_gate_chi2, a mirage addition to
// Lafer 2014 Sec. 3.4), with default options: a range inside the cut-off d_c but far outside its
// innovation variance J P J^T + R is never associated, so the estimate is what it would be
// without that range, while the nominal range is associated; with the gate off the outlier is
// associated and pulls the estimate.
#include <cmath>

#include <gtest/gtest.h>

#include "methods/mint/square_room.h"
#include "mirage/methods/mint/mint_tracker.h"

namespace mirage::methods::mint {
namespace {

TEST(MintTracker, DefaultInnovationGateKeepsARangeInsideTheCutoffOutOfTheUpdate) {
  // The VAs up to order 2 of the empty room (MintOptions::max_order), 1 cm ranges; at step 21 the
  // range of one reflection is offset_m long. Its VA has no other range within 0.3 m, so only its
  // own range competes for it. A gross error (3 m) lies beyond d_c = 15 cm and never reaches the
  // gate (the cut-off assignment drops it); 10 cm is inside d_c and, for a track on 20 steps of
  // ~1 cm ranges, far outside the 3-sigma gate, so only the gate can reject it.
  const auto plan = testing::EmptySquareRoom();
  const auto vas = testing::SquareRoomVas(plan, MintOptions{}.max_order);
  const int va = testing::IsolatedReflection(vas, plan, 0, Vec2(2.55, 2.0), 0.3);
  ASSERT_GE(va, 0);
  const auto run = [&](double gate_chi2, double offset_m) {
    MintOptions options;
    options.innovation_gate_chi2 = gate_chi2;
    MintTracker tracker(options, vas, plan, 0.01 * std::sqrt(10.0));
    MintTracker twin = tracker;
    return testing::StepWithAndWithoutOutlier(tracker, twin, vas, plan, va, offset_m);
  };
  const double default_gate = MintOptions{}.innovation_gate_chi2;
  ASSERT_GT(default_gate, 0.0) << "the gate is on by default";

  const auto [nominal, nominal_without] = run(default_gate, 0.0);
  EXPECT_TRUE(testing::Associated(nominal, va)) << "the gate keeps the nominal range";

  const auto [gated, gated_without] = run(default_gate, 0.10);
  EXPECT_FALSE(testing::Associated(gated, va));
  EXPECT_LT((gated.position_m - gated_without.position_m).norm(), 1e-9) << "the gated range changed the estimate";

  const auto [gross, gross_without] = run(default_gate, 3.0);
  EXPECT_FALSE(testing::Associated(gross, va));
  EXPECT_LT((gross.position_m - gross_without.position_m).norm(), 1e-9) << "the 3 m range changed the estimate";

  const auto [open, open_without] = run(0.0, 0.10);
  EXPECT_TRUE(testing::Associated(open, va));
  EXPECT_GT((open.position_m - open_without.position_m).norm(), 0.01)
      << "without the gate the 10 cm range pulls the estimate";
}

}  // namespace
}  // namespace mirage::methods::mint
