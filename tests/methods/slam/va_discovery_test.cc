// SPDX-License-Identifier: MIT
// The VA discovery on its own: the ranges of one reflection seen from an L-shaped walk, fed in as
// the tracker feeds them (one anchor, the ranges no active VA explains, the active VAs, the agent's
// estimate and its covariance). A first-order VA is promoted on the right side of the walk once
// the walk turns, and nothing is learnt from steps at which the agent is poorly localised; a far
// VA with a clean fit is promoted with a larger std; the sweep finds a far VA that the
// step-to-step groups lose.
#include "mirage/methods/slam/va_discovery.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "core/options_descriptor_expectations.h"
#include "mirage/core/constants.h"
#include "mirage/core/rng.h"
#include "mirage/geometry/trajectory.h"

namespace mirage::methods::slam {
namespace {

// An anchor at (1, 2) and the wall x = 0: the VA is its mirror image (-1, 2).
const Vec2 kVa_m(-1.0, 2.0);
constexpr double kCutoff_m = 0.15;
constexpr double kRangeSigma_m = 0.01;

// 1.5 m east, then 1.5 m north, 5 cm steps: the mirror ambiguity about the first leg
// (y = 1, mirror image (-1, 0)) is resolved by the second.
const Vec2 kCorner_m(2.5, 1.0);
std::vector<geometry::TrajectorySample> Walk() {
  const std::vector<Vec2> waypoints{Vec2(1.0, 1.0), kCorner_m, Vec2(2.5, 2.5)};
  return geometry::SampleTrajectory(waypoints, 0.5, 0.1);
}

// The step at the corner.
int CornerStep() {
  const auto walk = Walk();
  for (std::size_t k = 0; k < walk.size(); ++k) {
    if ((walk[k].position_m - kCorner_m).norm() < 1e-9) return static_cast<int>(k);
  }
  ADD_FAILURE() << "the walk misses its corner";
  return -1;
}

struct Outcome {
  std::vector<DiscoveredVa> promoted;
  std::vector<int> promoted_steps;
  int most_groups = 0;
  std::size_t most_candidates = 0;
};

// Runs the walk; covariance_at(step) is the agent's position covariance the tracker would pass.
template <typename Covariance>
Outcome RunWalk(const DiscoveryOptions& options, Covariance covariance_at) {
  VaDiscovery discovery(options);
  core::Rng rng(7, 0);
  Outcome out;
  std::vector<Vec2> active_m;  // the promoted VAs, which the tracker would now associate
  const auto walk = Walk();
  for (std::size_t k = 0; k < walk.size(); ++k) {
    const Vec2 agent_m = walk[k].position_m;
    const double range_m = (kVa_m - agent_m).norm() + rng.Normal(0.0, kRangeSigma_m);
    const bool explained = std::any_of(active_m.begin(), active_m.end(), [&](const Vec2& va_m) {
      return std::abs((va_m - agent_m).norm() - range_m) < kCutoff_m;
    });
    std::vector<core::RangeMeasurement> unassociated;
    if (!explained) unassociated.push_back({range_m, std::nullopt});
    const int step = static_cast<int>(k);
    for (auto& va : discovery.Process(step, 0.1 * step, 0, agent_m, covariance_at(step), unassociated, active_m, kCutoff_m)) {
      active_m.push_back(va.position_m);
      out.promoted.push_back(std::move(va));
      out.promoted_steps.push_back(step);
    }
    out.most_groups = std::max(out.most_groups, discovery.group_count());
    out.most_candidates = std::max(out.most_candidates, discovery.candidates().size());
  }
  return out;
}

Eigen::Matrix2d Isotropic(double sigma_m) { return Eigen::Matrix2d::Identity() * sigma_m * sigma_m; }

TEST(VaDiscovery, PromotesTheVaOnTheRightSideOnceTheWalkTurns) {
  const Outcome out = RunWalk(DiscoveryOptions{}, [](int) { return Isotropic(0.01); });
  ASSERT_EQ(out.promoted.size(), 1u);
  const DiscoveredVa& va = out.promoted.front();
  EXPECT_EQ(va.anchor_index, 0);
  EXPECT_LT((va.position_m - kVa_m).norm(), 0.05) << va.position_m.transpose();  // not (-1, 0)
  EXPECT_GT(out.promoted_steps.front(), CornerStep()) << "promoted before the walk turned";
}

TEST(VaDiscovery, LearnsNothingWhileTheAgentIsPoorlyLocalised) {
  DiscoveryOptions options;
  options.max_agent_sigma_m = 0.1;
  // 12 cm std along the diagonal, 1 cm across it: each axis alone has 8.5 cm, so only the worst
  // direction (the largest eigenvalue) exceeds the limit.
  const Eigen::Matrix2d principal = Eigen::Vector2d(0.12 * 0.12, 0.01 * 0.01).asDiagonal();
  const Eigen::Matrix2d rotation = Eigen::Rotation2Dd(0.25 * core::kPi).toRotationMatrix();
  const Eigen::Matrix2d diagonal_ellipse = rotation * principal * rotation.transpose();
  ASSERT_LT(std::sqrt(diagonal_ellipse(0, 0)), 0.1);
  ASSERT_LT(std::sqrt(diagonal_ellipse(1, 1)), 0.1);
  const Outcome out = RunWalk(options, [&](int) { return diagonal_ellipse; });
  EXPECT_TRUE(out.promoted.empty());
  EXPECT_EQ(out.most_groups, 0);
  EXPECT_EQ(out.most_candidates, 0u);
  // On either side of the limit: the same walk promotes the VA just inside it, nothing just outside.
  EXPECT_EQ(RunWalk(options, [](int) { return Isotropic(0.0999); }).promoted.size(), 1u);
  EXPECT_TRUE(RunWalk(options, [](int) { return Isotropic(0.1001); }).promoted.empty());
}

TEST(VaDiscovery, StepsOfAPoorlyLocalisedAgentAreLeftOutOfTheSamples) {
  // Lost for the 10 steps after the turn: the VA is still found, from the other steps only.
  const int turn_step = CornerStep();
  const auto covariance_at = [&](int step) {
    return step > turn_step && step <= turn_step + 10 ? Isotropic(0.3) : Isotropic(0.01);
  };
  const Outcome out = RunWalk(DiscoveryOptions{}, covariance_at);
  ASSERT_EQ(out.promoted.size(), 1u);
  const auto walk = Walk();
  for (const auto& s : out.promoted.front().samples) {
    for (int step = turn_step + 1; step <= turn_step + 10; ++step) {
      EXPECT_GT((s.agent_m - walk[static_cast<std::size_t>(step)].position_m).norm(), 1e-9)
          << "a sample from lost step " << step;
    }
  }
}

TEST(VaDiscovery, ValidateNamesTheAgentSigmaLimit) {
  DiscoveryOptions options;
  options.max_agent_sigma_m = 0.0;
  const auto problems = Validate(options);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems.front().find("max_agent_sigma_m"), std::string::npos);
}

// The far-VA promotion rule (verify_far_sigma_per_m): a VA 10-11 m away seen from a 2.5 m
// L-shaped walk is placed to about 16 cm across its direction when promoted: more than
// verify_max_sigma_m (5 cm), within 1.5 % of its distance. Returns the VAs promoted from its ranges.
const Vec2 kDistantVa_m(-8.0, 4.0);
std::vector<DiscoveredVa> RunShortWalkToDistantVa(const DiscoveryOptions& options, double range_sigma_m) {
  VaDiscovery discovery(options);
  core::Rng rng(5, 0);
  const std::vector<Vec2> waypoints{Vec2(1.0, 1.0), Vec2(2.5, 1.0), Vec2(2.5, 2.0)};
  const auto walk = geometry::SampleTrajectory(waypoints, 0.5, 0.1);
  std::vector<DiscoveredVa> promoted;
  std::vector<Vec2> active_m;
  for (std::size_t k = 0; k < walk.size(); ++k) {
    const Vec2 agent_m = walk[k].position_m;
    const double range_m = (kDistantVa_m - agent_m).norm() + rng.Normal(0.0, range_sigma_m);
    std::vector<core::RangeMeasurement> unassociated;
    if (active_m.empty()) unassociated.push_back({range_m, std::nullopt});
    for (auto& va : discovery.Process(static_cast<int>(k), 0.1 * static_cast<double>(k), 0, agent_m, Isotropic(0.01), unassociated, active_m,
                                      kCutoff_m)) {
      active_m.push_back(va.position_m);
      promoted.push_back(std::move(va));
    }
  }
  return promoted;
}

TEST(VaDiscovery, AFarVaWithACleanFitIsPromotedDespiteItsAbsoluteStd) {
  DiscoveryOptions near_only;
  near_only.verify_far_sigma_per_m = 0.0;
  EXPECT_TRUE(RunShortWalkToDistantVa(near_only, 0.01).empty()) << "the std is within 5 cm after all";
  const auto promoted = RunShortWalkToDistantVa(DiscoveryOptions{}, 0.01);
  ASSERT_EQ(promoted.size(), 1u);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(promoted.front().covariance_m2);
  const double sigma_m = std::sqrt(eig.eigenvalues()(1));
  EXPECT_GT(sigma_m, DiscoveryOptions{}.verify_max_sigma_m);
  EXPECT_LT((promoted.front().position_m - kDistantVa_m).norm(), 3.0 * sigma_m) << "the std is honest";
}

TEST(VaDiscovery, TheFarVaRuleNeedsACleanFit) {
  // 2 cm range noise: the fit's RMS (about 2 cm) is within verify_fit_rms_m (4.5 cm); the far
  // rule's own RMS limit alone decides. The limits are set here, not the defaults, so the verdict
  // does not hang on how close this seed's RMS comes to 2.5 cm.
  DiscoveryOptions strict;
  strict.verify_far_fit_rms_m = 0.01;
  EXPECT_TRUE(RunShortWalkToDistantVa(strict, 0.02).empty());
  DiscoveryOptions any_rms;
  any_rms.verify_far_fit_rms_m = 1.0;
  EXPECT_EQ(RunShortWalkToDistantVa(any_rms, 0.02).size(), 1u);
}

TEST(VaDiscovery, ValidateNamesTheFarVaOptions) {
  DiscoveryOptions options;
  options.verify_far_sigma_per_m = -0.01;
  options.verify_far_fit_rms_m = 0.0;
  const auto problems = Validate(options);
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_NE(problems[0].find("verify_far_sigma_per_m"), std::string::npos);
  EXPECT_NE(problems[1].find("verify_far_fit_rms_m"), std::string::npos);
}

// The sweep (stage D', mirage): a far, weak reflection seen from a straight walk changes its range
// by almost a step length per step and is missed at every fourth step, so the step-to-step groups
// (7 cm gate) break at every missed step and never grow to a candidate; the consensus search over
// the last 60 steps finds it among the clutter. Clutter alone gives nothing.
constexpr double kClutterPerStep = 15.0;   // diffuse-multipath peaks and noise, Poisson count
constexpr double kRangeWindow_m = 15.0;    // clutter uniform over [0, 15] m

// 3 m east along y = 1 (5 cm steps): the VA 9.5 m ahead and 2 m to the side changes its range by
// 4.8-4.9 cm per step, 9.7 cm over a missed step.
const Vec2 kFarVa_m(12.0, 3.0);

struct SweepOutcome {
  int sweep_candidates = 0;
  // A candidate made of the VA's ranges: at least 20, nine in ten within 4 cm of the VA's range
  // (where its hypotheses lie is the RLS's and the promotion's business, tested above).
  bool candidate_of_va = false;
};

SweepOutcome RunStraightWalk(const DiscoveryOptions& options, bool with_va) {
  VaDiscovery discovery(options);
  core::Rng rng(11, 0);
  const std::vector<Vec2> waypoints{Vec2(0.0, 1.0), Vec2(3.0, 1.0)};
  const auto walk = geometry::SampleTrajectory(waypoints, 0.5, 0.1);
  SweepOutcome out;
  for (std::size_t k = 0; k < walk.size(); ++k) {
    const Vec2 agent_m = walk[k].position_m;
    std::vector<core::RangeMeasurement> ranges;
    if (with_va && k % 4 != 3) {  // missed at every fourth step
      ranges.push_back({(kFarVa_m - agent_m).norm() + rng.Normal(0.0, kRangeSigma_m), std::nullopt});
    }
    const int clutter = rng.Poisson(kClutterPerStep);
    for (int c = 0; c < clutter; ++c) ranges.push_back({rng.Uniform() * kRangeWindow_m, std::nullopt});
    const Eigen::Matrix2d agent_covariance_m2 = Eigen::Matrix2d::Identity() * 0.01 * 0.01;
    discovery.Process(static_cast<int>(k), 0.1 * static_cast<double>(k), 0, agent_m, agent_covariance_m2, ranges, {}, kCutoff_m);
    for (const auto& candidate : discovery.candidates()) {
      const auto own = std::count_if(candidate.samples.begin(), candidate.samples.end(), [](const DiscoverySample& s) {
        return std::abs(s.range_m - (kFarVa_m - s.agent_m).norm()) < 0.04;
      });
      const auto all = static_cast<std::ptrdiff_t>(candidate.samples.size());
      if (all >= 20 && 10 * own >= 9 * all) out.candidate_of_va = true;
    }
  }
  out.sweep_candidates = discovery.sweep_candidates();
  return out;
}

TEST(VaDiscovery, TheSweepFindsAFarVaThatTheGroupsLoseAtMissedSteps) {
  DiscoveryOptions groups_only;
  groups_only.sweep.enabled = false;
  EXPECT_FALSE(RunStraightWalk(groups_only, true).candidate_of_va) << "the step-to-step groups found it after all";
  const SweepOutcome out = RunStraightWalk(DiscoveryOptions{}, true);
  EXPECT_TRUE(out.candidate_of_va);
  EXPECT_GE(out.sweep_candidates, 1);
}

TEST(VaDiscovery, TheSweepMakesNoCandidateFromClutterAlone) {
  EXPECT_EQ(RunStraightWalk(DiscoveryOptions{}, false).sweep_candidates, 0);
}

TEST(VaDiscovery, ValidateNamesEachSweepOption) {
  const auto problem_with = [](auto change) {
    DiscoveryOptions options;
    change(options.sweep);
    const auto problems = Validate(options);
    return problems.size() == 1 ? problems.front() : std::string("(") + std::to_string(problems.size()) + " problems)";
  };
  EXPECT_NE(problem_with([](SweepOptions& o) { o.window_s = 0.0; }).find("sweep.window_s"), std::string::npos);
  EXPECT_NE(problem_with([](SweepOptions& o) { o.every_steps = 0; }).find("sweep.every_steps"), std::string::npos);
  EXPECT_NE(problem_with([](SweepOptions& o) { o.min_baseline_m = 0.0; }).find("sweep.min_baseline_m"),
            std::string::npos);
  EXPECT_NE(problem_with([](SweepOptions& o) { o.gate_m = -1.0; }).find("sweep.gate_m"), std::string::npos);
  EXPECT_NE(problem_with([](SweepOptions& o) { o.min_support_fraction = 1.5; }).find("sweep.min_support_fraction"),
            std::string::npos);
}

TEST(DiscoveryOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMember) {
  test::ExpectDescribesEveryMember(
      DiscoveryOptionsDescriptor(),
      {"enabled", "max_agent_sigma_m", "group_gate_m", "group_max_gap_steps", "group_size", "min_group_baseline_m",
       "max_fit_rms_m", "rls_initial_sigma_m", "rls_range_sigma_m", "min_measurements", "min_turn_m", "verify",
       "verify_fit_rms_m", "verify_min_inlier_fraction", "verify_mirror_ratio", "verify_residual_cap_m", "verify_max_sigma_m",
       "verify_far_sigma_per_m", "verify_far_fit_rms_m", "resolve_misses", "merge_hypotheses_m",
       "candidate_timeout_s", "candidate_max_age_s", "duplicate_radius_m", "sweep"});
}

}  // namespace
}  // namespace mirage::methods::slam
