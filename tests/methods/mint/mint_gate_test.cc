// SPDX-License-Identifier: MIT
// MINT's default-on innovation gate (MintOptions::innovation_gate_chi2, a mirage addition to
// Lafer 2014 Sec. 3.4): a range inside the cut-off d_c but far outside its innovation variance
// J P J^T + R is never associated, so the estimate is what it would be without that range; with
// the gate off the same range is associated and pulls the estimate.
#include <cmath>

#include <gtest/gtest.h>

#include "methods/mint/square_room.h"
#include "mirage/methods/mint/mint_tracker.h"

namespace mirage::methods::mint {
namespace {

TEST(MintTracker, DefaultInnovationGateKeepsARangeInsideTheCutoffOutOfTheUpdate) {
  // The first-order VAs of the empty room, 1 cm ranges and R right (variance estimation off,
  // sigma 1 cm); at step 21 the range of one reflection is 10 cm long: inside d_c = 15 cm, about
  // 7 innovation sigmas out. Its VA has no other range within 0.3 m.
  const auto plan = testing::EmptySquareRoom();
  const auto vas = testing::SquareRoomVas(plan, 1);
  const int va = testing::IsolatedReflection(vas, plan, 0, Vec2(2.55, 2.0), 0.3);
  ASSERT_GE(va, 0);
  const auto run = [&](double gate_chi2) {
    MintOptions options;
    options.max_order = 1;
    options.variance.enabled = false;
    options.range_sigma_m = 0.01;
    options.innovation_gate_chi2 = gate_chi2;
    MintTracker tracker(options, vas, plan, 0.01 * std::sqrt(10.0));
    MintTracker twin = tracker;
    return testing::StepWithAndWithoutOutlier(tracker, twin, vas, plan, va, 0.10);
  };

  const auto [gated, gated_without] = run(MintOptions{}.innovation_gate_chi2);
  EXPECT_FALSE(testing::Associated(gated, va));
  EXPECT_LT((gated.position_m - gated_without.position_m).norm(), 1e-9) << "the gated range changed the estimate";

  const auto [open, open_without] = run(0.0);
  EXPECT_TRUE(testing::Associated(open, va));
  EXPECT_GT((open.position_m - open_without.position_m).norm(), 0.01)
      << "without the gate the 10 cm range pulls the estimate";
}

}  // namespace
}  // namespace mirage::methods::mint
