// SPDX-License-Identifier: MIT
// SLAM's start without a start point: a least-squares fix from three or more anchors, the floor
// plan's search with two, and no start at all where two anchors and no plan leave the two
// crossings of their range circles indistinguishable.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "methods/mint/square_room.h"
#include "mirage/methods/slam/slam_estimator.h"

namespace mirage::methods::slam {
namespace {

using mint::testing::MeasureRanges;
using mint::testing::MeasurementModel;

World RoomWorld(const std::vector<Vec2>& anchors, bool with_plan) {
  World world;
  if (with_plan) world.floor_plan = mint::testing::SquareRoomWithPillar();
  for (std::size_t i = 0; i < anchors.size(); ++i) {
    // Appended, not "A" + std::to_string(...): GCC 12's -Wrestrict misfires on that at -O2.
    std::string id = "A";
    id += std::to_string(i + 1);
    world.anchors.push_back({id, Vec3(anchors[i].x(), anchors[i].y(), 0.0)});
  }
  world.agents = {"agent"};
  world.physical.speed_mps = 0.5;
  return world;
}

// The ranges of the LOS and first-order reflections of the square room (with its pillar) at
// p_m, with 1 cm noise, as one epoch at t_s.
core::Epoch RoomEpoch(const std::vector<Vec2>& anchors, double t_s, const Vec2& p_m, core::Rng& rng) {
  const auto plan = mint::testing::SquareRoomWithPillar();
  const auto vas = geometry::VirtualAnchorSet::Generate(anchors, plan, 1);
  core::Epoch epoch;
  epoch.t_s = t_s;
  for (auto set : MeasureRanges(vas, plan, p_m, MeasurementModel{}, rng)) {
    set.t_s = t_s;
    epoch.range_sets.push_back(set);
  }
  return epoch;
}

TEST(SlamEstimator, StartsItselfFromTheFixOfThreeAnchorsWithoutAFloorPlan) {
  const std::vector<Vec2> anchors{Vec2(1.0, 5.0), Vec2(4.0, 1.5), Vec2(5.5, 5.5)};
  SlamEstimator estimator(SlamOptions{}, RoomWorld(anchors, false));
  core::Rng rng(2);
  const Vec2 agent(4.5, 3.0);  // every LOS clear of the pillar at (2.5, 3.0)

  ASSERT_TRUE(estimator.InitializeFromEpoch(RoomEpoch(anchors, 0.0, agent, rng)));
  const StepOutput out = estimator.Process(RoomEpoch(anchors, 0.1, agent, rng));

  EXPECT_LT((out.agents.front().position_m.head<2>() - agent).norm(), 0.05);
}

TEST(SlamEstimator, WaitsWhenTheEarliestRangesOfThreeAnchorsDisagree) {
  // A clutter range before one anchor's LOS: the fix's residuals are far above 3 sigma.
  const std::vector<Vec2> anchors{Vec2(1.0, 5.0), Vec2(4.0, 1.5), Vec2(5.5, 5.5)};
  SlamEstimator estimator(SlamOptions{}, RoomWorld(anchors, false));
  core::Rng rng(2);
  core::Epoch epoch = RoomEpoch(anchors, 0.0, Vec2(4.5, 3.0), rng);
  epoch.range_sets[1].ranges.push_back({0.8, 0.01});

  EXPECT_FALSE(estimator.InitializeFromEpoch(epoch));
}

TEST(SlamEstimator, NeverStartsFromTwoAnchorsWithoutAFloorPlan) {
  const std::vector<Vec2> anchors{Vec2(1.0, 5.0), Vec2(4.0, 1.5)};
  SlamEstimator estimator(SlamOptions{}, RoomWorld(anchors, false));
  core::Rng rng(4);
  for (int k = 0; k < 5; ++k) {
    EXPECT_FALSE(estimator.InitializeFromEpoch(RoomEpoch(anchors, 0.1 * k, Vec2(2.0, 2.5), rng)));
  }
}

TEST(SlamEstimator, StartsFromTwoAnchorsWithTheFloorPlansReflections) {
  const std::vector<Vec2> anchors{Vec2(1.0, 5.0), Vec2(4.0, 1.5)};
  SlamEstimator estimator(SlamOptions{}, RoomWorld(anchors, true));
  core::Rng rng(4);

  EXPECT_FALSE(estimator.InitializeFromEpoch(RoomEpoch(anchors, 0.0, Vec2(2.0, 2.5), rng)));
  ASSERT_TRUE(estimator.InitializeFromEpoch(RoomEpoch(anchors, 0.1, Vec2(2.05, 2.5), rng)));
  const StepOutput out = estimator.Process(RoomEpoch(anchors, 0.2, Vec2(2.1, 2.5), rng));

  EXPECT_LT((out.agents.front().position_m.head<2>() - Vec2(2.1, 2.5)).norm(), 0.08);
}

}  // namespace
}  // namespace mirage::methods::slam
