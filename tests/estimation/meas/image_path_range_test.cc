// SPDX-License-Identifier: MIT
// The coop link model: the row of a specular path between antennas carried by agents (or fixed),
// over walls whose normal offsets are in the state, against central differences of the
// image-source length over every state coordinate: an agent's own channel, a channel between two
// agents, and a channel from a fixed anchor, first- and second-order paths, with and without
// the walls in the state.
#include "mirage/estimation/meas/image_path_range.h"

#include <vector>

#include <gtest/gtest.h>

#include "estimation/jacobian_check.h"
#include "mirage/geometry/image_source.h"

namespace mirage::estimation {
namespace {

using geometry::FloorPlan;
using geometry::Wall;
using testing::ExpectRowsMatchCentralDifferences;

FloorPlan Room() {
  return FloorPlan({Wall{Vec2(0, 0), Vec2(5, 0), 0.5, "south"}, Wall{Vec2(5, 0), Vec2(5, 4), 0.5, "east"},
                    Wall{Vec2(5, 4), Vec2(0, 4), 0.5, "north"}, Wall{Vec2(0, 4), Vec2(0, 0), 0.5, "west"}},
                   {});
}

const Vec2 kTxOffset(0.025, 0.0);
const Vec2 kRxOffset(-0.025, 0.0);
const Vec2 kAnchorAt(4.5, 3.5);

// [agent 0 position, velocity | agent 1 position, velocity | wall offsets 0..3 when with_walls].
State TwoAgents(bool with_walls) {
  StateLayout layout;
  for (int m = 0; m < 2; ++m) {
    layout.Append(blocks::kPosition, m);
    layout.Append(blocks::kVelocity, m);
  }
  if (with_walls) {
    for (int s = 0; s < 4; ++s) layout.Append(blocks::kWallOffset, s);
  }
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(layout.mean_dimension());
  mean.head<8>() << 1.2, 1.1, 0.1, 0.0, 3.6, 2.7, 0.0, -0.1;
  if (with_walls) mean.tail<4>() << 0.01, -0.02, 0.005, 0.0;
  return State(layout, mean, Eigen::MatrixXd::Identity(mean.size(), mean.size()), 0.0);
}

// The plan with each wall moved along its normal by its offset in the state (0 without walls).
FloorPlan PlanAt(const State& state) {
  std::vector<Wall> walls = Room().walls();
  for (int s = 0; s < 4; ++s) {
    const auto block = state.layout().Find(BlockKey(blocks::kWallOffset, s));
    if (!block) continue;
    const Vec2 shift = state.mean()(block->mean_offset) * geometry::WallNormal(walls[static_cast<std::size_t>(s)]);
    walls[static_cast<std::size_t>(s)].start_m += shift;
    walls[static_cast<std::size_t>(s)].end_m += shift;
  }
  return FloorPlan(walls, {});
}

Vec2 Agent(const State& state, int m) { return state.Mean(BlockKey(blocks::kPosition, m)); }

enum class Link { kSelf, kRelative, kAnchor };

struct Ends {
  Vec2 tx, rx;
};

Ends EndsAt(const State& state, Link link) {
  switch (link) {
    case Link::kSelf: return {Agent(state, 0) + kTxOffset, Agent(state, 0) + kRxOffset};
    case Link::kRelative: return {Agent(state, 0) + kTxOffset, Agent(state, 1) + kRxOffset};
    case Link::kAnchor: break;
  }
  return {kAnchorAt, Agent(state, 1) + kRxOffset};
}

void ExpectLinkRowsMatch(Link link, bool with_walls) {
  const State state = TwoAgents(with_walls);
  const Ends ends = EndsAt(state, link);
  const std::optional<Block> a0 = state.layout().At(BlockKey(blocks::kPosition, 0));
  const std::optional<Block> a1 = state.layout().At(BlockKey(blocks::kPosition, 1));
  const std::optional<Block> tx = link == Link::kAnchor ? std::nullopt : a0;
  const std::optional<Block> rx = link == Link::kRelative || link == Link::kAnchor ? a1 : a0;
  std::vector<MeasurementRow> rows;
  std::vector<geometry::WallSequence> sequences;
  const FloorPlan plan = PlanAt(state);
  for (const auto& walls : geometry::VisibleImagePaths(plan, ends.tx, ends.rx, 2)) {
    if (walls.empty()) continue;  // the coupling / line of sight has no walls; order >= 1 here
    std::vector<std::optional<Block>> wall_blocks;
    for (const int w : walls) {
      wall_blocks.push_back(with_walls ? state.layout().Find(BlockKey(blocks::kWallOffset, w)) : std::nullopt);
    }
    const auto path = geometry::ComputeImagePath(plan, walls, ends.tx, ends.rx);
    rows.push_back(ImagePathRangeRow(path, tx, rx, with_walls ? std::span(wall_blocks) : std::span<const std::optional<Block>>(), 0.01));
    sequences.push_back(walls);
  }
  ASSERT_GE(rows.size(), 10u);
  ExpectRowsMatchCentralDifferences(
      state, rows,
      [&](const State& s, std::size_t i) {
        const Ends e = EndsAt(s, link);
        return geometry::ComputeImagePath(PlanAt(s), sequences[i], e.tx, e.rx).length_m;
      },
      1e-6, 1e-7, with_walls ? "with walls" : "without walls");
}

TEST(ImagePathRangeRow, AnAgentsOwnChannelGetsTheTotalDerivativeAndTheWallOffsets) {
  ExpectLinkRowsMatch(Link::kSelf, true);
  ExpectLinkRowsMatch(Link::kSelf, false);
}

TEST(ImagePathRangeRow, AChannelBetweenTwoAgentsMovesWithBoth) {
  ExpectLinkRowsMatch(Link::kRelative, true);
  ExpectLinkRowsMatch(Link::kRelative, false);
}

TEST(ImagePathRangeRow, AChannelFromAFixedAnchorMovesOnlyWithTheReceiver) {
  ExpectLinkRowsMatch(Link::kAnchor, true);
  ExpectLinkRowsMatch(Link::kAnchor, false);
}

}  // namespace
}  // namespace mirage::estimation
