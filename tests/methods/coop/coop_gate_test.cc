// SPDX-License-Identifier: MIT
// The cooperative tracker's default-on innovation gate (CoopOptions::innovation_gate_sigma, our
// addition to the cut-off association of Kulmer et al. Sec. III-B3): an associated range whose
// innovation is far outside its predicted innovation variance h P h^T + r leaves the update, so
// the estimate is what it would be without that range, while the nominal range is kept; with the
// gate off the outlier pulls the agents.
#include <vector>

#include <gtest/gtest.h>

#include "methods/coop/path_signals.h"

namespace mirage::methods::coop {
namespace {

// Given ranges, whatever count is asked.
class FixedRanges final : public LinkSignal {
 public:
  explicit FixedRanges(std::vector<double> ranges_m) : ranges_m_(std::move(ranges_m)) {}
  [[nodiscard]] std::vector<double> Ranges(int /*count*/) const override { return ranges_m_; }
  [[nodiscard]] double AmplitudeAt(double /*range_m*/) const override { return 1.0; }

 private:
  std::vector<double> ranges_m_;
};

struct Outcome {
  CoopStepInfo with_outlier;
  std::vector<Vec2> with_outlier_m;     // the agents after the epoch with the outlier
  std::vector<Vec2> without_range_m;    // after the same epoch without that range
};

// Two agents known to 5 mm and 5 mm/s, 5 mm ranges (variance estimation off); one 1 s step in
// which only the relative link measures: its paths' exact lengths, the first one offset_m long.
// The predicted positions are then known to about 8 mm, a path length of the link to about 1.3 cm. Why not R's
// default: with it (the fallback sigma R_0 = 7 cm) the 3-sigma gate is at least 21 cm wide, wider
// than d_c = 15 cm, so no range that the cut-off assignment lets through can be gated; the gate
// acts when the SINR-based variance is below (d_c / 3)^2, as with these 5 mm.
Outcome RunWithOutlier(double gate_sigma, double offset_m) {
  CoopOptions options;
  options.innovation_gate_sigma = gate_sigma;
  options.agent_sigma_m = 0.005;
  options.velocity_sigma_mps = 0.005;
  options.variance.enabled = false;
  options.variance.default_sigma_m = 0.005;
  CoopTracker tracker(options, testing::Room(), EnumerateLinks(2, false), AntennaLayout{}, std::nullopt,
                      testing::kPulse);
  const std::vector<Vec2> agents_m{Vec2(1.0, 2.0), Vec2(3.0, 5.0)};
  tracker.Initialize(agents_m, 0.0);
  std::vector<double> with_m;
  for (const auto& path : tracker.ExpectedPaths(2, agents_m, testing::Room())) with_m.push_back(path.range_m());
  const std::vector<double> without_m(with_m.begin() + 1, with_m.end());
  with_m.front() += offset_m;
  const FixedRanges silent({}), with(with_m), without(without_m);
  CoopTracker twin = tracker;
  Outcome out;
  out.with_outlier = tracker.Step(1.0, std::vector<const LinkSignal*>{&silent, &silent, &with});
  twin.Step(1.0, std::vector<const LinkSignal*>{&silent, &silent, &without});
  for (int m = 0; m < 2; ++m) {
    out.with_outlier_m.push_back(tracker.Position(m));
    out.without_range_m.push_back(twin.Position(m));
  }
  return out;
}

TEST(CoopTracker, DefaultInnovationGateKeepsARangeInsideTheCutoffOutOfTheUpdate) {
  const double default_gate = CoopOptions{}.innovation_gate_sigma;
  ASSERT_GT(default_gate, 0.0) << "the gate is on by default";
  const auto moved_m = [](const Outcome& o) {
    return (o.with_outlier_m[0] - o.without_range_m[0]).norm() + (o.with_outlier_m[1] - o.without_range_m[1]).norm();
  };

  // The nominal ranges: all associated, none gated.
  const Outcome nominal = RunWithOutlier(default_gate, 0.0);
  EXPECT_EQ(nominal.with_outlier.links[2].gated, 0);
  EXPECT_EQ(nominal.with_outlier.links[2].associated, nominal.with_outlier.links[2].expected);

  // 12 cm: inside d_c, about 10 innovation sigmas out. Gated, and the agents stay where the epoch
  // without that range puts them.
  const Outcome gated = RunWithOutlier(default_gate, 0.12);
  EXPECT_EQ(gated.with_outlier.links[2].gated, 1);
  EXPECT_LT(moved_m(gated), 1e-9);

  // 3 m: beyond d_c, the cut-off assignment drops it before the gate sees it.
  const Outcome gross = RunWithOutlier(default_gate, 3.0);
  EXPECT_EQ(gross.with_outlier.links[2].associated, gross.with_outlier.links[2].expected - 1);
  EXPECT_LT(moved_m(gross), 1e-9);

  const Outcome open = RunWithOutlier(0.0, 0.12);
  EXPECT_EQ(open.with_outlier.links[2].gated, 0);
  EXPECT_GT(moved_m(open), 0.002) << "without the gate the 12 cm range pulls the agents";
}

}  // namespace
}  // namespace mirage::methods::coop
