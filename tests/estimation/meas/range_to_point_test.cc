// SPDX-License-Identifier: MIT
// Range to a fixed point: 3-D agents, and planar agents at a known height under 3-D anchors;
// prediction and Jacobian against central differences at generic, near-degenerate and seeded
// random points, and the degenerate case.
#include "mirage/estimation/meas/range_to_point.h"

#include <vector>

#include <gtest/gtest.h>

#include "estimation/jacobian_check.h"
#include "mirage/core/rng.h"
#include "rng_vectors.h"

namespace mirage::estimation {
namespace {

using testing::ExpectRowsMatchCentralDifferences;

State AgentState(const Eigen::VectorXd& position, const BlockType& type) {
  StateLayout layout;
  layout.Append(blocks::kWallOffset, 0);  // a block before the agent, so offsets are not 0
  layout.Append(type, 0);
  Eigen::VectorXd mean(1 + position.size());
  mean << 0.1, position;
  return State(layout, mean, Eigen::MatrixXd::Identity(mean.size(), mean.size()), 0.0);
}

TEST(RangeToPointRow, ThreeDimensionalRangeAndJacobianMatchCentralDifferences) {
  core::Rng rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3 p = mirage::testing::UniformVec3(rng, Vec3(-5, -5, 0), Vec3(5, 5, 3));
    const Vec3 anchor = mirage::testing::UniformVec3(rng, Vec3(-5, -5, 0), Vec3(5, 5, 3));
    const State state = AgentState(p, blocks::kPosition3);
    const Block position = state.layout().At(BlockKey(blocks::kPosition3, 0));
    const auto row = RangeToPointRow(state, position, anchor, 0.0, 0.01);
    ASSERT_TRUE(row.has_value());
    const std::vector<MeasurementRow> rows{*row};
    ExpectRowsMatchCentralDifferences(
        state, rows, [&](const State& s, std::size_t) { return (s.Mean(position.key) - anchor).norm(); }, 1e-5, 1e-8);
    EXPECT_DOUBLE_EQ(row->variance, 0.01);
  }
}

TEST(RangeToPointRow, PlanarAgentAtAKnownHeightSeesTheThreeDimensionalRange) {
  // Tag at 0.6 m, anchor at 2.9 m, 3 m apart in the plane: range sqrt(9 + 2.3^2).
  const State state = AgentState(Eigen::Vector2d(1.0, 1.0), blocks::kPosition);
  const Block position = state.layout().At(BlockKey(blocks::kPosition, 0));
  const Vec3 anchor(4.0, 1.0, 2.9);

  const auto row = RangeToPointRow(state, position, anchor, 0.6, 0.01);

  ASSERT_TRUE(row.has_value());
  EXPECT_NEAR(row->predicted, std::sqrt(9.0 + 2.3 * 2.3), 1e-12);
  const std::vector<MeasurementRow> rows{*row};
  ExpectRowsMatchCentralDifferences(
      state, rows,
      [&](const State& s, std::size_t) {
        const Vec2 d = Vec2(s.Mean(position.key)) - anchor.head<2>();
        return std::sqrt(d.squaredNorm() + (0.6 - 2.9) * (0.6 - 2.9));
      },
      1e-5, 1e-8);
  // The height difference shortens the horizontal derivative: 3 / range, not 1.
  EXPECT_NEAR(row->jacobians[0](0), -3.0 / row->predicted, 1e-12);
}

TEST(RangeToPointRow, NearTheAnchorTheJacobianStillMatchesAndOnItNothingIsReturned) {
  const Vec3 anchor(1.0, 2.0, 3.0);
  const State near = AgentState(Eigen::Vector3d(1.0 + 2e-3, 2.0, 3.0 + 1e-3), blocks::kPosition3);
  const Block position = near.layout().At(BlockKey(blocks::kPosition3, 0));
  const auto row = RangeToPointRow(near, position, anchor, 0.0, 1.0);
  ASSERT_TRUE(row.has_value());
  const std::vector<MeasurementRow> rows{*row};
  ExpectRowsMatchCentralDifferences(
      near, rows, [&](const State& s, std::size_t) { return (s.Mean(position.key) - anchor).norm(); }, 1e-7, 1e-5);

  const State on = AgentState(Eigen::Vector3d(1.0, 2.0, 3.0 + 1e-4), blocks::kPosition3);
  EXPECT_FALSE(RangeToPointRow(on, on.layout().At(BlockKey(blocks::kPosition3, 0)), anchor, 0.0, 1.0).has_value());
}

}  // namespace
}  // namespace mirage::estimation
