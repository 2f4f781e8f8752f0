// SPDX-License-Identifier: MIT
// The SLAM tracker on synthetic unlabeled ranges in the 6 m x 6 m square room of
// methods/mint/square_room.h: the known-VA baseline, discovery from the anchors alone on clean
// ranges, lazy state augmentation, the amplitude gate (also in a blocked anchor's shadow), the
// tighter innovation gate for VAs without a visibility region, the
// shadow cone, the LOS re-acquisition, the track-loss recovery with a floor-plan map, and option
// validation.
#include "mirage/methods/slam/slam_tracker.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <vector>

#include <gtest/gtest.h>

#include "core/options_descriptor_expectations.h"
#include "methods/mint/square_room.h"
#include "mirage/core/constants.h"
#include "mirage/geometry/trajectory.h"

namespace mirage::methods::slam {
namespace {

using mint::testing::MeasureRanges;
using mint::testing::MeasurementModel;

const double kSigma1M = 0.01 * std::sqrt(10.0);

// A loop with three corners: 2.5 m east, 3 m north, 2.5 m west (170 steps of 5 cm).
std::vector<geometry::TrajectorySample> Loop() {
  const std::vector<Vec2> waypoints{Vec2(1.5, 1.5), Vec2(4.0, 1.5), Vec2(4.0, 4.5), Vec2(1.5, 4.5)};
  return geometry::SampleTrajectory(waypoints, 0.5, 0.1);
}

struct Outcome {
  double max_error_m = 0.0;
  std::vector<MapVa> map;
  int max_state_vas = 0;
};

Outcome RunLoop(const SlamOptions& options, const geometry::FloorPlan& plan, const geometry::VirtualAnchorSet& known,
            const geometry::VirtualAnchorSet& truth_vas, const MeasurementModel& model, std::uint64_t seed) {
  core::Rng rng(seed, 0);
  const auto samples = Loop();
  SlamTracker tracker(options, known, plan, kSigma1M);
  tracker.Initialize(samples.front().t_s, samples.front().position_m);
  Outcome out;
  for (std::size_t k = 1; k < samples.size(); ++k) {
    const auto ranges = MeasureRanges(truth_vas, plan, samples[k].position_m, model, rng);
    const auto step = tracker.Step(samples[k].t_s, ranges);
    out.max_error_m = std::max(out.max_error_m, (step.position_m - samples[k].position_m).norm());
    out.max_state_vas = std::max(out.max_state_vas, step.state_vas);
  }
  out.map = tracker.Map();
  return out;
}

TEST(SlamTracker, KnownVaBaselineTracksAndPutsOnlyAssociatedVasIntoTheState) {
  const auto plan = mint::testing::EmptySquareRoom();
  const auto vas = mint::testing::SquareRoomVas(plan, 1);
  SlamOptions options;
  options.prior_max_order = 1;
  options.discovery.enabled = false;
  const Outcome out = RunLoop(options, plan, vas, vas, MeasurementModel{}, 1);
  EXPECT_LT(out.max_error_m, 0.05);
  // 2 anchors x 4 walls = 8 first-order VAs, all visible somewhere on the loop; the anchors
  // themselves are fixed and never in the state.
  EXPECT_GT(out.max_state_vas, 0);
  EXPECT_LE(out.max_state_vas, 8);
  for (const auto& va : out.map) {
    if (va.origin != MapVaOrigin::kPrior || va.associations == 0) continue;
    const Vec2 truth = vas[va.id].position_m;
    EXPECT_LT((va.position_m - truth).norm(), 0.05) << "VA " << va.id;
    EXPECT_GT(va.covariance_m2.trace(), 0.0);
  }
}

TEST(SlamTracker, DiscoversFirstOrderVasFromTheAnchorsAloneOnCleanRanges) {
  const auto plan = mint::testing::EmptySquareRoom();
  const auto anchors_only = mint::testing::SquareRoomVas(plan, 0);
  const auto truth = mint::testing::SquareRoomVas(plan, 1);
  SlamOptions options;  // prior_max_order 0: only the anchors
  options.prior_visibility = false;
  const Outcome out = RunLoop(options, plan, anchors_only, truth, MeasurementModel{}, 2);
  EXPECT_LT(out.max_error_m, 0.10);
  int discovered = 0, near_truth = 0;
  for (const auto& va : out.map) {
    if (va.origin != MapVaOrigin::kDiscovered) continue;
    ++discovered;
    double best_m = 1e9;
    for (const auto& t : truth.all()) {
      if (t.order == 1 && t.anchor_index == va.anchor_index) best_m = std::min(best_m, (t.position_m - va.position_m).norm());
    }
    if (best_m < 0.15) ++near_truth;
  }
  EXPECT_GE(discovered, 3);
  EXPECT_GE(near_truth, discovered - 1) << "at most one discovered VA far from every true VA";
}

// Runs the loop with discovery, then one step without any range: the prediction alone, so the
// change of each VA block is the random walk's. Returns the largest deviation of a discovered
// VA's covariance change from q^2 dt I, and the number of discovered VAs in the state.
std::pair<double, int> WalkDeviation(double q_m_per_sqrt_s) {
  const auto plan = mint::testing::EmptySquareRoom();
  const auto anchors_only = mint::testing::SquareRoomVas(plan, 0);
  const auto truth = mint::testing::SquareRoomVas(plan, 1);
  SlamOptions options;
  options.prior_visibility = false;
  options.discovered_va_walk_m_per_sqrt_s = q_m_per_sqrt_s;
  core::Rng rng(2, 0);
  const auto samples = Loop();
  SlamTracker tracker(options, anchors_only, plan, kSigma1M);
  tracker.Initialize(samples.front().t_s, samples.front().position_m);
  for (std::size_t k = 1; k < samples.size(); ++k) {
    (void)tracker.Step(samples[k].t_s, MeasureRanges(truth, plan, samples[k].position_m, MeasurementModel{}, rng));
  }
  const estimation::State before = tracker.state();
  const double dt_s = 0.3;
  (void)tracker.Step(before.t_s() + dt_s, {});
  const estimation::State& after = tracker.state();
  double deviation = 0.0;
  int vas = 0;
  for (const auto& block : before.layout().blocks()) {
    if (block.key.type_id != estimation::blocks::kVirtualAnchor.id) continue;
    ++vas;
    const Eigen::Matrix2d change = after.Covariance(block.key) - before.Covariance(block.key);
    const Eigen::Matrix2d expected = Eigen::Matrix2d::Identity() * q_m_per_sqrt_s * q_m_per_sqrt_s * dt_s;
    deviation = std::max(deviation, (change - expected).cwiseAbs().maxCoeff());
    EXPECT_TRUE(after.Mean(block.key).isApprox(before.Mean(block.key))) << "a walk has zero mean";
  }
  return {deviation, vas};
}

TEST(SlamTracker, DiscoveredVasWalkByTheirRandomWalkOnlyWhenItIsOn) {
  const auto [off_deviation, off_vas] = WalkDeviation(0.0);
  const auto [on_deviation, on_vas] = WalkDeviation(0.01);
  ASSERT_GE(on_vas, 3) << "the loop discovers VAs";
  ASSERT_GE(off_vas, 3);
  EXPECT_LT(off_deviation, 1e-15);
  EXPECT_LT(on_deviation, 1e-15) << "each discovered VA gains (0.01 m)^2 / s x 0.3 s";
}

TEST(SlamTracker, WithoutDiscoveryTheMapHoldsOnlyTheAnchors) {
  const auto plan = mint::testing::EmptySquareRoom();
  const auto anchors_only = mint::testing::SquareRoomVas(plan, 0);
  const auto truth = mint::testing::SquareRoomVas(plan, 1);
  SlamOptions options;
  options.discovery.enabled = false;
  const Outcome out = RunLoop(options, plan, anchors_only, truth, MeasurementModel{}, 3);
  EXPECT_EQ(out.map.size(), 2u);
  EXPECT_EQ(out.max_state_vas, 0);
}

// Runs the loop up to step k with `known` in the tracker and `truth` producing the ranges; at
// step k `edit` changes the ranges first, at step k - 1 `edit_previous`. Returns what step k
// produced.
using Edit = std::function<void(std::vector<core::RangeSet>&, const Vec2&)>;
SlamStepResult RunToStep(const SlamOptions& options, const geometry::VirtualAnchorSet& known,
                         const geometry::VirtualAnchorSet& truth, std::uint64_t seed, std::size_t k, const Edit& edit,
                         const Edit& edit_previous = [](auto&, const Vec2&) {}) {
  const auto plan = mint::testing::EmptySquareRoom();
  SlamTracker tracker(options, known, plan, kSigma1M);
  const auto samples = Loop();
  tracker.Initialize(samples.front().t_s, samples.front().position_m);
  core::Rng rng(seed, 0);
  for (std::size_t i = 1; i < k; ++i) {
    auto ranges = MeasureRanges(truth, plan, samples[i].position_m, MeasurementModel{}, rng);
    if (i + 1 == k) edit_previous(ranges, samples[i].position_m);
    tracker.Step(samples[i].t_s, ranges);
  }
  auto ranges = MeasureRanges(truth, plan, samples[k].position_m, MeasurementModel{}, rng);
  edit(ranges, samples[k].position_m);
  return tracker.Step(samples[k].t_s, ranges);
}

// Counts the discovered VAs of each anchor that step 150 of the loop associates when every
// non-LOS range arrives at `amplitude_factor` of its amplitude (a stand-in weaker than the path,
// as behind an obstacle) and, with `block_anchor0`, anchor 0's LOS is missing.
std::array<int, 2> DiscoveredAssociationsWithWeakRanges(double blocked_amplitude_probability, bool block_anchor0,
                                                        double amplitude_factor) {
  const auto plan = mint::testing::EmptySquareRoom();
  const auto anchors_only = mint::testing::SquareRoomVas(plan, 0);
  const auto truth = mint::testing::SquareRoomVas(plan, 1);
  SlamOptions options;
  options.prior_visibility = false;
  options.blocked_amplitude_probability = blocked_amplitude_probability;
  const auto step = RunToStep(options, anchors_only, truth, 4, 150, [&](std::vector<core::RangeSet>& ranges,
                                                                           const Vec2& p_m) {
    for (auto& anchor : ranges) {
      const double los_m = (anchors_only[anchor.anchor_index].position_m - p_m).norm();
      if (block_anchor0 && anchor.anchor_index == 0) {
        std::erase_if(anchor.ranges, [&](const core::RangeMeasurement& r) { return std::abs(r.range_m - los_m) < 0.1; });
      }
      for (auto& r : anchor.ranges) {
        if (std::abs(r.range_m - los_m) >= 0.1 && r.amplitude) r.amplitude = amplitude_factor * *r.amplitude;
      }
    }
  });
  std::array<int, 2> count{0, 0};
  for (const auto& a : step.associations) {
    if (a.va_id >= kFirstDiscoveredVaId) ++count[static_cast<std::size_t>(a.anchor_index)];
  }
  return count;
}

TEST(SlamTracker, BlockedAnchorsDiscoveredVasNeedAStrongerAmplitude) {
  // At 0.45 of their amplitude (Rician K = 10 dB: about the law's 0.5-5 % quantile) the ranges
  // pass the ordinary gate (1e-3) but not the blocked anchor's (0.1).
  const auto blocked = DiscoveredAssociationsWithWeakRanges(0.1, true, 0.45);
  EXPECT_EQ(blocked[0], 0) << "anchor 0's LOS is blocked: its VAs' weak ranges are stand-ins";
  EXPECT_GE(blocked[1], 1) << "anchor 1's LOS is there: the ordinary gate for its VAs";
  const auto open = DiscoveredAssociationsWithWeakRanges(0.1, false, 0.45);
  EXPECT_GE(open[0], 1) << "with the LOS present the same weak ranges pass";
  const auto off = DiscoveredAssociationsWithWeakRanges(0.0, true, 0.45);
  EXPECT_GE(off[0], 1) << "switched off, only the ordinary gate";
  const auto strong = DiscoveredAssociationsWithWeakRanges(0.1, true, 1.0);
  const auto strong_off = DiscoveredAssociationsWithWeakRanges(0.0, true, 1.0);
  EXPECT_GE(strong[0], 1);
  EXPECT_EQ(strong, strong_off) << "the paths' own amplitudes pass while the LOS is blocked";
}

// Options for a run with the first-order VAs of the floor plan known and no discovery.
SlamOptions FirstOrderVasKnown() {
  SlamOptions options;
  options.prior_max_order = 1;
  options.discovery.enabled = false;
  return options;
}

// Per VA id, the smallest shift (0-14 cm in 0.5 cm steps) at which step 60 of the loop no longer
// associates that VA (1 m if it always does), with the first-order VAs known. Shifted are the
// reflections' ranges of both anchors, or with `shift_los` anchor 0's LOS range only.
std::map<int, double> RejectionShifts(double gate_chi2, bool prior_visibility, bool reassociate, bool shift_los) {
  const auto plan = mint::testing::EmptySquareRoom();
  const auto vas = mint::testing::SquareRoomVas(plan, 1);
  SlamOptions options = FirstOrderVasKnown();
  options.prior_visibility = prior_visibility;
  options.reassociate = reassociate;
  options.no_visibility_model_gate_chi2 = gate_chi2;
  std::map<int, double> rejected_at_m;
  for (const auto& va : vas.all()) rejected_at_m[va.id] = 1.0;
  for (int i = 28; i >= 0; --i) {  // downwards: the smallest rejecting shift is written last
    const double shift_m = 0.005 * i;
    const auto step = RunToStep(options, vas, vas, 6, 60, [&](std::vector<core::RangeSet>& ranges, const Vec2& p_m) {
      for (auto& anchor : ranges) {
        const double los_m = (vas[anchor.anchor_index].position_m - p_m).norm();  // vas[a]: anchor a
        for (auto& r : anchor.ranges) {
          const bool los = std::abs(r.range_m - los_m) < 0.1;
          if (shift_los ? (los && anchor.anchor_index == 0) : !los) r.range_m += shift_m;
        }
      }
    });
    for (const auto& va : vas.all()) {
      const bool associated = std::any_of(step.associations.begin(), step.associations.end(),
                                          [&](const SlamAssociation& a) { return a.va_id == va.id; });
      if (!associated) rejected_at_m[va.id] = shift_m;
    }
  }
  return rejected_at_m;
}

TEST(SlamTracker, TheNoVisibilityModelGateIsTighterOnlyForVasWithoutAVisibilityRegion) {
  // Without visibility regions (prior_visibility off, as for discovered VAs) the 2-sigma gate
  // rejects a shifted reflection at a smaller shift than the 3-sigma gate. (The ideal ratio of
  // the two shifts is 2/3; the range's own error and the 0.5 cm steps move it, so only the order
  // is asserted.)
  const auto wide = RejectionShifts(0.0, false, true, false);
  const auto tight = RejectionShifts(4.0, false, true, false);
  const auto plan = mint::testing::EmptySquareRoom();
  const auto vas = mint::testing::SquareRoomVas(plan, 1);
  int compared = 0;
  for (const auto& va : vas.all()) {
    if (va.order == 0 || wide.at(va.id) == 0.0) continue;  // an anchor, or not associated even unshifted
    ++compared;
    EXPECT_LT(wide.at(va.id), 1.0) << "VA " << va.id << ": a 14 cm shift leaves the 3-sigma gate";
    EXPECT_LT(tight.at(va.id), wide.at(va.id)) << "VA " << va.id;
  }
  EXPECT_GE(compared, 6) << "most of the 8 first-order VAs are associated at step 60";
  // With visibility regions the option changes nothing.
  EXPECT_EQ(RejectionShifts(4.0, true, true, false), RejectionShifts(0.0, true, true, false));
  // Nor for the anchors' LOS: in the joint association (reassociate off: one stage, with the
  // gate) anchor 0's shifted LOS leaves at the same shift either way.
  const auto los_wide = RejectionShifts(0.0, false, false, true);
  const auto los_tight = RejectionShifts(4.0, false, false, true);
  const int los_id = vas[0].id;  // anchor 0 itself: a VA set lists each anchor before its VAs
  EXPECT_LT(los_wide.at(los_id), 1.0) << "a 14 cm shift leaves the LOS's 3-sigma gate";
  EXPECT_EQ(los_tight.at(los_id), los_wide.at(los_id));
}

// The range variance each VA's association reports at step 60 of the loop (first-order VAs
// known), with the ranges of `erratic_va` off by +-`jump_m` from step 20 on, the sign
// alternating from step to step (as for a VA between two wall offsets whose ranges come from
// either, or a path merged with a neighbouring one now and then). A constant offset would not
// do: the VA is in the state, and its position absorbs it.
std::map<int, double> VariancesAtStep60(int nis_window_updates, int erratic_va, double jump_m) {
  const auto plan = mint::testing::EmptySquareRoom();
  const auto vas = mint::testing::SquareRoomVas(plan, 1);
  SlamOptions options = FirstOrderVasKnown();
  options.nis_window_updates = nis_window_updates;
  SlamTracker tracker(options, vas, plan, kSigma1M);
  const auto samples = Loop();
  tracker.Initialize(samples.front().t_s, samples.front().position_m);
  core::Rng rng(8, 0);
  SlamStepResult step;
  for (std::size_t k = 1; k <= 60; ++k) {
    auto ranges = MeasureRanges(vas, plan, samples[k].position_m, MeasurementModel{}, rng);
    const auto& erratic = vas[erratic_va];
    const double path_m = (erratic.position_m - samples[k].position_m).norm();
    for (auto& r : ranges[static_cast<std::size_t>(erratic.anchor_index)].ranges) {
      if (k >= 20 && std::abs(r.range_m - path_m) < 0.05) r.range_m += k % 2 == 0 ? jump_m : -jump_m;
    }
    step = tracker.Step(samples[k].t_s, ranges);
  }
  std::map<int, double> variance_m2;
  for (const auto& a : step.associations) variance_m2[a.va_id] = a.variance_m2;
  return variance_m2;
}

TEST(SlamTracker, AVaWhoseInnovationsExceedTheirVarianceIsWeightedDown) {
  const auto plan = mint::testing::EmptySquareRoom();
  const auto vas = mint::testing::SquareRoomVas(plan, 1);
  const int erratic = vas.ForAnchor(0)[1];  // anchor 0's first wall VA (ForAnchor lists the anchor first)
  ASSERT_EQ(vas[erratic].order, 1);
  const auto scaled = VariancesAtStep60(20, erratic, 0.03);
  const auto plain = VariancesAtStep60(0, erratic, 0.03);
  ASSERT_TRUE(scaled.count(erratic) && plain.count(erratic)) << "the erratic VA is still associated at step 60";
  // +-3 cm against a range std of 1 cm: the mean NIS is several times 1.
  EXPECT_GT(scaled.at(erratic) / plain.at(erratic), 2.0);
  int consistent = 0;
  for (const auto& [id, variance_m2] : plain) {
    if (id == erratic || !scaled.count(id)) continue;
    ++consistent;
    // A consistent VA's mean NIS over 20 updates stays below 2 (chi^2_20 / 20 > 2 with
    // probability 0.005).
    EXPECT_LT(scaled.at(id) / variance_m2, 2.0) << "VA " << id;
  }
  EXPECT_GE(consistent, 4);
}

// Whether the tracker associates a weak range near anchor 0's LOS at step 60 of the loop, after
// 59 steps of normal ranges (the amplitude window forms after about 18 steps of 5 cm).
bool AssociatesAWeakLosStandIn(double amplitude_gate_probability) {
  const auto plan = mint::testing::EmptySquareRoom();
  const auto vas = mint::testing::SquareRoomVas(plan, 1);
  SlamOptions options = FirstOrderVasKnown();
  options.amplitude_gate_probability = amplitude_gate_probability;
  const int los_id = vas[0].id;  // anchor 0 itself: a VA set lists each anchor before its VAs
  const auto step = RunToStep(options, vas, vas, 5, 60, [&](std::vector<core::RangeSet>& ranges, const Vec2& p_m) {
    // The LOS is blocked: in its place a diffuse-multipath peak 2 cm later at a tenth of the
    // amplitude - inside every range gate.
    const double los_m = (vas[los_id].position_m - p_m).norm();
    auto& list = ranges[0].ranges;
    const auto los = std::min_element(list.begin(), list.end(), [&](const auto& a, const auto& b) {
      return std::abs(a.range_m - los_m) < std::abs(b.range_m - los_m);
    });
    los->range_m = los_m + 0.02;
    los->amplitude = 0.1 * *los->amplitude;
  });
  return std::any_of(step.associations.begin(), step.associations.end(),
                     [&](const SlamAssociation& a) { return a.va_id == los_id; });
}

// The range associated to anchor 0's LOS at step 3 of the loop, before any amplitude window has
// filled: the LOS arrives 8 cm late (as if the track lagged the walker) and a diffuse-multipath
// peak at `peak_factor` of its amplitude arrives where the LOS should be - nearer to the
// prediction, inside every range gate.
std::optional<double> StartUpLosRangeOffset(double startup_amplitude_k_factor, double peak_factor = 0.1) {
  const auto plan = mint::testing::EmptySquareRoom();
  const auto vas = mint::testing::SquareRoomVas(plan, 1);
  SlamOptions options = FirstOrderVasKnown();
  options.startup_amplitude_k_factor = startup_amplitude_k_factor;
  const int los_id = vas[0].id;  // anchor 0 itself
  double los_m = 0.0;
  const auto step = RunToStep(options, vas, vas, 5, 3, [&](std::vector<core::RangeSet>& ranges, const Vec2& p_m) {
    los_m = (vas[los_id].position_m - p_m).norm();
    auto& list = ranges[0].ranges;
    const auto los = std::min_element(list.begin(), list.end(), [&](const auto& a, const auto& b) {
      return std::abs(a.range_m - los_m) < std::abs(b.range_m - los_m);
    });
    core::RangeMeasurement peak = *los;
    peak.amplitude = peak_factor * *los->amplitude;
    los->range_m = los_m + 0.08;
    peak.range_m = los_m;
    list.push_back(peak);
  });
  for (const auto& a : step.associations) {
    if (a.va_id == los_id) return a.measured_range_m - los_m;
  }
  return std::nullopt;
}

TEST(SlamTracker, StartUpAmplitudeLawKeepsTheLosGateOffAWeakerPeak) {
  const auto with_law = StartUpLosRangeOffset(10.0);
  ASSERT_TRUE(with_law.has_value());
  EXPECT_NEAR(*with_law, 0.08, 1e-9) << "the LOS itself, 8 cm late";
  const auto without = StartUpLosRangeOffset(0.0);
  ASSERT_TRUE(without.has_value());
  EXPECT_NEAR(*without, 0.0, 1e-9) << "without the start-up law the nearer weak peak is taken";
  // A peak at 0.7 of the LOS's amplitude is above the K = 10 law's 1e-3 quantile (0.35 of the
  // amplitude the LOS had so far, which this step's draw may fall short of): it passes, and the
  // nearer range wins as without the law.
  const auto strong = StartUpLosRangeOffset(10.0, 0.7);
  ASSERT_TRUE(strong.has_value());
  EXPECT_NEAR(*strong, 0.0, 1e-9);
}

TEST(SlamTracker, ValidateNamesABadStartUpKFactor) {
  SlamOptions options;
  options.startup_amplitude_k_factor = -1.0;
  const auto problems = Validate(options);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].rfind("startup_amplitude_k_factor", 0), 0u);
}

