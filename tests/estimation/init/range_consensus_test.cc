// SPDX-License-Identifier: MIT
// The consensus search for a point seen in unlabeled ranges: found among clutter from a straight
// walk with missed scans (with its mirror image about the walk), never returned below the support
// it needs, refined by its supporting ranges when the proposing ones are off, not proposed where
// excluded, and nothing from clutter alone.
#include "mirage/estimation/init/range_consensus.h"

#include <algorithm>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/core/rng.h"

namespace mirage::estimation {
namespace {

// 60 scans 5 cm apart along y = 1; the point 9.5 m ahead and 2 m to the side, mirror about y = 1.
const Vec2 kPoint_m(12.0, 3.0);
const Vec2 kMirror_m(12.0, -1.0);
constexpr int kScans = 60;

struct Signal {
  bool with_point = true;
  double detection = 0.75;
  double clutter_per_scan = 15.0;  // Poisson count, uniform over [0, 15] m
};

struct Recording {
  std::vector<RangeScan> scans;
  std::vector<bool> saw;  // the point's range is in the scan
};

Recording Record(const Signal& signal, std::uint64_t seed) {
  core::Rng rng(seed, 0);
  Recording out;
  for (int k = 0; k < kScans; ++k) {
    RangeScan scan;
    scan.position_m = Vec2(0.05 * k, 1.0);
    const bool saw = signal.with_point && rng.Uniform() < signal.detection;
    if (saw) scan.ranges_m.push_back((kPoint_m - scan.position_m).norm() + rng.Normal(0.0, 0.01));
    const int clutter = rng.Poisson(signal.clutter_per_scan);
    for (int c = 0; c < clutter; ++c) scan.ranges_m.push_back(rng.Uniform(0.0, 15.0));
    std::sort(scan.ranges_m.begin(), scan.ranges_m.end());
    out.scans.push_back(std::move(scan));
    out.saw.push_back(saw);
  }
  return out;
}

std::vector<RangeScan> Scans(const Signal& signal, std::uint64_t seed) { return Record(signal, seed).scans; }

// Proposals come from the scan pairs (0, n-1), (n/8, n-1-n/8) and (n/4, n-1-n/4) only: the point
// is found if both scans of one of them saw it (otherwise at a later sweep of a sliding buffer).
bool AProposingPairSawIt(const std::vector<bool>& saw) {
  for (const int offset : {0, kScans / 8, kScans / 4}) {
    if (saw[static_cast<std::size_t>(offset)] && saw[static_cast<std::size_t>(kScans - 1 - offset)]) return true;
  }
  return false;
}

RangeConsensusOptions SixtyPercent() {
  RangeConsensusOptions options;
  options.min_support = kScans * 6 / 10;
  return options;
}

TEST(RangeConsensus, FindsAFarPointAmongClutterDespiteMissedScans) {
  int tested = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const Recording recording = Record({}, seed);
    if (!AProposingPairSawIt(recording.saw)) continue;
    ++tested;
    const auto& scans = recording.scans;
    const auto found = FindRangeConsensus(scans, {}, SixtyPercent());
    ASSERT_TRUE(found) << "seed " << seed;
    // A straight walk cannot tell the point from its mirror image: either may come first. Ranges
    // from 3 m of straight walk place a point 9.5 m away to 9.4 cm (CRLB, worst direction, 1 cm
    // range noise, 45 ranges): within three of those.
    const bool direct = (found->position_m - kPoint_m).norm() < (found->position_m - kMirror_m).norm();
    const Vec2 expected_m = direct ? kPoint_m : kMirror_m;
    const Vec2 expected_mirror_m = direct ? kMirror_m : kPoint_m;
    EXPECT_LT((found->position_m - expected_m).norm(), 0.28)
        << "seed " << seed << ": " << found->position_m.transpose();
    EXPECT_LT((found->mirror_m - expected_mirror_m).norm(), 0.28) << "seed " << seed;
    // The support is the point's own ranges, all of them but for a few near the gate's edge.
    const auto seen = static_cast<std::size_t>(std::count(recording.saw.begin(), recording.saw.end(), true));
    std::size_t own = 0;
    for (const auto& [k, j] : found->support) {
      if (recording.saw[k] && std::abs(scans[k].ranges_m[j] - (kPoint_m - scans[k].position_m).norm()) < 0.04) ++own;
    }
    EXPECT_GE(found->support.size(), static_cast<std::size_t>(kScans * 6 / 10)) << "seed " << seed;
    EXPECT_GE(own + 3, seen) << "seed " << seed;
    EXPECT_LE(found->support.size(), own + 3) << "seed " << seed << ": clutter in the support";
  }
  EXPECT_GE(tested, 3) << "too few seeds had a proposing pair that saw the point";
}

TEST(RangeConsensus, RefinesAPoorProposalByItsSupportingRanges) {
  // Only the first and last scans propose (the inner proposing scans, n/8 and n/4 in from either
  // end, miss the point), and their ranges are 2 cm off in opposite directions: the intersection
  // of their circles lies off along them and predicts only 32 of the 54 accurate scans within the
  // 1 cm gate. The least-squares refinement over those finds the point all of them support.
  core::Rng rng(8, 0);
  std::vector<RangeScan> scans;
  std::size_t accurate = 0;
  for (int k = 0; k < kScans; ++k) {
    RangeScan scan;
    scan.position_m = Vec2(0.05 * k, 1.0);
    const bool missed =
        k == kScans / 8 || k == kScans - 1 - kScans / 8 || k == kScans / 4 || k == kScans - 1 - kScans / 4;
    const double bias_m = k == 0 ? 0.02 : (k == kScans - 1 ? -0.02 : 0.0);
    if (!missed) scan.ranges_m.push_back((kPoint_m - scan.position_m).norm() + bias_m + rng.Normal(0.0, 0.002));
    if (!missed && bias_m == 0.0) ++accurate;
    scans.push_back(std::move(scan));
  }
  RangeConsensusOptions options;
  options.gate_m = 0.01;  // five times the noise
  options.min_support = 50;
  const auto found = FindRangeConsensus(scans, {}, options);
  ASSERT_TRUE(found);
  EXPECT_GE(found->support.size(), accurate);
}

TEST(RangeConsensus, ReturnsNothingFromClutterAlone) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    EXPECT_FALSE(FindRangeConsensus(Scans({.with_point = false}, seed), {}, SixtyPercent())) << "seed " << seed;
  }
}

