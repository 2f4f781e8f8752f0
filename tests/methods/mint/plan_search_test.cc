// SPDX-License-Identifier: MIT
// Starting without a start point: the search of the whole floor plan (SearchFloorPlan), its
// refusal of ambiguous rooms, the two-epoch confirmation (ConfirmedStart), and MINT's
// InitializeFromEpoch built on them.
#include <vector>

#include <gtest/gtest.h>

#include "methods/mint/square_room.h"
#include "mirage/methods/mint/mint_estimator.h"
#include "mirage/methods/mint/relocalization.h"

namespace mirage::methods::mint {
namespace {

using testing::MeasureRanges;
using testing::MeasurementModel;
using testing::SquareRoomWithPillar;

// Anchors that no symmetry of the square room maps onto themselves. (The fixture's anchors
// (1, 5) and (5, 1) both lie on the diagonal x + y = 6: mirroring about it fixes them and the
// room, so every position has a twin; see RefusesARoomWhoseSymmetry... below.)
const std::vector<Vec2> kAnchors{Vec2(1.0, 5.0), Vec2(4.0, 1.5)};

geometry::VirtualAnchorSet Vas(const geometry::FloorPlan& plan, const std::vector<Vec2>& anchors = kAnchors) {
  return geometry::VirtualAnchorSet::Generate(anchors, plan, 1);
}

TEST(SearchFloorPlan, FindsTheAgentAnywhereInTheRoomFromOneEpochOfNoisyRangesWithClutter) {
  const auto plan = SquareRoomWithPillar();
  const auto vas = Vas(plan);
  MeasurementModel model;
  model.clutter_per_anchor = 3;
  core::Rng rng(3);
  const RelocalizationOptions options;
  for (const Vec2& truth : {Vec2(1.2, 1.3), Vec2(4.6, 4.1), Vec2(3.3, 0.8), Vec2(0.7, 3.9), Vec2(4.9, 2.4)}) {
    const auto ranges = MeasureRanges(vas, plan, truth, model, rng);

    const auto found = SearchFloorPlan(vas, plan, ranges, options);

    ASSERT_TRUE(found.has_value()) << truth.transpose();
    EXPECT_LT((found->position_m - truth).norm(), options.match_tolerance_m + 0.03) << truth.transpose();
    EXPECT_DOUBLE_EQ(found->grid_step_m, options.search_step_m);
  }
}

TEST(SearchFloorPlan, RefusesARoomWhoseSymmetryMakesTwoPositionsExplainTheRanges) {
  // Both anchors on the square room's diagonal x + y = 6: mirroring about it maps the room, each
  // anchor and each of its VAs onto themselves, so p and its mirror (6 - y, 6 - x) give the same
  // ranges.
  const geometry::FloorPlan plan(testing::SquareWalls(), {});
  const auto symmetric = Vas(plan, testing::TwoAnchors());
  MeasurementModel model;
  core::Rng rng(5);
  const Vec2 agent(1.5, 1.2);
  EXPECT_FALSE(SearchFloorPlan(symmetric, plan, MeasureRanges(symmetric, plan, agent, model, rng), RelocalizationOptions{})
                   .has_value());

  // The same agent with the second anchor off the diagonal is found.
  const auto asymmetric = Vas(plan);
  const auto found =
      SearchFloorPlan(asymmetric, plan, MeasureRanges(asymmetric, plan, agent, model, rng), RelocalizationOptions{});
  ASSERT_TRUE(found.has_value());
  EXPECT_LT((found->position_m - agent).norm(), 0.08);
}

TEST(SearchFloorPlan, FindsNothingWithoutAFloorPlan) {
  const geometry::FloorPlan none;
  const auto vas = Vas(none);
  EXPECT_FALSE(SearchFloorPlan(vas, none, {}, RelocalizationOptions{}).has_value());
}

TEST(ConfirmedStart, TakesAStartOnlyWhenTheNextEpochsSearchAgrees) {
  ConfirmedStart start(0.5);  // 0.5 m/s: 5 cm between epochs 0.1 s apart
  const PlanFix a{Vec2(1.0, 1.0), 0.1};
  // The first fix waits for confirmation.
  EXPECT_FALSE(start.Add(0.0, a).has_value());
  // A fix 2 m away is no confirmation: it becomes the new candidate.
  EXPECT_FALSE(start.Add(0.1, PlanFix{Vec2(3.0, 1.0), 0.1}).has_value());
  // Within two grid steps plus 0.5 m/s * 0.1 s of the candidate: confirmed, at the newer fix.
  const auto confirmed = start.Add(0.2, PlanFix{Vec2(3.2, 1.04), 0.1});
  ASSERT_TRUE(confirmed.has_value());
  EXPECT_EQ(*confirmed, Vec2(3.2, 1.04));
}

TEST(ConfirmedStart, ForgetsTheCandidateWhenAnEpochFindsNothing) {
  ConfirmedStart start(std::nullopt);
  EXPECT_FALSE(start.Add(0.0, PlanFix{Vec2(1.0, 1.0), 0.1}).has_value());
  EXPECT_FALSE(start.Add(0.1, std::nullopt).has_value());
  EXPECT_FALSE(start.Add(0.2, PlanFix{Vec2(1.0, 1.0), 0.1}).has_value());
  EXPECT_TRUE(start.Add(0.3, PlanFix{Vec2(1.05, 1.0), 0.1}).has_value());
}

TEST(MintEstimator, StartsItselfAfterTwoAgreeingEpochsNearTheTruth) {
  World world;
  world.floor_plan = SquareRoomWithPillar();
  world.anchors = {{"A1", Vec3(1.0, 5.0, 0.0)}, {"A2", Vec3(4.0, 1.5, 0.0)}};
  world.agents = {"agent"};
  world.physical.speed_mps = 0.5;
  MintEstimator estimator(MintOptions{}, world);
  const auto vas = Vas(world.floor_plan);
  core::Rng rng(11);
  const auto epoch_at = [&](double t_s, const Vec2& p_m) {
    core::Epoch epoch;
    epoch.t_s = t_s;
    for (auto set : MeasureRanges(vas, world.floor_plan, p_m, MeasurementModel{}, rng)) {
      set.t_s = t_s;
      epoch.range_sets.push_back(set);
    }
    return epoch;
  };

  EXPECT_FALSE(estimator.InitializeFromEpoch(epoch_at(0.0, Vec2(1.5, 1.5))));
  ASSERT_TRUE(estimator.InitializeFromEpoch(epoch_at(0.1, Vec2(1.55, 1.5))));
  const StepOutput out = estimator.Process(epoch_at(0.2, Vec2(1.6, 1.5)));

  EXPECT_LT((out.agents.front().position_m.head<2>() - Vec2(1.6, 1.5)).norm(), 0.08);
}

}  // namespace
}  // namespace mirage::methods::mint