TEST(SlamTracker, ValidateNamesABadSpeedLimit) {
  SlamOptions options;
  options.max_speed_mps = 0.0;  // off
  EXPECT_TRUE(Validate(options).empty());
  for (const double bad : {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    options.max_speed_mps = bad;
    const auto problems = Validate(options);
    ASSERT_EQ(problems.size(), 1u) << bad;
    EXPECT_EQ(problems[0].rfind("max_speed_mps", 0), 0u) << bad;
  }
}

TEST(SlamTracker, AmplitudeGateRejectsAWeakStandInForABlockedLos) {
  EXPECT_FALSE(AssociatesAWeakLosStandIn(1e-3));
  EXPECT_TRUE(AssociatesAWeakLosStandIn(0.0));  // without the gate the range test alone accepts it
}

// Whether the tracker takes anchor 0's LOS at step step_k of the loop back at stage 1 when it
// arrives 0.3 m later than expected (as for a track 0.3 m off after a shadow), at
// `amplitude_factor` of its amplitude, with the LOS missing at the step before if `missed_before`.
// (Here the rest of the map is right, so stage 2 overrules the pulled reference; in the
// seminar room it is the map that is off.)
bool ReacquiresLos(double los_reacquire_m, bool missed_before, double amplitude_factor, std::size_t step_k = 60) {
  const auto plan = mint::testing::EmptySquareRoom();
  const auto vas = mint::testing::SquareRoomVas(plan, 1);
  SlamOptions options;  // amplitude gate on (1e-3)
  options.prior_max_order = 1;
  options.discovery.enabled = false;
  options.los_reacquire_m = los_reacquire_m;
  const auto nearest_los = [&](std::vector<core::RangeSet>& ranges, const Vec2& p_m) {
    const double los_m = (vas[0].position_m - p_m).norm();  // vas[0]: anchor 0 itself
    auto& list = ranges[0].ranges;
    return std::min_element(list.begin(), list.end(), [&](const auto& a, const auto& b) {
      return std::abs(a.range_m - los_m) < std::abs(b.range_m - los_m);
    });
  };
  const Edit miss = [&](std::vector<core::RangeSet>& ranges, const Vec2& p_m) {
    if (missed_before) ranges[0].ranges.erase(nearest_los(ranges, p_m));
  };
  const Edit late = [&](std::vector<core::RangeSet>& ranges, const Vec2& p_m) {
    const auto los = nearest_los(ranges, p_m);
    los->range_m += 0.3;
    los->amplitude = amplitude_factor * *los->amplitude;
  };
  const auto step = RunToStep(options, vas, vas, 5, step_k, late, miss);
  EXPECT_LE(step.reacquired_los, 1) << "anchor 1's LOS was never missed";
  return step.reacquired_los == 1;
}

TEST(SlamTracker, AZeroFirstAmplitudeDoesNotShutTheLosOut) {
  // Recorded input may give an amplitude of 0. At step 1, the first the start-up law records,
  // every range of anchor 0 has one; at step 2 its LOS must still be associated (a law with a
  // zero specular amplitude would reject every amplitude there is).
  const auto plan = mint::testing::EmptySquareRoom();
  const auto vas = mint::testing::SquareRoomVas(plan, 1);
  const Edit zero = [](std::vector<core::RangeSet>& ranges, const Vec2&) {
    for (auto& r : ranges[0].ranges) r.amplitude = 0.0;
  };
  const auto step = RunToStep(FirstOrderVasKnown(), vas, vas, 5, 2, [](auto&, const Vec2&) {}, zero);
  EXPECT_TRUE(std::any_of(step.associations.begin(), step.associations.end(),
                          [&](const SlamAssociation& a) { return a.va_id == vas[0].id; }));
}

TEST(SlamTracker, TheStartUpLawDoesNotWidenTheLosReacquisition) {
  // At step 3 no amplitude window has filled: only the start-up law exists, and only a fitted
  // law may open the wider window. At step 60 the same late LOS is taken back.
  EXPECT_FALSE(ReacquiresLos(0.4, true, 1.0, 3));
  EXPECT_TRUE(ReacquiresLos(0.4, true, 1.0, 60));
}

TEST(SlamTracker, LosReacquisitionTakesAStrongLosOutsideTheCutoffOnlyAfterAMiss) {
  EXPECT_TRUE(ReacquiresLos(0.4, true, 1.0)) << "a missed LOS returning 0.3 m off is searched 0.4 m wide";
  EXPECT_FALSE(ReacquiresLos(0.25, true, 1.0)) << "0.3 m is outside a 0.25 m window";
  EXPECT_FALSE(ReacquiresLos(0.0, true, 1.0)) << "off: the 0.15 m cut-off alone";
  EXPECT_FALSE(ReacquiresLos(0.4, false, 1.0)) << "the LOS was there a step ago: no wider window";
  EXPECT_FALSE(ReacquiresLos(0.4, true, 0.1)) << "a range at a tenth of the LOS amplitude is no LOS";
}

TEST(SlamTracker, ShadowConeWeakensOnlyTheDiscoveredVasBehindABlockedAnchor) {
  // Step 150 is on the loop's westward leg at (2, 4.5): anchor 0 (1, 5) lies 153 deg off the
  // x axis, its west-wall VA (-1, 5) 17 deg from that, its north-wall VA (1, 7) 42 deg away.
  constexpr std::size_t kStep = 150;
  const auto plan = mint::testing::EmptySquareRoom();
  const auto anchors_only = mint::testing::SquareRoomVas(plan, 0);
  const auto truth = mint::testing::SquareRoomVas(plan, 1);
  SlamOptions options;
  options.shadow_cone_deg = 30.0;  // off by default; 5 cm std added
  options.prior_visibility = false;
  const auto block_los = [&](std::vector<core::RangeSet>& ranges, const Vec2& p_m) {
    const double los_m = (anchors_only[0].position_m - p_m).norm();
    std::erase_if(ranges[0].ranges, [&](const core::RangeMeasurement& r) { return std::abs(r.range_m - los_m) < 0.1; });
  };
  const auto step_blocked = RunToStep(options, anchors_only, truth, 4, kStep, block_los);
  const auto step_open = RunToStep(options, anchors_only, truth, 4, kStep, [](auto&, const Vec2&) {});
  const auto& blocked = step_blocked.associations;
  const auto& open = step_open.associations;
  const Vec2 agent_m = step_open.position_m;
  const Vec2 to_anchor = (truth[0].position_m - agent_m).normalized();
  const double shadow_m2 = SlamOptions{}.shadow_sigma_m * SlamOptions{}.shadow_sigma_m;
  int inside = 0, outside = 0;
  for (const auto& a : blocked) {
    ASSERT_NE(a.va_id, truth[0].id) << "the blocked LOS has no range to associate";
    if (a.va_id < kFirstDiscoveredVaId) continue;
    const auto same = std::find_if(open.begin(), open.end(), [&](const SlamAssociation& o) { return o.va_id == a.va_id; });
    ASSERT_NE(same, open.end()) << "VA " << a.va_id << " is associated with the LOS present too";
    // Where does this VA lie? The nearest true VA of its anchor stands for it.
    double best_m = 1e9;
    Vec2 va_m = Vec2::Zero();
    for (const auto& t : truth.all()) {
      if (t.anchor_index != a.anchor_index) continue;
      const double d_m = std::abs((t.position_m - agent_m).norm() - a.measured_range_m);
      if (d_m < best_m) {
        best_m = d_m;
        va_m = t.position_m;
      }
    }
    const double cos_angle = (va_m - agent_m).normalized().dot(to_anchor);
    if (cos_angle > std::cos(30.0 * core::kPi / 180.0)) {
      ++inside;
      EXPECT_NEAR(a.variance_m2 - same->variance_m2, shadow_m2, 1e-4) << "VA " << a.va_id << " in the cone";
    } else {
      ++outside;
      EXPECT_NEAR(a.variance_m2, same->variance_m2, 1e-4) << "VA " << a.va_id << " outside the cone";
    }
  }
  EXPECT_GE(inside, 1) << "the west-wall VA of anchor 0 is discovered and seen at step " << kStep;
  EXPECT_GE(outside, 1);
}

// A track on the wrong intersection of the two LOS circles (the mirror image of the truth about
// the anchors' line, where both LOS ranges fit) with the floor plan's VAs known: the recovery
// scores each candidate by the VAs visible there and restarts the track at the truth, once a LOS
// has gone missing (the search runs only for floor_plan_watch_s after that).
struct MirrorOutcome {
  bool relocalized = false;
  double final_error_m = 0.0;
};

// Anchor 0's LOS (its shortest range) is not detected.
void DropAnchor0Los(std::vector<core::RangeSet>& ranges) {
  auto& r = ranges[0].ranges;
  r.erase(std::min_element(r.begin(), r.end(), [](const auto& a, const auto& b) { return a.range_m < b.range_m; }));
}

// The room, anchors and the two points of a mirror test.
struct MirrorSetup {
  geometry::FloorPlan plan = mint::testing::EmptySquareRoom();
  // Not the fixture's anchors: they lie on the room's anti-diagonal, about which the whole room
  // is symmetric, so there the mirror image explains every VA as well as the truth does.
  std::vector<Vec2> anchors_m{Vec2(1.0, 5.0), Vec2(5.0, 2.0)};
  Vec2 truth_m = Vec2(2.0, 2.5);
  Vec2 mirror_m = Vec2(3.68, 4.74);  // about the anchors' line
  int max_order = 1;                 // of the map and of the measured paths
};

// The tracker starts on the mirror image; the ranges come from there before step jump_step (the
// track is right) and from the truth from then on (the track is lost: both LOS ranges still fit).
// At drop_step (0: never) anchor 0's LOS is not detected.
MirrorOutcome RunFromTheMirror(const SlamOptions& options, int drop_step, int jump_step,
                               const MirrorSetup& setup = {}) {
  const auto vas = geometry::VirtualAnchorSet::Generate(setup.anchors_m, setup.plan, setup.max_order);
  MeasurementModel model;
  model.max_order = setup.max_order;
  SlamTracker tracker(options, vas, setup.plan, kSigma1M);
  tracker.Initialize(0.0, setup.mirror_m);
  core::Rng rng(11, 0);
  MirrorOutcome out;
  for (int k = 1; k <= 40; ++k) {
    auto ranges = MeasureRanges(vas, setup.plan, k < jump_step ? setup.mirror_m : setup.truth_m, model, rng);
    if (k == drop_step) DropAnchor0Los(ranges);
    const auto step = tracker.Step(0.1 * k, ranges);
    out.relocalized = out.relocalized || step.relocalized;
    out.final_error_m = (step.position_m - setup.truth_m).norm();
  }
  return out;
}

// Lost from the first step; the LOS is missed at step 5, or never.
MirrorOutcome StartOnTheMirror(const SlamOptions& options, bool drop_a_los) {
  return RunFromTheMirror(options, drop_a_los ? 5 : 0, 1);
}

SlamOptions FloorPlanMapOptions() {
  SlamOptions options;
  options.prior_max_order = 1;
  options.prior_visibility = true;
  options.discovery.enabled = false;
  return options;
}

TEST(SlamTracker, FloorPlanMapRestartsATrackOnTheMirrorIntersectionAfterALosLoss) {
  SlamOptions options = FloorPlanMapOptions();

  const MirrorOutcome restarted = StartOnTheMirror(options, true);
  EXPECT_TRUE(restarted.relocalized);
  EXPECT_LT(restarted.final_error_m, 0.05);

  // Without stage 1 the miss is read off the joint association: the search runs all the same.
  SlamOptions joint = options;
  joint.reassociate = false;
  const MirrorOutcome without_stage1 = StartOnTheMirror(joint, true);
  EXPECT_TRUE(without_stage1.relocalized);
  EXPECT_LT(without_stage1.final_error_m, 0.05);

  // Without a LOS loss the search does not run; without the recovery the track stays lost.
  const MirrorOutcome unwatched = StartOnTheMirror(options, false);
  EXPECT_FALSE(unwatched.relocalized);
  EXPECT_GT(unwatched.final_error_m, 1.0);
  options.recovery.enabled = false;
  const MirrorOutcome disabled = StartOnTheMirror(options, true);
  EXPECT_FALSE(disabled.relocalized);
  EXPECT_GT(disabled.final_error_m, 1.0);
}

TEST(SlamTracker, FloorPlanSearchEndsFloorPlanWatchSAfterTheLastLosMiss) {
  SlamOptions options = FloorPlanMapOptions();
  // The track is lost from the 11th step on. Steps counted as the tracker does (the k-th call is
  // step k - 1): a miss in the 3rd call is step 2, the loss begins at step 10, and once a
  // candidate has won, the pending restart keeps the search running until it completes. Steps
  // are 0.1 s apart, so a window of 0.7 s is 7 steps.
  constexpr int kMissCall = 3;
  constexpr int kJumpCall = 11;

  // A window of 0.7 s ends at step 9, one step before the loss: the track stays lost.
  options.recovery.floor_plan_watch_s = 0.7;
  const MirrorOutcome expired = RunFromTheMirror(options, kMissCall, kJumpCall);
  EXPECT_FALSE(expired.relocalized);
  EXPECT_GT(expired.final_error_m, 1.0);

  // A window of 0.8 s reaches step 10, the first lost step: the restart completes.
  options.recovery.floor_plan_watch_s = 0.8;
  const MirrorOutcome just_reached = RunFromTheMirror(options, kMissCall, kJumpCall);
  EXPECT_TRUE(just_reached.relocalized);
  EXPECT_LT(just_reached.final_error_m, 0.05);

  // With the short window, a miss after the loss restarts it.
  options.recovery.floor_plan_watch_s = 0.7;
  const MirrorOutcome watched = RunFromTheMirror(options, kJumpCall + 1, kJumpCall);
  EXPECT_TRUE(watched.relocalized);
  EXPECT_LT(watched.final_error_m, 0.05);
}

// The fixture's anchors lie on the square room's anti-diagonal, so the mirror image of a point
// about their line explains the measured ranges with some VA as well as the truth does: counted
// everywhere, 31 VAs of order <= 2 match at either point (noise-free count). Only visibility
// breaks the tie: the truth sees 23 VAs, all matching; at the mirror point the pillar leaves 18
// matching ones visible. Scored where visible, the truth wins by 5 (the margin is 4) and the lost
// track restarts there; scored everywhere it would not (checked by swapping the score).
TEST(SlamTracker, FloorPlanRecoveryScoresEachVaOnlyWhereItIsVisible) {
  MirrorSetup setup;
  setup.plan = mint::testing::SquareRoomWithPillar();
  setup.anchors_m = mint::testing::TwoAnchors();
  setup.truth_m = Vec2(2.7, 1.6);
  setup.mirror_m = Vec2(4.4, 3.3);  // (6 - y, 6 - x): about the anchors' line x + y = 6
  setup.max_order = 2;
  SlamOptions options = FloorPlanMapOptions();
  options.prior_max_order = 2;

  const MirrorOutcome outcome = RunFromTheMirror(options, 5, 1, setup);

  EXPECT_TRUE(outcome.relocalized);
  EXPECT_LT(outcome.final_error_m, 0.05);
}

TEST(SlamTracker, InitializeForgetsAnEarlierLosMiss) {
  const MirrorSetup setup;  // both LOS ranges fit at the mirror point too
  const auto& plan = setup.plan;
  const Vec2& truth_m = setup.truth_m;
  const Vec2& mirror_m = setup.mirror_m;
  const auto vas = geometry::VirtualAnchorSet::Generate(setup.anchors_m, plan, setup.max_order);
  SlamTracker tracker(FloorPlanMapOptions(), vas, plan, kSigma1M);
  core::Rng rng(11, 0);
  // A first run, correct on the mirror point, misses anchor 0's LOS at its last step.
  tracker.Initialize(0.0, mirror_m);
  for (int k = 1; k <= 5; ++k) {
    auto ranges = MeasureRanges(vas, plan, mirror_m, MeasurementModel{}, rng);
    if (k == 5) DropAnchor0Los(ranges);
    tracker.Step(0.1 * k, ranges);
  }
  // A new run starts lost on the mirror point: that miss belongs to the old run and opens no
  // search (kept, it would: the new run's step count starts again below it).
  tracker.Initialize(0.0, mirror_m);
  bool relocalized = false;
  for (int k = 1; k <= 8; ++k) {
    relocalized = tracker.Step(0.1 * k, MeasureRanges(vas, plan, truth_m, MeasurementModel{}, rng)).relocalized ||
                  relocalized;
  }
  EXPECT_FALSE(relocalized);
}

TEST(SlamTracker, ValidateNamesTheBadOption) {
  SlamOptions options;
  options.cutoff_m = 0.0;
  options.blocked_amplitude_probability = 0.6;
  options.los_reacquire_m = -0.1;
  options.no_visibility_model_gate_chi2 = -1.0;
  options.nis_window_updates = -1;
  options.discovered_va_walk_m_per_sqrt_s = -0.001;
  options.discovery.group_size = 2;
  const auto problems = Validate(options);
  ASSERT_EQ(problems.size(), 7u);
  // In the order of the members (the descriptor's).
  EXPECT_EQ(problems[0].rfind("cutoff_m", 0), 0u);
  EXPECT_EQ(problems[1].rfind("no_visibility_model_gate_chi2", 0), 0u);
  EXPECT_EQ(problems[2].rfind("blocked_amplitude_probability", 0), 0u);
  EXPECT_EQ(problems[3].rfind("los_reacquire_m", 0), 0u);
  EXPECT_EQ(problems[4].rfind("nis_window_updates", 0), 0u);
  EXPECT_EQ(problems[5].rfind("discovered_va_walk_m_per_sqrt_s", 0), 0u);
  EXPECT_EQ(problems[6].rfind("discovery.group_size", 0), 0u);
}

TEST(SlamOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMember) {
  test::ExpectDescribesEveryMember(
      SlamOptionsDescriptor(),
      {"cutoff_m", "range_sigma_m", "initial_position_sigma_m", "initial_velocity_sigma_mps", "prior_max_order",
       "prior_va_sigma_m", "prior_visibility", "reassociate", "innovation_gate_chi2", "no_visibility_model_gate_chi2",
       "va_filter", "va_filter_sigma_m", "va_filter_keeps_associating", "va_filter_anchors",
       "amplitude_gate_probability", "startup_amplitude_k_factor", "blocked_amplitude_probability", "shadow_cone_deg",
       "shadow_sigma_m", "los_reacquire_m", "nis_window_updates", "discovered_va_walk_m_per_sqrt_s", "joseph_update",
       "motion", "max_speed_mps", "variance", "discovery", "recovery"});
}

}  // namespace
}  // namespace mirage::methods::slam
