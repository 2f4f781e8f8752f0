// SPDX-License-Identifier: MIT
// The fix that survives wrong ranges: a wrong range that least squares absorbs with a height
// error (near-coplanar anchors) is left out by its deletion residual; an anchor whose earliest
// range is a false peak is re-admitted with its line of sight; a fix with no anchor to spare is
// marked unverified; too many wrong ranges give no fix.
#include "mirage/estimation/init/robust_position_fix.h"

#include <vector>

#include <gtest/gtest.h>

#include "mirage/core/rng.h"

namespace mirage::estimation {
namespace {

// Six anchors 2.5 m to 4 m high round a 20 m x 12 m hall (the range EKF's hold-out).
const std::vector<Vec3> kHall{Vec3(0.5, 0.5, 3.0),   Vec3(10.0, 0.3, 4.0),  Vec3(19.5, 0.5, 2.5),
                              Vec3(19.5, 11.5, 3.5), Vec3(10.0, 11.7, 2.5), Vec3(0.5, 11.5, 4.0)};
const Vec3 kTag(7.77, 6.84, 1.2);

std::vector<AnchorCandidates> Candidates(const Vec3& tag_m) {
  std::vector<AnchorCandidates> out;
  for (const auto& anchor_m : kHall) out.push_back({anchor_m, {(tag_m - anchor_m).norm()}});
  return out;
}

TEST(FixPositionRobust, UsesEveryAnchorWhenTheRangesAgree) {
  const auto fix = FixPositionRobust(Candidates(kTag), std::nullopt, 0.25, 9.0);
  ASSERT_TRUE(fix.has_value());
  EXPECT_LT((fix->fix.position_m - kTag).norm(), 1e-6);
  EXPECT_EQ(fix->anchors_used, 6);
  EXPECT_TRUE(fix->redundant);
}

// The true range to anchor 1 is missed and a false one 1.57 m short is left (a case from the
// hold-out). Least squares over all six trades it for a height 3.6 m off, with every residual
// inside a 3-sigma gate; the deletion residual of anchor 1 is not.
TEST(FixPositionRobust, LeavesOutAWrongRangeThatLeastSquaresAbsorbsInTheHeight) {
  auto candidates = Candidates(kTag);
  candidates[1].ranges_m = {(kTag - kHall[1]).norm() - 1.57};
  std::vector<Vec3> anchors_m;
  std::vector<double> ranges_m;
  for (const auto& c : candidates) {
    anchors_m.push_back(c.anchor_m);
    ranges_m.push_back(c.ranges_m.front());
  }
  const auto plain = FixPosition(anchors_m, ranges_m, std::nullopt, 0.25);
  ASSERT_TRUE(plain.has_value());
  EXPECT_GT((plain->position_m - kTag).norm(), 1.0) << "least squares no longer absorbs it: the case tests nothing";

  const auto fix = FixPositionRobust(candidates, std::nullopt, 0.25, 9.0);

  ASSERT_TRUE(fix.has_value());
  EXPECT_EQ(fix->range_index[1], -1);
  EXPECT_EQ(fix->anchors_used, 5);
  EXPECT_LT((fix->fix.position_m - kTag).norm(), 1e-3) << fix->fix.position_m.transpose();
}

TEST(FixPositionRobust, ReadmitsAnAnchorWhoseEarliestRangeIsAFalsePeak) {
  auto candidates = Candidates(kTag);
  const double true_m = candidates[3].ranges_m.front();
  candidates[3].ranges_m = {true_m - 4.0, true_m, true_m + 3.0};

  const auto fix = FixPositionRobust(candidates, std::nullopt, 0.25, 9.0);

  ASSERT_TRUE(fix.has_value());
  EXPECT_EQ(fix->range_index[3], 1);
  EXPECT_EQ(fix->anchors_used, 6);
  EXPECT_LT((fix->fix.position_m - kTag).norm(), 1e-6);
}

TEST(FixPositionRobust, MarksAFixWithNoAnchorToSpareAsUnverified) {
  // Three anchors and a known height: two unknowns, one range to spare.
  const std::vector<AnchorCandidates> three{{kHall[0], {(kTag - kHall[0]).norm()}},
                                            {kHall[2], {(kTag - kHall[2]).norm()}},
                                            {kHall[4], {(kTag - kHall[4]).norm()}}};
  const auto spare = FixPositionRobust(three, 1.2, 0.25, 9.0);
  ASSERT_TRUE(spare.has_value());
  EXPECT_TRUE(spare->redundant);
  // Three coplanar ceiling anchors in 3-D (the mirror rule fixes the height): nothing to spare.
  const Vec3 tag(2.0, 1.5, 1.0);
  std::vector<AnchorCandidates> ceiling;
  for (const Vec3& a : {Vec3(0, 0, 2.9), Vec3(6, 0, 2.9), Vec3(0, 5, 2.9)}) ceiling.push_back({a, {(tag - a).norm()}});
  const auto exact = FixPositionRobust(ceiling, std::nullopt, 0.25, 9.0);
  ASSERT_TRUE(exact.has_value());
  EXPECT_LT((exact->fix.position_m - tag).norm(), 1e-6);
  EXPECT_FALSE(exact->redundant);
}

TEST(FixPositionRobust, GivesNoFixWhenMostRangesAreWrong) {
  core::Rng rng(7);
  auto candidates = Candidates(kTag);
  for (int i = 0; i < 4; ++i) candidates[static_cast<std::size_t>(i)].ranges_m = {rng.Uniform(0.0, 40.0)};
  const auto fix = FixPositionRobust(candidates, std::nullopt, 0.25, 9.0);
  EXPECT_FALSE(fix.has_value()) << fix->fix.position_m.transpose();
}

// Noisy ranges, one wrong range in every other draw: the fix stays within the noise's reach.
TEST(FixPositionRobust, StaysNearTheTruthOverNoisyDrawsWithOneWrongRange) {
  core::Rng rng(11);
  int far = 0, none = 0;
  const int draws = 400;
  for (int k = 0; k < draws; ++k) {
    auto candidates = Candidates(kTag);
    for (auto& c : candidates) c.ranges_m.front() += rng.Normal(0.0, 0.1);
    if (k % 2 == 0) candidates[static_cast<std::size_t>(k / 2 % 6)].ranges_m = {rng.Uniform(0.0, 25.0)};
    const auto fix = FixPositionRobust(candidates, std::nullopt, 0.1, 9.0);
    if (!fix) {
      ++none;
      continue;
    }
    far += (fix->fix.position_m - kTag).norm() > 1.0 ? 1 : 0;
  }
  EXPECT_LE(far, draws / 100) << "fixes more than 1 m off";
  EXPECT_LE(none, draws / 20) << "draws without a fix";
}

}  // namespace
}  // namespace mirage::estimation
