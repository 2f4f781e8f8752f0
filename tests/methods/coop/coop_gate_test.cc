// SPDX-License-Identifier: MIT
// The cooperative tracker's default-on innovation gate (CoopOptions::innovation_gate_sigma, our
// addition to the cut-off association of Kulmer et al. Sec. III-B3): an associated range whose
// innovation is far outside its predicted innovation variance h P h^T + r leaves the update, so
// the estimate is what it would be without that range; with the gate off it pulls the agents.
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

// Two agents known to 5 mm, 5 mm ranges (variance estimation off); one step in which only the
// relative link measures: its paths' exact lengths, the first one 12 cm long (inside d_c = 15 cm,
// about 14 innovation sigmas out).
Outcome RunWithOutlier(double gate_sigma) {
  CoopOptions options;
  options.innovation_gate_sigma = gate_sigma;
  options.agent_sigma_m = 0.005;
  options.variance.enabled = false;
  options.variance.default_sigma_m = 0.005;
  CoopTracker tracker(options, testing::Room(), EnumerateLinks(2, false), AntennaLayout{}, std::nullopt,
                      testing::kPulse);
  const std::vector<Vec2> agents_m{Vec2(1.0, 2.0), Vec2(3.0, 5.0)};
  tracker.Initialize(agents_m, 0.0);
  std::vector<double> with_m;
  for (const auto& path : tracker.ExpectedPaths(2, agents_m, testing::Room())) with_m.push_back(path.range_m());
  const std::vector<double> without_m(with_m.begin() + 1, with_m.end());
  with_m.front() += 0.12;
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
  const Outcome gated = RunWithOutlier(CoopOptions{}.innovation_gate_sigma);
  EXPECT_EQ(gated.with_outlier.links[2].gated, 1);
  for (int m = 0; m < 2; ++m) {
    EXPECT_LT((gated.with_outlier_m[m] - gated.without_range_m[m]).norm(), 1e-9) << "agent " << m;
  }

  const Outcome open = RunWithOutlier(0.0);
  EXPECT_EQ(open.with_outlier.links[2].gated, 0);
  EXPECT_GT((open.with_outlier_m[0] - open.without_range_m[0]).norm() +
                (open.with_outlier_m[1] - open.without_range_m[1]).norm(),
            0.002)
      << "without the gate the 12 cm range pulls the agents";
}

}  // namespace
}  // namespace mirage::methods::coop
