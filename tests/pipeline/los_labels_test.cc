// SPDX-License-Identifier: MIT
// The LOS labels of one epoch against the simulation's: a labelled direct stamp is a true
// positive; a labelled other stamp a false positive, and a false negative too when its record
// has a direct stamp; a record with a direct stamp and no label (also at an emission without a
// fix) a false negative; mismatched shapes give no count.
#include "mirage/pipeline/los_labels.h"

#include <gtest/gtest.h>

namespace mirage::pipeline {
namespace {

core::Epoch ThreeRecords() {
  core::Epoch epoch;
  for (int m = 0; m < 3; ++m) {
    core::ToaStamps record;
    record.receiver_index = m;
    record.toa_s = {0.010 + 0.001 * m, 0.015 + 0.001 * m};
    epoch.toas.push_back(record);
  }
  return epoch;
}

TEST(CountLosLabels, CountsEachRecordOnce) {
  const core::Epoch epoch = ThreeRecords();
  // Record 0: the first stamp is direct; record 1: the second; record 2: none (a blocked path).
  const std::vector<std::vector<bool>> direct{{true, false}, {false, true}, {false, false}};
  // Labels: record 0 right, record 1 wrong (the echo), record 2 a stamp although none is direct.
  const auto count = CountLosLabels(epoch, direct, {0, 0, 1});
  ASSERT_TRUE(count.has_value());
  EXPECT_EQ(count->true_positives, 1);
  EXPECT_EQ(count->false_positives, 2);
  EXPECT_EQ(count->false_negatives, 1);
  EXPECT_DOUBLE_EQ(count->Precision().value(), 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(count->Recall().value(), 0.5);
  // No fix: every record with a direct stamp is missed, nothing is labelled wrongly.
  const auto none = CountLosLabels(epoch, direct, {-1, -1, -1});
  ASSERT_TRUE(none.has_value());
  EXPECT_EQ(none->true_positives, 0);
  EXPECT_EQ(none->false_positives, 0);
  EXPECT_EQ(none->false_negatives, 2);
  EXPECT_FALSE(none->Precision().has_value());  // nothing labelled: no precision, not 0
  LosLabelCount sum = *count;
  sum += *none;
  EXPECT_DOUBLE_EQ(sum.Recall().value(), 0.25);
}

TEST(CountLosLabels, GivesNoCountWithoutLabelsOrWithMismatchedShapes) {
  const core::Epoch epoch = ThreeRecords();
  const std::vector<std::vector<bool>> direct{{true, false}, {false, true}, {false, false}};
  EXPECT_FALSE(CountLosLabels(epoch, direct, {}).has_value());      // the method labels nothing
  EXPECT_FALSE(CountLosLabels(epoch, {}, {0, 1, -1}).has_value());  // no simulation labels
  EXPECT_FALSE(CountLosLabels(epoch, {{true, false}, {false, true}, {false}}, {0, 1, -1}).has_value());
  EXPECT_FALSE(CountLosLabels(epoch, direct, {0, 2, -1}).has_value());  // no such stamp
  // An epoch without stamp records (a UWB source): no count, not a count of zeros.
  EXPECT_FALSE(CountLosLabels(core::Epoch{}, {}, {}).has_value());
}

}  // namespace
}  // namespace mirage::pipeline
