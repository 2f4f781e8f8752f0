// SPDX-License-Identifier: MIT
// The cooperative EKF (Kulmer et al. Algorithm 1) on exact ranges: links and antennas, expected
// paths and their ambiguity pruning, tracking two agents from self and relative ranges alone,
// learning a wall offset (and not learning it when the wall update is off), and the innovation
// gate. Range signals are synthetic (the true path lengths plus seeded noise and clutter), so
// these tests isolate the filter from the channel simulator.
#include "mirage/methods/coop/coop_tracker.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/options_descriptor_expectations.h"
#include "methods/coop/path_signals.h"
#include "mirage/core/rng.h"

namespace mirage::methods::coop {
namespace {

using geometry::FloorPlan;
using testing::kPulse;
using testing::Room;

struct Walk {
  std::vector<std::vector<Vec2>> truth;  // per step, per agent
};

Walk TwoAgents(int steps) {
  Walk w;
  for (int n = 0; n <= steps; ++n) {
    w.truth.push_back({Vec2(1.0 + 0.02 * n, 1.2 + 0.01 * n), Vec2(3.3, 5.5 - 0.02 * n)});
  }
  return w;
}

// Runs the tracker on exact signals from `truth_plan`; returns the largest error over the run.
double Track(CoopTracker& tracker, const FloorPlan& truth_plan, const Walk& walk, double sigma_m, int clutter,
             std::uint64_t seed) {
  core::Rng rng(seed);
  tracker.Initialize(walk.truth.front(), 0.0);
  double worst_m = 0.0;
  for (std::size_t n = 1; n < walk.truth.size(); ++n) {
    testing::StepOnTruth(tracker, static_cast<double>(n), truth_plan, walk.truth[n], sigma_m, clutter, rng);
    for (int m = 0; m < tracker.agent_count(); ++m) {
      worst_m = std::max(worst_m, (tracker.Position(m) - walk.truth[n][static_cast<std::size_t>(m)]).norm());
    }
  }
  return worst_m;
}

TEST(CoopLink, EnumeratesSelfRelativeAndAnchorLinksInThePapersOrder) {
  const auto links = EnumerateLinks(3, true);
  ASSERT_EQ(links.size(), 9u);  // 3 self + 3 pairs + 3 anchor links (Sec. IV-D: 9 vs 6)
  EXPECT_EQ(links[0].kind, LinkKind::kSelf);
  EXPECT_EQ(links[3].Name(), "rel 1-2");
  EXPECT_EQ(links[5].Name(), "rel 2-3");
  EXPECT_EQ(links[8].Name(), "anchor-3");
  EXPECT_EQ(EnumerateLinks(4, false).size(), 10u);
  // Antennas side by side: a self link is a short bistatic link.
  const LinkEnds ends = AntennaPositions(links[0], {Vec2(1, 1), Vec2(2, 2), Vec2(3, 3)}, Vec2(9, 9), AntennaLayout{});
  EXPECT_NEAR((ends.tx_m - ends.rx_m).norm(), 0.05, 1e-12);
  EXPECT_EQ(AntennaPositions(links[8], {Vec2(1, 1), Vec2(2, 2), Vec2(3, 3)}, Vec2(9, 9), AntennaLayout{}).tx_m, Vec2(9, 9));
}

TEST(CoopTracker, ExpectedPathsDropTheCouplingAndAmbiguousPairs) {
  CoopOptions options;
  CoopTracker tracker(options, Room(), EnumerateLinks(2, false), AntennaLayout{}, std::nullopt, kPulse);
  // At (1, 1) the south and west single bounces of the self link are both 2 m long: both go.
  const std::vector<Vec2> agents{Vec2(1.0, 1.0), Vec2(3.0, 5.0)};
  int visible = 0;
  const auto paths = tracker.ExpectedPaths(0, agents, Room(), &visible);
  EXPECT_GT(visible, static_cast<int>(paths.size()));
  for (const auto& p : paths) {
    EXPECT_FALSE(p.walls.empty()) << "the antenna coupling is not a path";
    for (const auto& q : paths) {
      if (&p != &q) {
        EXPECT_GE(std::abs(p.range_m() - q.range_m()), tracker.cutoff_m());
      }
    }
  }
  for (const auto& p : paths) {
    EXPECT_FALSE(p.walls.size() == 1 && (p.walls[0] == 0 || p.walls[0] == 3)) << "the 2 m pair was kept";
  }
  EXPECT_NEAR(tracker.cutoff_m(), 0.1499, 1e-3);  // c T_p at 0.5 ns
}

TEST(CoopTracker, TracksTwoAgentsWithoutAnchorsFromNoisyRangesWithClutter) {
  CoopOptions options;
  CoopTracker tracker(options, Room(), EnumerateLinks(2, false), AntennaLayout{}, std::nullopt, kPulse);
  const double worst_m = Track(tracker, Room(), TwoAgents(100), 0.01, 3, 7);
  EXPECT_LT(worst_m, 0.05);
  // The covariance stays consistent with the error: the agents' position sigma is cm-level.
  EXPECT_LT(std::sqrt(tracker.PositionCovariance(0).trace()), 0.05);
}

// A link that measured nothing this step (the filter only predicts).
class SilentSignal final : public LinkSignal {
 public:
  [[nodiscard]] std::vector<double> Ranges(int /*count*/) const override { return {}; }
  [[nodiscard]] double AmplitudeAt(double /*range_m*/) const override { return 0.0; }
};

TEST(CoopTracker, ProcessNoiseAllowsAVelocityChangeOfVmaxPerStepAtAnyStepTime) {
  // Kulmer Sec. IV-B: sigma_a = v_max / (3 dt), so one step adds (v_max / 3)^2 to each velocity
  // variance whatever the step time. (Taking v_max / 3 as sigma_a holds only for 1 s steps.)
  for (const double dt_s : {0.5, 1.0, 2.0}) {
    CoopOptions options;
    CoopTracker tracker(options, Room(), EnumerateLinks(2, false), AntennaLayout{}, std::nullopt, kPulse);
    tracker.Initialize(TwoAgents(0).truth.front(), 0.0);
    const SilentSignal silent;
    const std::vector<const LinkSignal*> signals(tracker.links().size(), &silent);

    tracker.Step(dt_s, signals);

    const auto& layout = tracker.state().layout();
    const int v = layout.At(estimation::BlockKey(estimation::blocks::kVelocity, 1)).offset;
    const double added_mps2 = tracker.state().covariance()(v, v) - options.velocity_sigma_mps * options.velocity_sigma_mps;
    EXPECT_NEAR(added_mps2, std::pow(options.max_speed_mps / 3.0, 2), 1e-15) << "dt " << dt_s << " s";
  }
}

TEST(CoopTracker, LearnsABiasedWallOffsetOnlyWithTheWallUpdate) {
  // The provided plan has the west wall 4 cm too far east; the truth has it at x = 0. With the
  // update the filter moves it back (offset along its normal, which points east for the wall
  // drawn north to south... the sign is checked against the truth, not assumed).
  CoopOptions options;
  options.wall_sigma_m = 0.01;
  const FloorPlan provided = Room(0.04);
  CoopTracker learning(options, provided, EnumerateLinks(2, false), AntennaLayout{}, std::nullopt, kPulse);
  const double worst_learning_m = Track(learning, Room(), TwoAgents(120), 0.005, 0, 3);
  // Anchorless, the frame itself may drift; the room's width (the paper's d12, Sec. IV-C2) may
  // not: it must go from 4.36 m back towards the true 4.40 m.
  const auto walls = learning.CurrentPlan().walls();
  const double width_m = walls[1].start_m.x() - walls[3].start_m.x();
  EXPECT_LT(std::abs(width_m - 4.4), 0.01) << "width " << width_m << " m";
  EXPECT_GT(learning.WallOffsetSigma(3), 0.0);
  EXPECT_LT(learning.WallOffsetSigma(3), 0.01);

  options.wall_update = false;
  CoopTracker fixed(options, provided, EnumerateLinks(2, false), AntennaLayout{}, std::nullopt, kPulse);
  const double worst_fixed_m = Track(fixed, Room(), TwoAgents(120), 0.005, 0, 3);
  EXPECT_EQ(fixed.WallOffset(3), 0.0);
  EXPECT_NEAR(fixed.CurrentPlan().walls()[3].start_m.x(), 0.04, 1e-12);
  EXPECT_LT(worst_learning_m, worst_fixed_m);
}

TEST(CoopTracker, InnovationGateDropsAWrongRange) {
  // One range 12 cm off (inside d_c = 15 cm, so the association keeps it) with 5 mm noise:
  // the gate drops it, without the gate it is used.
  class OffSignal final : public LinkSignal {
   public:
    explicit OffSignal(std::vector<double> r) : r_(std::move(r)) {}
    [[nodiscard]] std::vector<double> Ranges(int) const override { return r_; }
    [[nodiscard]] double AmplitudeAt(double) const override { return 1.0; }
    std::vector<double> r_;
  };
  for (const double gate : {3.0, 0.0}) {
    CoopOptions options;
    options.innovation_gate_sigma = gate;
    options.agent_sigma_m = 0.005;
    options.variance.enabled = false;
    options.variance.default_sigma_m = 0.005;
    CoopTracker tracker(options, Room(), EnumerateLinks(2, false), AntennaLayout{}, std::nullopt, kPulse);
    const std::vector<Vec2> agents{Vec2(1.0, 2.0), Vec2(3.0, 5.0)};
    tracker.Initialize(agents, 0.0);
    const auto rel_paths = tracker.ExpectedPaths(2, agents, Room());
    std::vector<double> rel;
    for (std::size_t i = 0; i < rel_paths.size(); ++i) rel.push_back(rel_paths[i].range_m() + (i == 0 ? 0.12 : 0.0));
    OffSignal none({}), none2({}), relative(rel);
    const std::vector<const LinkSignal*> signals{&none, &none2, &relative};
    const auto info = tracker.Step(1.0, signals);
    if (gate > 0.0) {
      EXPECT_EQ(info.links[2].gated, 1);
      EXPECT_EQ(info.links[2].associated, static_cast<int>(rel.size()) - 1);
    } else {
      EXPECT_EQ(info.links[2].gated, 0);
      EXPECT_EQ(info.links[2].associated, static_cast<int>(rel.size()));
    }
  }
}

TEST(CoopTracker, RejectsInvalidOptionsAndMismatchedInput) {
  CoopOptions bad;
  bad.max_order = 3;
  EXPECT_FALSE(Validate(bad).empty());
  EXPECT_THROW(CoopTracker(bad, Room(), EnumerateLinks(2, false), AntennaLayout{}, std::nullopt, kPulse),
               std::invalid_argument);
  EXPECT_THROW(CoopTracker(CoopOptions{}, Room(), EnumerateLinks(2, true), AntennaLayout{}, std::nullopt, kPulse),
               std::invalid_argument);
  CoopTracker tracker(CoopOptions{}, Room(), EnumerateLinks(2, false), AntennaLayout{}, std::nullopt, kPulse);
  EXPECT_THROW(tracker.Initialize(std::vector<Vec2>{Vec2(1, 1)}, 0.0), std::invalid_argument);
  tracker.Initialize(std::vector<Vec2>{Vec2(1, 1), Vec2(2, 2)}, 0.0);
  EXPECT_THROW(tracker.Step(1.0, std::vector<const LinkSignal*>{}), std::invalid_argument);
}

TEST(CoopOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMember) {
  test::ExpectDescribesEveryMember(CoopOptionsDescriptor(),
                                   {"agent_sigma_m", "velocity_sigma_mps", "wall_sigma_m", "wall_update",
                                    "max_speed_mps", "max_order", "cutoff_m", "extraction_factor", "self_gate_m",
                                    "innovation_gate_sigma", "variance", "anchor_links", "antenna_spacing_m"});
}

TEST(CoopOptionsDescriptor, KeepsTheCooperativeVarianceDefaults) {
  const auto& defaults = CoopOptionsDescriptor().defaults().variance;
  EXPECT_EQ(defaults.window_max_m, CoopOptions::DefaultVariance().window_max_m);
  EXPECT_EQ(defaults.min_sigma_m, CoopOptions::DefaultVariance().min_sigma_m);
  EXPECT_NE(defaults.window_max_m, estimation::RangeVarianceOptions{}.window_max_m);
}

TEST(CoopOptions, RejectsASelfGateThatDoesNotClearTheAntennaSpacing) {
  CoopOptions o;
  o.antenna_spacing_m = 0.04;
  o.self_gate_m = 0.03;

  EXPECT_EQ(Validate(o), std::vector<std::string>{"self_gate_m: 0.03 m must exceed antenna_spacing_m (0.04 m), where "
                                                  "the TX-RX coupling of a self link arrives"});
  o.antenna_spacing_m = 0.0;  // no coupling range to clear
  EXPECT_TRUE(Validate(o).empty());
}

}  // namespace
}  // namespace mirage::methods::coop
