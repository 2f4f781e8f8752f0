// SPDX-License-Identifier: MIT
#include "mirage/estimation/state.h"

#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

namespace mirage::estimation {
namespace {

constexpr BlockKey kPos0(blocks::kPosition, 0);
constexpr BlockKey kVel0(blocks::kVelocity, 0);
constexpr BlockKey kVa7(blocks::kVirtualAnchor, 7);
constexpr BlockKey kVa9(blocks::kVirtualAnchor, 9);
constexpr BlockKey kWall2(blocks::kWallOffset, 2);

// [pos0 (2) | vel0 (2) | va7 (2) | wall2 (1) | va9 (2)] -> offsets 0, 2, 4, 6, 7; dimension 9.
StateLayout FiveBlockLayout() {
  StateLayout layout;
  layout.Append(blocks::kPosition, 0);
  layout.Append(blocks::kVelocity, 0);
  layout.Append(blocks::kVirtualAnchor, 7);
  layout.Append(blocks::kWallOffset, 2);
  layout.Append(blocks::kVirtualAnchor, 9);
  return layout;
}

void ExpectBlock(const StateLayout& layout, BlockKey key, int offset, int size) {
  const auto block = layout.Find(key);
  ASSERT_TRUE(block.has_value());
  EXPECT_EQ(block->offset, offset);
  EXPECT_EQ(block->size, size);
  EXPECT_EQ(block->key, key);
}

// ---------------------------------------------------------------------------------------------
// StateLayout
// ---------------------------------------------------------------------------------------------

TEST(StateLayout, AppendReturnsConsecutiveOffsetsAndGrowsTheDimension) {
  StateLayout layout;

  EXPECT_EQ(layout.Append(blocks::kPosition, 0), 0);
  EXPECT_EQ(layout.Append(blocks::kVelocity, 0), 2);
  EXPECT_EQ(layout.Append(blocks::kWallOffset, 2), 4);
  EXPECT_EQ(layout.Append(blocks::kVirtualAnchor, 7), 5);
  EXPECT_EQ(layout.dimension(), 7);
  ASSERT_EQ(layout.blocks().size(), 4U);
  EXPECT_EQ(layout.blocks()[2].key, kWall2);
}

TEST(StateLayout, FindDistinguishesKeysByKindAndId) {
  const StateLayout layout = FiveBlockLayout();

  ExpectBlock(layout, kVa7, 4, 2);
  ExpectBlock(layout, kVa9, 7, 2);
  EXPECT_FALSE(layout.Find(BlockKey(blocks::kVirtualAnchor, 8)).has_value());
  EXPECT_FALSE(layout.Find(BlockKey(blocks::kPosition, 1)).has_value());
  // Same id, other kind.
  EXPECT_FALSE(layout.Find(BlockKey(blocks::kWallOffset, 7)).has_value());
}

TEST(StateLayout, AtReturnsTheSameBlockAsFind) {
  const StateLayout layout = FiveBlockLayout();

  const Block block = layout.At(kWall2);

  EXPECT_EQ(block.key, kWall2);
  EXPECT_EQ(block.offset, 6);
  EXPECT_EQ(block.size, 1);
}

TEST(StateLayout, RemovingAMiddleBlockShiftsOnlyTheLaterOffsets) {
  StateLayout layout = FiveBlockLayout();

  layout.Remove(kVa7);  // size 2 at offset 4

  EXPECT_EQ(layout.dimension(), 7);
  EXPECT_FALSE(layout.Find(kVa7).has_value());
  ExpectBlock(layout, kPos0, 0, 2);
  ExpectBlock(layout, kVel0, 2, 2);
  ExpectBlock(layout, kWall2, 4, 1);  // 6 - 2
  ExpectBlock(layout, kVa9, 5, 2);    // 7 - 2
  ASSERT_EQ(layout.blocks().size(), 4U);
  EXPECT_EQ(layout.blocks()[2].key, kWall2);  // order kept
  EXPECT_EQ(layout.blocks()[3].key, kVa9);
}

TEST(StateLayout, RemovingTheFirstBlockShiftsEveryOffset) {
  StateLayout layout = FiveBlockLayout();

  layout.Remove(kPos0);

  EXPECT_EQ(layout.dimension(), 7);
  ExpectBlock(layout, kVel0, 0, 2);
  ExpectBlock(layout, kVa7, 2, 2);
  ExpectBlock(layout, kWall2, 4, 1);
  ExpectBlock(layout, kVa9, 5, 2);
}

TEST(StateLayout, RemovingTheLastBlockLeavesTheOthersInPlace) {
  StateLayout layout = FiveBlockLayout();

  layout.Remove(kVa9);

  EXPECT_EQ(layout.dimension(), 7);
  ExpectBlock(layout, kWall2, 6, 1);
  EXPECT_FALSE(layout.Find(kVa9).has_value());
}

TEST(StateLayout, AppendAfterRemoveStartsAtTheNewEnd) {
  StateLayout layout = FiveBlockLayout();
  layout.Remove(kWall2);  // dimension 9 -> 8

  const int offset = layout.Append(blocks::kWallOffset, 2);

  EXPECT_EQ(offset, 8);
  EXPECT_EQ(layout.dimension(), 9);
  ExpectBlock(layout, kVa9, 6, 2);
  EXPECT_EQ(layout.blocks().back().key, kWall2);
}

// ---------------------------------------------------------------------------------------------
// State
// ---------------------------------------------------------------------------------------------

// Mean 0, 1, ..., 8 and covariance P(i, j) = 10 i + j, so every entry names its position.
State NumberedState() {
  Eigen::VectorXd mean(9);
  Eigen::MatrixXd P(9, 9);
  for (int i = 0; i < 9; ++i) {
    mean(i) = i;
    for (int j = 0; j < 9; ++j) P(i, j) = 10.0 * i + j;
  }
  return State(FiveBlockLayout(), mean, P, 2.5);
}

TEST(State, ExposesDimensionTimeAndTheFullMeanAndCovariance) {
  const State state = NumberedState();

  EXPECT_EQ(state.dimension(), 9);
  EXPECT_DOUBLE_EQ(state.t_s(), 2.5);
  EXPECT_DOUBLE_EQ(state.mean()(8), 8.0);
  EXPECT_DOUBLE_EQ(state.covariance()(3, 7), 37.0);
}

TEST(State, MeanOfABlockIsItsSegment) {
  const State state = NumberedState();

  EXPECT_EQ(state.Mean(kVa7), Eigen::Vector2d(4, 5));
  EXPECT_EQ(state.Mean(kWall2), Eigen::VectorXd::Constant(1, 6.0));
  EXPECT_EQ(state.Mean(kVa9), Eigen::Vector2d(7, 8));
}

TEST(State, CovarianceOfABlockIsItsDiagonalBlock) {
  const State state = NumberedState();

  Eigen::Matrix2d expected_va9;
  expected_va9 << 77, 78, 87, 88;  // rows/cols 7-8
  EXPECT_EQ(state.Covariance(kVa9), Eigen::MatrixXd(expected_va9));
  EXPECT_EQ(state.Covariance(kWall2), Eigen::MatrixXd::Constant(1, 1, 66.0));
}

TEST(State, SetMeanWritesOnlyThatBlockAndLeavesTheCovariance) {
  State state = NumberedState();
  const Eigen::MatrixXd P_before = state.covariance();

  state.SetMean(kVel0, Eigen::Vector2d(-1.5, 0.25));

  Eigen::VectorXd expected(9);
  expected << 0, 1, -1.5, 0.25, 4, 5, 6, 7, 8;
  EXPECT_EQ(state.mean(), expected);
  EXPECT_EQ(state.covariance(), P_before);
}

TEST(State, DefaultConstructedStateIsEmpty) {
  const State state;

  EXPECT_EQ(state.dimension(), 0);
  EXPECT_EQ(state.mean().size(), 0);
  EXPECT_DOUBLE_EQ(state.t_s(), 0.0);
}

}  // namespace
}  // namespace mirage::estimation
