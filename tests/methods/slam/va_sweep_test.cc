// SPDX-License-Identifier: MIT
// The sweep's buffers and schedule: each anchor searched on its own steps, only the last
// window_s seconds kept, the ranges of a find spent, nothing before the walk spans the minimum
// baseline, non-finite ranges dropped, and Reset forgets everything. The search itself is
// estimation/init/range_consensus (tested there); the candidates it starts, VaDiscovery's.
#include "mirage/methods/slam/va_sweep.h"

#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "core/options_descriptor_expectations.h"
#include "mirage/core/rng.h"

namespace mirage::methods::slam {
namespace {

// A point 9.5 m ahead of a walk along y = 1 in 5 cm steps, seen at every step among 10 clutter
// ranges uniform over [0, 15] m.
const Vec2 kPoint_m(12.0, 3.0);
const Vec2 kMirror_m(12.0, -1.0);

std::vector<core::RangeMeasurement> RangesAt(const Vec2& agent_m, core::Rng& rng, bool with_point = true) {
  std::vector<core::RangeMeasurement> ranges;
  if (with_point) ranges.push_back({(kPoint_m - agent_m).norm() + rng.Normal(0.0, 0.01), std::nullopt});
  for (int c = 0; c < 10; ++c) ranges.push_back({rng.Uniform(0.0, 15.0), std::nullopt});
  return ranges;
}

Vec2 AgentAt(int step) { return Vec2(0.05 * step, 1.0); }

// Buffers steps [first, last] for the anchor.
void Walk(VaSweep& sweep, int anchor_index, int first, int last, core::Rng& rng, bool with_point = true) {
  for (int step = first; step <= last; ++step) {
    const auto ranges = RangesAt(AgentAt(step), rng, with_point);
    sweep.Buffer(0.1 * step, anchor_index, AgentAt(step), ranges, std::vector<bool>(ranges.size(), false));
  }
}

bool AtThePoint(const SweepFind& find) {
  for (const Vec2& start : find.starts) {
    if (std::min((start - kPoint_m).norm(), (start - kMirror_m).norm()) < 0.3) return true;
  }
  return false;
}

TEST(VaSweep, SearchesEachAnchorOnItsOwnSteps) {
  SweepOptions options;  // every 5 steps: anchor 0 at steps 0, 5, ..., anchor 1 at 4, 9, ...
  VaSweep sweep(options, 10, 0.2);
  core::Rng rng(1, 0);
  Walk(sweep, 0, 0, 40, rng);
  Walk(sweep, 1, 0, 40, rng);
  EXPECT_FALSE(sweep.Search(41, 0, {}));
  EXPECT_FALSE(sweep.Search(40, 1, {}));
  const auto found_0 = sweep.Search(40, 0, {});
  ASSERT_TRUE(found_0);
  EXPECT_TRUE(AtThePoint(*found_0));
  const auto found_1 = sweep.Search(44, 1, {});
  ASSERT_TRUE(found_1);
  EXPECT_TRUE(AtThePoint(*found_1));
}

TEST(VaSweep, KeepsOnlyTheLastWindowSteps) {
  SweepOptions options;
  options.window_s = 2.0;  // 20 steps of 0.1 s
  VaSweep sweep(options, 10, 0.2);
  core::Rng rng(2, 0);
  Walk(sweep, 0, 0, 100, rng);
  EXPECT_EQ(sweep.buffered_steps(0), 20u);
  EXPECT_EQ(sweep.buffered_steps(1), 0u);
}

TEST(VaSweep, TheRangesOfAFindAreSpent) {
  VaSweep sweep(SweepOptions{}, 10, 0.2);
  core::Rng rng(3, 0);
  Walk(sweep, 0, 0, 40, rng);
  const std::size_t before = sweep.buffered_ranges(0);
  const auto found = sweep.Search(40, 0, {});
  ASSERT_TRUE(found);
  EXPECT_GE(found->samples.size(), 35u);
  EXPECT_EQ(sweep.buffered_ranges(0), before - found->samples.size());
  // Five steps later, without the point in the new steps: its old ranges are gone, and the five
  // new steps alone are too few.
  Walk(sweep, 0, 41, 45, rng, false);
  EXPECT_FALSE(sweep.Search(45, 0, {}));
}

TEST(VaSweep, SearchesNothingBeforeTheWalkSpansTheMinimumBaseline) {
  SweepOptions options;
  options.min_baseline_m = 1.0;
  VaSweep sweep(options, 10, 0.2);
  core::Rng rng(4, 0);
  Walk(sweep, 0, 0, 15, rng);  // 0.75 m
  EXPECT_FALSE(sweep.Search(15, 0, {}));
  Walk(sweep, 0, 16, 25, rng);  // 1.25 m
  EXPECT_TRUE(sweep.Search(25, 0, {}));
}

TEST(VaSweep, DropsNonFiniteRanges) {
  VaSweep sweep(SweepOptions{}, 10, 0.2);
  core::Rng rng(5, 0);
  std::size_t finite = 0;
  for (int step = 0; step <= 40; ++step) {
    auto ranges = RangesAt(AgentAt(step), rng);
    finite += ranges.size();
    ranges.push_back({std::numeric_limits<double>::quiet_NaN(), std::nullopt});
    ranges.push_back({std::numeric_limits<double>::infinity(), std::nullopt});
    sweep.Buffer(0.1 * step, 0, AgentAt(step), ranges, std::vector<bool>(ranges.size(), false));
  }
  EXPECT_EQ(sweep.buffered_ranges(0), finite);
  const auto found = sweep.Search(40, 0, {});
  ASSERT_TRUE(found);
  for (const auto& s : found->samples) EXPECT_TRUE(std::isfinite(s.range_m));
}

TEST(VaSweep, ResetForgetsTheBuffers) {
  VaSweep sweep(SweepOptions{}, 10, 0.2);
  core::Rng rng(6, 0);
  Walk(sweep, 0, 0, 40, rng);
  sweep.Reset();
  EXPECT_EQ(sweep.buffered_steps(0), 0u);
  EXPECT_EQ(sweep.buffered_ranges(0), 0u);
  EXPECT_FALSE(sweep.Search(40, 0, {}));
}

TEST(SweepOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMember) {
  test::ExpectDescribesEveryMember(SweepOptionsDescriptor(), {"enabled", "window_s", "every_steps",
                                                              "min_baseline_m", "gate_m", "min_support_fraction"});
}

}  // namespace
}  // namespace mirage::methods::slam