TEST(RangeConsensus, NeverReturnsAPointBelowTheSupportItNeeds) {
  // Without clutter the point is supported by exactly the scans that saw it.
  const auto scans = Scans({.detection = 0.75, .clutter_per_scan = 0.0}, 4);
  const auto seen = static_cast<std::size_t>(
      std::count_if(scans.begin(), scans.end(), [](const RangeScan& s) { return !s.ranges_m.empty(); }));
  const auto saw = [&](int k) { return !scans[static_cast<std::size_t>(k)].ranges_m.empty(); };
  ASSERT_TRUE((saw(0) && saw(kScans - 1)) || (saw(kScans / 8) && saw(kScans - 1 - kScans / 8)) ||
              (saw(kScans / 4) && saw(kScans - 1 - kScans / 4)))
      << "no proposing pair of scans saw the point";
  RangeConsensusOptions options;
  options.min_support = seen;
  const auto found = FindRangeConsensus(scans, {}, options);
  ASSERT_TRUE(found);
  EXPECT_EQ(found->support.size(), seen);
  options.min_support = seen + 1;
  EXPECT_FALSE(FindRangeConsensus(scans, {}, options));
}

TEST(RangeConsensus, ExcludedPointsAreNotProposed) {
  const auto scans = Scans({.clutter_per_scan = 0.0}, 5);
  const std::vector<Vec2> both{kPoint_m, kMirror_m};
  EXPECT_FALSE(FindRangeConsensus(scans, both, SixtyPercent()));
  const std::vector<Vec2> one{kPoint_m};
  const auto found = FindRangeConsensus(scans, one, SixtyPercent());
  ASSERT_TRUE(found);
  EXPECT_LT((found->position_m - kMirror_m).norm(), 0.1);
}

TEST(RangeConsensus, ScansCloserThanTheMinimumPairDistanceProposeNothing) {
  // The proposing scan pairs are 2.95, 2.2 and 1.5 m apart.
  const auto scans = Scans({.detection = 1.0, .clutter_per_scan = 0.0}, 6);
  RangeConsensusOptions options = SixtyPercent();
  options.min_pair_distance_m = 3.0;
  EXPECT_FALSE(FindRangeConsensus(scans, {}, options));
  options.min_pair_distance_m = 2.9;
  EXPECT_TRUE(FindRangeConsensus(scans, {}, options));
}

}  // namespace
}  // namespace mirage::estimation
