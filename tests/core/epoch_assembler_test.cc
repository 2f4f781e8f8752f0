// SPDX-License-Identifier: MIT
// The epoch rule: records with equal times (window 0) or within the window of an epoch's first
// record form one epoch, kinds kept apart and in time order; a later record closes the epoch;
// records older than the open epoch are counted as out of order and dropped.
#include "mirage/core/epoch_assembler.h"

#include <vector>

#include <gtest/gtest.h>

namespace mirage::core {
namespace {

RangeSet Ranges(double t_s, int anchor) {
  RangeSet r;
  r.t_s = t_s;
  r.anchor_index = anchor;
  r.anchor_id = std::to_string(anchor);
  r.anchor_id.insert(0, 1, 'A');
  r.ranges = {{1.0 + anchor, std::nullopt}};
  return r;
}

ImuSample Imu(double t_s) {
  ImuSample s;
  s.t_s = t_s;
  s.sensor_id = "imu";
  return s;
}

std::vector<Epoch> Assemble(EpochAssembler& assembler, const std::vector<double>& range_times) {
  std::vector<Epoch> epochs;
  for (std::size_t i = 0; i < range_times.size(); ++i) {
    if (auto e = assembler.Add(Ranges(range_times[i], static_cast<int>(i)))) epochs.push_back(std::move(*e));
  }
  if (auto e = assembler.Flush()) epochs.push_back(std::move(*e));
  return epochs;
}

TEST(EpochAssembler, RecordsWithEqualTimesFormOneEpochAtWindowZero) {
  EpochAssembler assembler;
  const auto epochs = Assemble(assembler, {0.0, 0.0, 0.1, 0.1, 0.1, 0.2});

  ASSERT_EQ(epochs.size(), 3u);
  EXPECT_EQ(epochs[0].range_sets.size(), 2u);
  EXPECT_EQ(epochs[1].range_sets.size(), 3u);
  EXPECT_EQ(epochs[2].range_sets.size(), 1u);
  EXPECT_DOUBLE_EQ(epochs[1].t_s, 0.1);
  EXPECT_EQ(epochs[1].range_sets[0].anchor_id, "A2");
  EXPECT_EQ(assembler.out_of_order(), 0);
}

TEST(EpochAssembler, AWindowGroupsStaggeredRecordsAndKeepsThemInTimeOrder) {
  // A TWR system that ranges one anchor after the other every 25 ms, in 100 ms rounds.
  EpochAssembler assembler(0.08);
  const auto epochs = Assemble(assembler, {0.000, 0.050, 0.025, 0.075, 0.100, 0.125});

  ASSERT_EQ(epochs.size(), 2u);
  ASSERT_EQ(epochs[0].range_sets.size(), 4u);
  EXPECT_DOUBLE_EQ(epochs[0].range_sets[1].t_s, 0.025);  // sorted, though it arrived third
  EXPECT_DOUBLE_EQ(epochs[0].range_sets[3].t_s, 0.075);
  EXPECT_DOUBLE_EQ(epochs[1].t_s, 0.1);
}

TEST(EpochAssembler, CountsAndDropsRecordsOlderThanTheOpenEpoch) {
  EpochAssembler assembler;
  const auto epochs = Assemble(assembler, {0.0, 0.1, 0.05, 0.2, 0.1});

  ASSERT_EQ(epochs.size(), 3u);
  EXPECT_EQ(assembler.out_of_order(), 2);
  std::size_t kept = 0;
  for (const auto& e : epochs) kept += e.size();
  EXPECT_EQ(kept, 3u);
}

TEST(EpochAssembler, KindsGoToTheirOwnListsOfTheSameEpoch) {
  EpochAssembler assembler;
  EXPECT_FALSE(assembler.Add(Ranges(1.0, 0)).has_value());
  EXPECT_FALSE(assembler.Add(Imu(1.0)).has_value());
  const auto closed = assembler.Add(Imu(1.01));

  ASSERT_TRUE(closed.has_value());
  EXPECT_EQ(closed->range_sets.size(), 1u);
  EXPECT_EQ(closed->imus.size(), 1u);
  EXPECT_EQ(closed->size(), 2u);
  EXPECT_FALSE(closed->empty());
}

}  // namespace
}  // namespace mirage::core
