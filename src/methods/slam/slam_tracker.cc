// SPDX-License-Identifier: MIT
#include "mirage/methods/slam/slam_tracker.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <unordered_set>

#include "mirage/core/constants.h"
#include "mirage/core/derived_defaults.h"
#include "mirage/estimation/covariance_ops.h"
#include "mirage/estimation/gates/chi2_gate.h"
#include "mirage/estimation/gates/rician_gate.h"
#include "mirage/estimation/meas/va_range.h"
#include "mirage/estimation/motion/speed_limit.h"
#include "mirage/estimation/range_association.h"
#include "mirage/geometry/visibility.h"
#include "mirage/methods/elapsed_time.h"
#include "mirage/methods/mint/relocalization.h"
#include "mirage/methods/tracker_options.h"

namespace mirage::methods::slam {

using estimation::BlockKey;
namespace blocks = estimation::blocks;

constexpr BlockKey kPosition(blocks::kPosition, 0);
constexpr BlockKey kVelocity(blocks::kVelocity, 0);

const core::OptionsDescriptor<SlamOptions>& SlamOptionsDescriptor() {
  using core::ValueRange;
  using O = SlamOptions;
  static const auto descriptor = [] {
    const ValueRange gate_range = ValueRange::Closed(0.0, 1e6);
    const ValueRange probability_range = ValueRange::Closed(0.0, 0.5);
    core::OptionsDescriptor<O> d("methods::slam::SlamOptions");
    AddTrackerStartFields(d);
    d.Integer(&O::prior_max_order,
              {.key = "prior_max_order",
               .range = ValueRange::Closed(0.0, geometry::kMaxVirtualAnchorOrder),
               .doc = "Highest order of the VAs known at the start from the known floor plan: 0 = only the physical "
                      "anchors (the paper's SLAM), 2 or 3 = the paper's known-VA baseline."});
    d.Number(&O::prior_va_sigma_m,
             {.key = "prior_va_sigma_m",
              .unit = "m",
              .range = ValueRange::Positive(),
              .doc = "Prior standard deviation of each known VA's position: 5 cm (a gap; the digest suggests 5-10 cm). "
                     "The physical anchors are exact and not in the state."});
    d.Boolean(&O::prior_visibility,
              {.key = "prior_visibility",
               .doc = "Prior VAs and the anchors' LOS are associated only where the known floor plan makes them "
                      "visible (ray tracing); off: the floor plan is not used."});
    d.Boolean(&O::reassociate, {.key = "reassociate",
                                .doc = "Two-stage association as in MINT (mirage): the LOS ranges first, then all VAs "
                                       "at that estimate."});
    d.Number(&O::innovation_gate_chi2,
             {.key = "innovation_gate_chi2",
              .range = gate_range,
              .doc = "Innovation gate inside the assignment (mirage; 0 = off), chi^2 with 1 degree of freedom; the "
                     "innovation variance includes the VA's covariance. 9: 3 sigma."});
    d.Number(&O::no_visibility_model_gate_chi2,
             {.key = "no_visibility_model_gate_chi2",
              .range = gate_range,
              .doc = "Innovation gate of the VAs without a visibility model (discovered ones, prior ones without a "
                     "visibility region; mirage; 0 = off): the tighter of this and innovation_gate_chi2. 4 (2 sigma) "
                     "halves the stand-ins of visible but unextracted paths such a VA takes and loses 3 % of its "
                     "right ranges (docs/methods/slam.md)."});
    d.Boolean(&O::va_filter, {.key = "va_filter",
                              .doc = "The VA filter (Leitinger Sec. III-C): a VA whose estimated range std exceeds "
                                     "va_filter_sigma_m takes no part in the association."});
    d.Number(&O::va_filter_sigma_m, {.key = "va_filter_sigma_m",
                                     .unit = "m",
                                     .range = ValueRange::Positive(),
                                     .doc = "sigma_d,max of the VA filter: 6.23 cm, the CRLB at SINR 0 dB (Leitinger "
                                            "Sec. IV)."});
    d.Boolean(&O::va_filter_keeps_associating,
              {.key = "va_filter_keeps_associating",
               .doc = "mirage: a filtered VA still takes part in the association, so its range variance stays current "
                      "and it can come back, but its ranges do not update the state; false (the paper) keeps it out "
                      "for good."});
    d.Boolean(&O::va_filter_anchors,
              {.key = "va_filter_anchors",
               .doc = "mirage: the VA filter applies to the physical anchors' LOS too, which detects a blocked LOS by "
                      "its range variance. Only with va_filter_keeps_associating."});
    d.Number(&O::amplitude_gate_probability,
             {.key = "amplitude_gate_probability",
              .range = probability_range,
              .doc = "Amplitude gate (mirage; 0 = off): a range is not associated to a VA if its amplitude is this "
                     "improbable, P(|alpha| <= measured), under the VA's fitted Rician law (Lafer Eq. 3.27). A blocked "
                     "path's weak diffuse stand-in passes any range gate but not this one."});
    d.Number(&O::startup_amplitude_k_factor,
             {.key = "startup_amplitude_k_factor",
              .range = ValueRange::Closed(0.0, 1e6),
              .doc = "K-factor of the provisional Rician law the amplitude gates use until a VA's amplitude window "
                     "first fills (mirage; 0 = off). 10: keeps the first steps' lagging prediction off weaker peaks "
                     "behind the LOS (seminar room, seed 14); at amplitude_gate_probability 1e-3 it rejects "
                     "amplitudes below 0.35 of the expected one."});
    d.Number(&O::blocked_amplitude_probability,
             {.key = "blocked_amplitude_probability",
              .range = probability_range,
              .doc = "Amplitude gate in a blocked anchor's shadow (mirage; 0 = off): while the anchor's LOS found no "
                     "range, its VAs without a visibility model take a range only if its amplitude has at least this "
                     "probability. 0.1 rejects 37 % of the diffuse stand-ins and 7 % of the paths' own ranges "
                     "(seminar room, seed 1). Needs reassociate."});
    d.Number(&O::shadow_cone_deg,
             {.key = "shadow_cone_deg",
              .unit = "deg",
              .range = ValueRange::Closed(0.0, 180.0),
              .doc = "Shadow cone half-width (mirage; 0 = off): a range of a VA without a visibility model that "
                     "reaches the agent within this angle of an anchor whose LOS found no range gets shadow_sigma_m^2 "
                     "more variance and stays out of the amplitude windows; needs reassociate. Off: since the sweep fills "
                     "the map, p90 is better on 17 of 18 seed-trajectory pairs of the seminar room "
                     "(docs/methods/slam.md)."});
    d.Number(&O::shadow_sigma_m, {.key = "shadow_sigma_m",
                                  .unit = "m",
                                  .range = ValueRange::Positive(),
                                  .doc = "Standard deviation added to a shadowed range: the diffuse stand-in's typical "
                                         "lag. 5 cm."});
    d.Number(&O::los_reacquire_m,
             {.key = "los_reacquire_m",
              .unit = "m",
              .range = ValueRange::NonNegative(),
              .doc = "LOS re-acquisition window (mirage; no effect unless above cutoff_m): an anchor's LOS that found "
                     "no range at the last step is searched this far from the predicted range, amplitude-checked. "
                     "0.4 m: above the drift of most shadowed runs; at 1 m other strong paths were taken for the LOS "
                     "(docs/methods/slam.md)."});
    d.Integer(&O::nis_window_updates,
              {.key = "nis_window_updates",
               .unit = "updates",
               .range = ValueRange::Closed(0.0, 1e5),
               .doc = "Innovation-scaled range variance (mirage; 0 = off): a VA's range variance is multiplied by the "
                      "mean NIS of its last this many updates when that mean exceeds 1 (at least 5 recorded). 20; 10 "
                      "and 40 gave about the same (docs/methods/slam.md)."});
    d.Number(&O::discovered_va_walk_m_per_sqrt_s,
             {.key = "discovered_va_walk_m_per_sqrt_s",
              .unit = "m/sqrt(s)",
              .range = ValueRange::NonNegative(),
              .doc = "Random walk of the discovered VAs (mirage; 0 = off): q^2 dt I is added to each one's covariance "
                     "at every prediction. Off: 6.3 mm/sqrt(s) makes the map's NEES consistent but trajectory 2 "
                     "worse at its corner (docs/methods/slam.md)."});
    d.Boolean(&O::joseph_update,
              {.key = "joseph_update",
               .doc = "Joseph form of the covariance update, as in MINT. Off: the standard form P - K H P halves the "
                      "O(n^2 m) cost of a step with tens of VAs (bench/methods/slam_step_bench.cc)."});
    d.Section(&O::motion,
              {.key = "motion", .doc = "Constant-velocity motion model of the agent (Lafer Eq. 3.13-3.16)."},
              estimation::ConstantVelocityOptionsDescriptor());
    d.Number(&O::max_speed_mps,
             {.key = "max_speed_mps",
              .unit = "m/s",
              .range = ValueRange::NonNegative(),
              .doc = "A walker's speed limit (mirage; 0 = off): a faster velocity estimate is scaled back onto it "
                     "after each update. 1.5 m/s, a brisk walk: it kept a restarted track from running away (seminar "
                     "room, seed 30) and changed no other run. Derived: 3 times the walker's speed (1.5 m/s at the "
                     "seminar room's 0.5 m/s); a velocity estimate beyond it is a track following clutter.",
              .derived = core::SpeedTimes(3.0)});
    d.Section(
        &O::variance,
        {.key = "variance", .doc = "Online range-variance estimation per VA (Lafer Sec. 3.6, Leitinger Sec. III-C)."},
        estimation::RangeVarianceOptionsDescriptor());
    d.Section(&O::discovery, {.key = "discovery", .doc = "Discovery of new VAs (Leitinger Sec. III-D)."},
              DiscoveryOptionsDescriptor());
    d.Section(&O::recovery, {.key = "recovery", .doc = "Track-loss detection and restart (mirage)."},
              TrackRecoveryOptionsDescriptor());
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const SlamOptions& options) { return SlamOptionsDescriptor().Validate(options); }

namespace {

// VAs without a visibility region the map needs before the track-loss recovery runs without the
// floor plan (below).
constexpr std::size_t kRecoveryMinVas = 2;

// The map's prior VAs come from a floor plan and have ray-traced visibility regions: they are
// candidates only where visible, and score in the track-loss recovery only there.
bool ScoresFloorPlanVas(const SlamOptions& options, const geometry::FloorPlan& plan) {
  return options.prior_visibility && options.prior_max_order > 0 && !plan.walls().empty();
}

// The recovery's options, with the margin for the map it scores.
TrackRecoveryOptions RecoveryOptions(const SlamOptions& options, const geometry::FloorPlan& plan) {
  TrackRecoveryOptions recovery = options.recovery;
  if (ScoresFloorPlanVas(options, plan)) recovery.min_margin = recovery.min_margin_floor_plan;
  return recovery;
}

}  // namespace

SlamTracker::SlamTracker(const SlamOptions& options, const geometry::VirtualAnchorSet& known_vas,
                         const geometry::FloorPlan& plan, double range_sigma_at_unit_sinr_m)
    : options_(options),
      known_vas_(&known_vas),
      plan_(&plan),
      variance_(options.variance, range_sigma_at_unit_sinr_m),
      motion_(options.motion),
      discovery_(options.discovery),
      recovery_(RecoveryOptions(options, plan)) {}

void SlamTracker::Initialize(double t_s, const Vec2& p0_m) {
  estimation::StateLayout layout;
  layout.Append(blocks::kPosition, 0);
  layout.Append(blocks::kVelocity, 0);
  Eigen::Vector4d mean;
  mean << p0_m, 0.0, 0.0;
  const double sp2 = options_.initial_position_sigma_m * options_.initial_position_sigma_m;
  const double sv2 = options_.initial_velocity_sigma_mps * options_.initial_velocity_sigma_mps;
  const Eigen::Vector4d diag(sp2, sp2, sv2, sv2);
  state_ = estimation::State(layout, mean, diag.asDiagonal().toDenseMatrix(), t_s);
  variance_.Reset();
  discovery_.Reset();
  recovery_.Reset();
  map_.clear();
  step_ = 0;
  last_los_miss_t_s_.reset();
  next_discovered_id_ = kFirstDiscoveredVaId;
  for (const auto& va : known_vas_->all()) {
    if (va.order > options_.prior_max_order) continue;
    Entry e = NewEntry();
    e.va.id = va.id;
    e.va.anchor_index = va.anchor_index;
    e.va.origin = va.order == 0 ? MapVaOrigin::kAnchor : MapVaOrigin::kPrior;
    e.va.order = va.order;
    e.va.position_m = va.position_m;
    if (va.order > 0) {
      e.va.covariance_m2 = Eigen::Matrix2d::Identity() * options_.prior_va_sigma_m * options_.prior_va_sigma_m;
    }
    e.prior_m = va.position_m;
    map_.push_back(e);
  }
}

bool SlamTracker::InState(std::size_t map_index) const {
  return state_.layout().Find(BlockKey(blocks::kVirtualAnchor, map_[map_index].va.id)).has_value();
}

Vec2 SlamTracker::VaPosition(std::size_t map_index) const {
  if (InState(map_index)) return state_.Mean(BlockKey(blocks::kVirtualAnchor, map_[map_index].va.id));
  return map_[map_index].prior_m;
}

double SlamTracker::CurrentVariance(int va_id) const {
  if (!options_.variance.enabled) return options_.range_sigma_m * options_.range_sigma_m;
  return variance_.CurrentVariance(va_id);
}

bool SlamTracker::HasVisibility(std::size_t map_index) const {
  return map_[map_index].va.origin == MapVaOrigin::kPrior && ScoresFloorPlanVas(options_, *plan_);
}

SlamTracker::Entry SlamTracker::NewEntry() const {
  Entry e;
  e.innovation_scale = estimation::InnovationScale(static_cast<std::size_t>(options_.nis_window_updates));
  return e;
}

bool SlamTracker::LacksVisibilityModel(std::size_t map_index) const {
  return map_[map_index].va.origin != MapVaOrigin::kAnchor && !HasVisibility(map_index);
}

bool SlamTracker::Filtered(std::size_t map_index) const {
  const MapVa& va = map_[map_index].va;
  if (!options_.va_filter || !options_.variance.enabled) return false;
  if (va.origin == MapVaOrigin::kAnchor && !(options_.va_filter_anchors && options_.va_filter_keeps_associating)) {
    return false;
  }
  // Only the VA's own estimate counts: the default 0.07 m would filter every new VA.
  const auto last = variance_.LastEstimatedVariance(va.id);
  return last && *last > options_.va_filter_sigma_m * options_.va_filter_sigma_m;
}

std::vector<std::size_t> SlamTracker::Candidates(int anchor_index, const Vec2& at_m, bool los_only) const {
  std::unordered_set<int> visible;
  const bool use_visibility = options_.prior_visibility && !plan_->walls().empty();
  if (use_visibility) {
    const int max_order = los_only ? 0 : options_.prior_max_order;
    for (const int id : geometry::VisibleVirtualAnchors(*known_vas_, anchor_index, *plan_, at_m, max_order)) {
      visible.insert(id);
    }
  }
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < map_.size(); ++i) {
    const MapVa& va = map_[i].va;
    if (va.anchor_index != anchor_index) continue;
    if (los_only && va.origin != MapVaOrigin::kAnchor) continue;
    if (va.origin != MapVaOrigin::kDiscovered && use_visibility && visible.count(va.id) == 0) continue;
    if (Filtered(i) && !options_.va_filter_keeps_associating) continue;
    out.push_back(i);
  }
  return out;
}

std::vector<SlamTracker::Pairing> SlamTracker::Associate(const Reference& reference,
                                                         std::span<const core::RangeSet> measurements,
                                                         bool los_only, double gate) const {
  std::vector<Pairing> pairings;
  const Vec2& at_m = reference.position_m;
  for (const auto& anchor : measurements) {
    std::vector<std::size_t> candidates;
    std::vector<double> expected_m;
    std::vector<double> predicted_variance_m2;  // the agent's and the VA's part, H P H^T
    std::vector<double> gate_variance_m2;       // plus the VA's range variance
    for (const std::size_t i : Candidates(anchor.anchor_index, at_m, los_only)) {
      // Agent and VA both from the joint state at the reference: with stage 1, a discovered VA
      // correlated with the agent has moved with it, and mixing the agent's posterior with the
      // VA's prior blocks can make H P H^T negative.
      const VaAtReference va = VaAt(reference, i);
      const auto prediction = estimation::PredictVaRange(at_m, va.mean_m);
      if (!prediction) continue;
      candidates.push_back(i);
      expected_m.push_back(prediction->range_m);
      // Innovation variance J_p P_pp J_p^T + J_v P_vv J_v^T + 2 J_p P_pv J_v^T + R (Eq. 16 rows).
      const double variance_m2 =
          (prediction->J_range_p * reference.covariance_m2 * prediction->J_range_p.transpose())(0, 0) +
          (prediction->J_range_va * va.covariance_m2 * prediction->J_range_va.transpose())(0, 0) +
          2.0 * (prediction->J_range_p * va.cross_m2 * prediction->J_range_va.transpose())(0, 0);
      predicted_variance_m2.push_back(variance_m2);
      gate_variance_m2.push_back(variance_m2 + CurrentVariance(map_[i].va.id));
    }
    // Per candidate, the amplitude gate's probability threshold and its law where there is one,
    // and the innovation gate. For the VAs without a visibility model both are stricter: the
    // amplitude threshold while their anchor's LOS is blocked at this step
    // (blocked_amplitude_probability; stage 2 only), the innovation gate always
    // (no_visibility_model_gate_chi2; 0 = off, as for the gate itself).
    const bool anchor_blocked = !los_only && options_.reassociate && LosMissed(anchor.anchor_index);
    std::vector<double> min_amplitude_probability(candidates.size(), options_.amplitude_gate_probability);
    std::vector<std::optional<estimation::RicianLaw>> laws(candidates.size());
    std::vector<double> gate_chi2(candidates.size(), gate);
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      const std::size_t i = candidates[k];
      if (LacksVisibilityModel(i)) {
        if (anchor_blocked) {
          min_amplitude_probability[k] = std::max(min_amplitude_probability[k], options_.blocked_amplitude_probability);
        }
        const double tight = options_.no_visibility_model_gate_chi2;
        if (tight > 0.0) gate_chi2[k] = gate > 0.0 ? std::min(gate, tight) : tight;
      }
      if (min_amplitude_probability[k] > 0.0) {
        laws[k] = GateLaw(i, at_m, expected_m[k]);
        if (!laws[k]) laws[k] = StartUpLaw(i, at_m, expected_m[k]);
      }
    }
    // LOS re-acquisition (SlamOptions::los_reacquire_m): a missed LOS gets the wider window,
    // but only where a fitted amplitude law can vouch for the range (the start-up law, from a
    // few steps' amplitudes, took a reflection 36 cm behind a twice-missed LOS on range-level
    // input and diverged the run). A VA with a fitted law never has a start-up one (StartUpLaw),
    // so a law here with a fitted one in the entry is the fitted law.
    std::vector<double> cutoff_m(candidates.size(), options_.cutoff_m);
    double widest_cutoff_m = options_.cutoff_m;
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      const Entry& e = map_[candidates[k]];
      if (los_only && e.los_missed && laws[k] && e.amplitude_law) {
        cutoff_m[k] = std::max(options_.cutoff_m, options_.los_reacquire_m);
        widest_cutoff_m = std::max(widest_cutoff_m, cutoff_m[k]);
      }
    }
    const auto n_expected = static_cast<Eigen::Index>(candidates.size());
    const auto n_measured = static_cast<Eigen::Index>(anchor.ranges.size());
    Eigen::MatrixXd distance(n_expected, n_measured);
    for (Eigen::Index r = 0; r < n_expected; ++r) {
      const auto k = static_cast<std::size_t>(r);
      const bool widened = cutoff_m[k] > options_.cutoff_m;
      for (Eigen::Index j = 0; j < n_measured; ++j) {
        const auto& z = anchor.ranges[static_cast<std::size_t>(j)];
        const double nu = z.range_m - expected_m[k];
        // The amplitude test (a series) only for pairs the range tests let through.
        const bool range_plausible =
            std::abs(nu) < cutoff_m[k] && estimation::InsideChi2Gate(nu, gate_variance_m2[k], gate_chi2[k]);
        // In the widened window the law is scaled to the range itself (the free-space loss of the
        // path it would be: the expected range can be 0.4 m off), and a range without an
        // amplitude is not taken.
        const auto law = widened ? GateLaw(candidates[k], at_m, z.range_m) : laws[k];
        bool amplitude_plausible = range_plausible;
        if (range_plausible && law) {
          amplitude_plausible =
              z.amplitude ? estimation::RicianCdf(*z.amplitude, *law) >= min_amplitude_probability[k] : !widened;
        }
        distance(r, j) = amplitude_plausible ? std::abs(nu) : std::numeric_limits<double>::infinity();
      }
    }
    const std::vector<int> assignment = estimation::AssociateWithCutoff(distance, widest_cutoff_m);
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      if (assignment[k] < 0) continue;
      Pairing p;
      p.anchor_index = anchor.anchor_index;
      p.map_index = candidates[k];
      p.measurement = &anchor.ranges[static_cast<std::size_t>(assignment[k])];
      p.innovation_m = p.measurement->range_m - expected_m[k];
      p.reacquired = std::abs(p.innovation_m) >= options_.cutoff_m;
      p.predicted_variance_m2 = predicted_variance_m2[k];
      for (std::size_t o = 0; o < candidates.size(); ++o) {
        if (o != k && std::abs(expected_m[o] - expected_m[k]) < options_.variance.overlap_distance_m) {
          p.overlapped = true;
        }
      }
      pairings.push_back(p);
    }
  }
  return pairings;
}

std::optional<estimation::RicianLaw> SlamTracker::GateLaw(std::size_t map_index, const Vec2& at_m,
                                                          double expected_range_m) const {
  const Entry& e = map_[map_index];
  if (!e.amplitude_law) return std::nullopt;
  // Valid near where it was fitted (LawReachM).
  if ((at_m - e.amplitude_law_at_m).norm() > LawReachM()) return std::nullopt;
  estimation::RicianLaw law = *e.amplitude_law;
  // The specular amplitude falls as 1 / d (free-space path loss along the path, Lafer Eq. 2.3);
  // the scatter floor is kept at K <= 100 (20 dB): a window of a strong LOS has almost no spread,
  // and a fluctuation of a few percent must still pass; only a drop to a fraction of the
  // amplitude (a blocked path, a diffuse peak) is rejected.
  law.nu *= e.amplitude_law_range_m / std::max(expected_range_m, 0.1);
  law.scatter_power = std::max(law.scatter_power, law.nu * law.nu / 100.0);
  return law;
}

void SlamTracker::StartUpAmplitudes::Add(double amplitude, double range_m, const Vec2& at_m, double reach_m) {
  if (!(amplitude > 0.0)) return;  // a zero amplitude (recorded input allows it) would zero the law
  if (count == 0 || (at_m - first_at_m).norm() > reach_m) *this = {0.0, 0, at_m};
  amplitude_range_sum_m += amplitude * range_m;
  ++count;
}

std::optional<double> SlamTracker::StartUpAmplitudes::MeanAmplitudeRange(const Vec2& at_m, double reach_m) const {
  if (count == 0 || !(amplitude_range_sum_m > 0.0) || (at_m - first_at_m).norm() > reach_m) return std::nullopt;
  return amplitude_range_sum_m / count;
}

std::optional<estimation::RicianLaw> SlamTracker::StartUpLaw(std::size_t map_index, const Vec2& at_m,
                                                             double expected_range_m) const {
  const Entry& e = map_[map_index];
  if (e.amplitude_law || !(options_.startup_amplitude_k_factor > 0.0)) return std::nullopt;
  // Valid as near as the fitted law is (GateLaw): a VA it shut out at the start is let in again.
  const auto amplitude_range_m = e.startup.MeanAmplitudeRange(at_m, LawReachM());
  if (!amplitude_range_m) return std::nullopt;
  // The specular amplitude the VA's associations so far had, scaled by 1/d as GateLaw's.
  estimation::RicianLaw law;
  law.nu = *amplitude_range_m / std::max(expected_range_m, 0.1);
  law.scatter_power = law.nu * law.nu / options_.startup_amplitude_k_factor;
  return law;
}

void SlamTracker::AddToState(std::size_t map_index) {
  // A prior VA is independent of everything until its first range: adding it now with its prior
  // covariance and no correlation equals carrying it in the state from the start.
  const Entry& e = map_[map_index];
  const Eigen::MatrixXd cross = Eigen::MatrixXd::Zero(2, state_.dimension());
  estimation::CovarianceOps::Augment(state_, blocks::kVirtualAnchor, e.va.id, e.prior_m, cross,
                                     e.va.covariance_m2);
}

SlamTracker::Reference SlamTracker::PriorReference() const {
  return {state_.Mean(kPosition), state_.Covariance(kPosition), std::nullopt};
}

SlamTracker::VaAtReference SlamTracker::VaAt(const Reference& reference, std::size_t map_index) const {
  VaAtReference out;
  if (!InState(map_index)) {  // independent of the agent: stage 1 does not move it
    out.mean_m = map_[map_index].prior_m;
    out.covariance_m2 = map_[map_index].va.covariance_m2;
    return out;
  }
  const BlockKey key(blocks::kVirtualAnchor, map_[map_index].va.id);
  const int v = state_.layout().At(key).offset;
  const int p = state_.layout().At(kPosition).offset;
  if (reference.stage_one) {
    out.mean_m = reference.stage_one->Mean(state_, v);
    out.covariance_m2 = reference.stage_one->Covariance(state_, v, v);
    out.cross_m2 = reference.stage_one->Covariance(state_, p, v);
  } else {
    out.mean_m = state_.Mean(key);
    out.covariance_m2 = state_.covariance().block<2, 2>(v, v);
    out.cross_m2 = state_.covariance().block<2, 2>(p, v);
  }
  return out;
}

SlamTracker::Reference SlamTracker::StageOne(const std::vector<Pairing>& los,
                                             const std::vector<double>& variances_m2) const {
  const int p = state_.layout().At(kPosition).offset;
  Reference reference = PriorReference();
  // Only the position columns of the rows are non-zero: the anchors are not in the state.
  assert(std::none_of(los.begin(), los.end(), [&](const Pairing& q) { return InState(q.map_index); }));
  const Rows rows = Linearize(state_, los, variances_m2);
  const auto m = static_cast<Eigen::Index>(rows.rows.size());
  Eigen::MatrixXd H_p(m, 2);
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(m, m);
  for (Eigen::Index i = 0; i < m; ++i) {
    const auto& row = rows.rows[static_cast<std::size_t>(i)];
    H_p.row(i) = row.jacobians[0].head<2>();  // the agent's position, the row's only block
    R(i, i) = row.variance;
  }
  const Eigen::VectorXd nu = Eigen::Map<const Eigen::VectorXd>(rows.innovations_m.data(), m);
  reference.stage_one = estimation::BlockUpdate::Make(state_, p, H_p, nu, R);
  if (reference.stage_one) {
    reference.position_m = reference.stage_one->Mean(state_, p);
    reference.covariance_m2 = reference.stage_one->Covariance(state_, p, p);
  }
  return reference;
}

std::optional<estimation::MeasurementRow> SlamTracker::VaRow(const estimation::State& state, int va_id,
                                                             double variance_m2) const {
  const auto entry = std::find_if(map_.begin(), map_.end(), [&](const Entry& e) { return e.va.id == va_id; });
  if (entry == map_.end()) return std::nullopt;
  return MapRow(state, static_cast<std::size_t>(entry - map_.begin()), variance_m2);
}

std::optional<estimation::MeasurementRow> SlamTracker::MapRow(const estimation::State& state, std::size_t map_index,
                                                              double variance_m2) const {
  // Leitinger Eq. (16), a current row: the agent's position and the VA's block when it has one.
  const BlockKey key(blocks::kVirtualAnchor, map_[map_index].va.id);
  const auto block = state.layout().Find(key);
  const Vec2 va_m = block ? Vec2(state.mean().segment<2>(block->mean_offset)) : map_[map_index].prior_m;
  return estimation::VaRangeRow(state, state.layout().At(kPosition), va_m, block, variance_m2);
}

SlamTracker::Rows SlamTracker::Linearize(const estimation::State& state, const std::vector<Pairing>& pairings,
                                         const std::vector<double>& variances_m2) const {
  Rows out;
  out.rows.reserve(pairings.size());
  out.innovations_m.reserve(pairings.size());
  for (std::size_t k = 0; k < pairings.size(); ++k) {
    const Pairing& p = pairings[k];
    const auto row = MapRow(state, p.map_index, variances_m2[k]);
    if (!row) continue;
    out.rows.push_back(*row);
    out.innovations_m.push_back(p.measurement->range_m - row->predicted);
  }
  return out;
}

std::vector<BlockKey> SlamTracker::DiscoveredVaBlocks() const {
  std::vector<BlockKey> out;
  for (std::size_t i = 0; i < map_.size(); ++i) {
    if (map_[i].va.origin == MapVaOrigin::kDiscovered && InState(i)) out.emplace_back(blocks::kVirtualAnchor, map_[i].va.id);
  }
  return out;
}

estimation::UpdateResult SlamTracker::Update(estimation::State& state, const std::vector<Pairing>& pairings,
                                             const std::vector<double>& variances_m2) const {
  const Rows rows = Linearize(state, pairings, variances_m2);
  estimation::UpdateOptions update;
  update.form = options_.joseph_update ? estimation::CovarianceForm::kJoseph : estimation::CovarianceForm::kStandard;
  return estimation::Update(state, rows.rows, rows.innovations_m, update);
}

SlamStepResult SlamTracker::Step(double t_s, std::span<const core::RangeSet> measurements) {
  // The agent moves (Eq. 13-14); discovered VAs may take a random walk (off by default).
  const estimation::RandomWalk va_walk(options_.discovered_va_walk_m_per_sqrt_s, DiscoveredVaBlocks());
  estimation::Propagate(state_, t_s, {&motion_, &va_walk});
  SlamStepResult result;
  Reference reference = PriorReference();
  std::vector<Vec2> blocked_m;  // the anchors whose LOS found no range at this step

  if (options_.reassociate) {
    // Stage 1 (as in MINT): the anchors' LOS ranges alone give the reference for stage 2.
    auto los = Associate(reference, measurements, true, 0.0);
    std::erase_if(los, [&](const Pairing& p) { return Filtered(p.map_index); });
    result.reacquired_los =
        static_cast<int>(std::count_if(los.begin(), los.end(), [](const Pairing& p) { return p.reacquired; }));
    NoteLosMisses(los, t_s);
    if (options_.shadow_cone_deg > 0.0) blocked_m = BlockedAnchors();
    if (!los.empty()) {
      std::vector<double> variances;
      for (const auto& p : los) variances.push_back(CurrentVariance(map_[p.map_index].va.id));
      reference = StageOne(los, variances);
    }
  }

  std::vector<Pairing> pairings = Associate(reference, measurements, false, options_.innovation_gate_chi2);
  // Without stage 1 the LOS misses are read off the joint association: the floor-plan recovery's
  // watch window needs them (the shadow cone and the re-acquisition are stage 1's).
  if (!options_.reassociate) NoteLosMisses(pairings, t_s);
  MarkShadowed(pairings, blocked_m, reference.position_m);

  std::vector<double> variances;
  std::vector<Pairing> updating;  // the pairings of VAs the filter lets through
  for (const auto& p : pairings) {
    const MapVa& va = map_[p.map_index].va;
    if (va.origin == MapVaOrigin::kPrior && !InState(p.map_index)) AddToState(p.map_index);
    SlamAssociation a;
    a.anchor_index = p.anchor_index;
    a.va_id = va.id;
    a.measured_range_m = p.measurement->range_m;
    if (options_.variance.enabled) {
      // Overlapping paths' amplitudes are not used (Sec. 3.6), nor a shadowed stand-in's.
      const auto& amplitude = p.measurement->amplitude;
      const bool amplitude_usable = amplitude && !p.overlapped && !p.shadowed;
      if (amplitude_usable) variance_.AddSample(va.id, reference.position_m, *amplitude);
      if (amplitude_usable && !map_[p.map_index].amplitude_law) {
        map_[p.map_index].startup.Add(*amplitude, (VaPosition(p.map_index) - reference.position_m).norm(),
                                      reference.position_m, LawReachM());
      }
      const estimation::RangeVariance v = variance_.Variance(va.id, amplitude_usable);
      a.variance_m2 = v.variance_m2;
      a.sinr = v.sinr;
      if (v.moments) {  // the window the estimate used, at this step's sample position
        Entry& e = map_[p.map_index];
        e.amplitude_law = estimation::RicianFromMoments(v.moments->mean, v.moments->variance);
        e.amplitude_law_at_m = reference.position_m;
        e.amplitude_law_range_m = (VaPosition(p.map_index) - reference.position_m).norm();
      }
    } else {
      a.variance_m2 = options_.range_sigma_m * options_.range_sigma_m;
    }
    // Judged after this step's sample entered the window: a VA leaves (and rejoins) the update
    // as soon as its own estimate says so.
    if (Filtered(p.map_index)) continue;
    // Weighted by the VA's own record of innovations (nis_window_updates), before this one
    // enters it; its NIS against the range variance of this update.
    estimation::InnovationScale& scale = map_[p.map_index].innovation_scale;
    const double scale_nis = p.innovation_m * p.innovation_m / (p.predicted_variance_m2 + a.variance_m2);
    a.variance_m2 *= scale.Factor();
    scale.Add(scale_nis);
    if (p.shadowed) a.variance_m2 += options_.shadow_sigma_m * options_.shadow_sigma_m;
    variances.push_back(a.variance_m2);
    updating.push_back(p);
    result.associations.push_back(a);
    ++map_[p.map_index].va.associations;
  }
  result.update = Update(state_, updating, variances);
  // Before the recovery looks at the track: a runaway velocity would carry the next predictions
  // beyond its reach (max_jump_m).
  estimation::LimitSpeed(state_, 0, options_.max_speed_mps);
  result.relocalized = RecoverTrack(t_s, measurements);

  // Discovery with the ranges nobody took, from the posterior agent position; not at a restart,
  // which has just cleared it and left the agent at its initial std.
  const Vec2 agent_m = state_.Mean(kPosition);
  const Eigen::Matrix2d agent_covariance_m2 = state_.Covariance(kPosition);
  for (const auto& anchor : measurements) {
    if (result.relocalized) break;
    std::vector<core::RangeMeasurement> rest;
    for (const auto& range : anchor.ranges) {
      const bool taken = std::any_of(pairings.begin(), pairings.end(),
                                     [&](const Pairing& p) { return p.measurement == &range; });
      if (!taken) rest.push_back(range);
    }
    std::vector<Vec2> active_m;
    for (std::size_t i = 0; i < map_.size(); ++i) {
      if (map_[i].va.anchor_index == anchor.anchor_index && !Filtered(i)) active_m.push_back(VaPosition(i));
    }
    auto found_vas =
        discovery_.Process(step_, t_s, anchor.anchor_index, agent_m, agent_covariance_m2, rest, active_m,
                           options_.cutoff_m);
    for (auto& found : found_vas) {
      // Lafer Eq. 4.7-4.9 with G_x = [I_2 0]: the new VA is correlated with everything the agent
      // position is, and P_new = P_pp + P_rls.
      const int p_offset = state_.layout().At(kPosition).offset;
      const Eigen::MatrixXd cross = state_.covariance().middleRows(p_offset, 2);
      const Eigen::Matrix2d P_pp = state_.covariance().block<2, 2>(p_offset, p_offset);
      Entry e = NewEntry();
      e.va.id = next_discovered_id_++;
      e.va.anchor_index = anchor.anchor_index;
      e.va.origin = MapVaOrigin::kDiscovered;
      e.va.discovered_step = step_;
      e.prior_m = found.position_m;
      estimation::CovarianceOps::Augment(state_, blocks::kVirtualAnchor, e.va.id, found.position_m, cross,
                                         P_pp + found.covariance_m2);
      // The candidate's amplitudes fill the variance window at once (digest Sec. 2.8, third
      // option), so the VA filter judges a new VA by its own history from the start.
      if (options_.variance.enabled) {
        for (const auto& s : found.samples) {
          if (s.amplitude) variance_.AddSample(e.va.id, s.agent_m, *s.amplitude);
        }
        if (!found.samples.empty() && found.samples.back().amplitude) variance_.Variance(e.va.id, true);
      }
      map_.push_back(e);
      ++result.discovered;
    }
  }
  ++step_;

  result.position_m = state_.Mean(kPosition);
  result.velocity_mps = state_.Mean(kVelocity);
  result.position_covariance = state_.Covariance(kPosition);
  for (const auto& block : state_.layout().blocks()) {
    if (block.key.type_id == blocks::kVirtualAnchor.id) ++result.state_vas;
  }
  return result;
}

void SlamTracker::NoteLosMisses(const std::vector<Pairing>& pairings, double t_s) {
  // A LOS pairing counts only if the VA filter lets it update (stage 1 has dropped the others).
  const auto is_los_of = [&](const Pairing& p, int anchor_index) {
    return p.anchor_index == anchor_index && map_[p.map_index].va.origin == MapVaOrigin::kAnchor &&
           !Filtered(p.map_index);
  };
  bool any_missed = false;
  for (auto& e : map_) {
    if (e.va.origin != MapVaOrigin::kAnchor) continue;
    e.los_missed = std::none_of(pairings.begin(), pairings.end(),
                                [&](const Pairing& p) { return is_los_of(p, e.va.anchor_index); });
    any_missed = any_missed || e.los_missed;
  }
  if (any_missed) last_los_miss_t_s_ = t_s;
}

bool SlamTracker::LosMissed(int anchor_index) const {
  return std::any_of(map_.begin(), map_.end(), [&](const Entry& e) {
    return e.va.origin == MapVaOrigin::kAnchor && e.va.anchor_index == anchor_index && e.los_missed;
  });
}

std::vector<Vec2> SlamTracker::BlockedAnchors() const {
  std::vector<Vec2> blocked_m;
  for (const auto& e : map_) {
    if (e.va.origin == MapVaOrigin::kAnchor && e.los_missed) blocked_m.push_back(e.prior_m);
  }
  return blocked_m;
}

void SlamTracker::MarkShadowed(std::vector<Pairing>& pairings, std::span<const Vec2> blocked_m,
                               const Vec2& at_m) const {
  if (blocked_m.empty()) return;
  // A path reaches the agent from the direction of its VA; within the cone around a blocked
  // anchor's direction it most likely passes the same obstacle (options: shadow_cone_deg).
  const double cos_cone = std::cos(options_.shadow_cone_deg * core::kPi / 180.0);
  std::vector<Vec2> to_blocked;
  for (const Vec2& a_m : blocked_m) to_blocked.push_back((a_m - at_m).normalized());
  for (auto& p : pairings) {
    if (!LacksVisibilityModel(p.map_index)) continue;
    const Vec2 to_va = (VaPosition(p.map_index) - at_m).normalized();
    p.shadowed =
        std::any_of(to_blocked.begin(), to_blocked.end(), [&](const Vec2& u) { return to_va.dot(u) > cos_cone; });
  }
}

bool SlamTracker::RecoverTrack(double t_s, std::span<const core::RangeSet> measurements) {
  if (!options_.recovery.enabled) return false;
  // With the floor plan's VAs (the known-VA baseline) every VA, the anchors' LOS included,
  // scores only where ray tracing makes it visible, as in MINT's relocalization: counted
  // everywhere, hundreds of them matched by chance and restarted good tracks (6 of 25 runs in
  // seminar_room_slam_known.yaml). Without it the points count everywhere, which is right for
  // VAs without a visibility region (discovered ones); with the anchors alone the two LOS
  // intersections tie, so it waits for kRecoveryMinVas such VAs.
  const bool floor_plan = ScoresFloorPlanVas(options_, *plan_);
  // Ray tracing every candidate costs about 110 us per step (BM_SlamStep40Vas with the search at
  // every step): with the floor plan the search runs only for a while after an anchor's LOS went
  // missing (at stage 1, or in the joint association without reassociate), which is how the lost
  // known-VA tracks began (an overshoot at a corner took the LOS out of the cut-off).
  const bool watching =
      last_los_miss_t_s_ && !Exceeds(t_s - *last_los_miss_t_s_, options_.recovery.floor_plan_watch_s);
  if (floor_plan && !watching && !recovery_.pending()) return false;
  std::vector<MapPoint> anchors;
  std::vector<MapPoint> points;  // scored everywhere
  for (std::size_t i = 0; i < map_.size(); ++i) {
    const MapVa& va = map_[i].va;
    if (va.origin == MapVaOrigin::kAnchor) {
      anchors.push_back({va.anchor_index, map_[i].prior_m});
      if (!floor_plan) points.push_back(anchors.back());
    } else if (!HasVisibility(i) && InState(i)) {
      points.push_back({va.anchor_index, VaPosition(i)});
    }
  }
  if (!floor_plan && points.size() < anchors.size() + kRecoveryMinVas) return false;
  const double tolerance_m = options_.recovery.match_tolerance_m;
  mint::RelocalizationOptions visible_scoring;  // MINT's score: the floor plan's VAs visible at p
  visible_scoring.max_order = options_.prior_max_order;
  visible_scoring.match_tolerance_m = tolerance_m;
  const auto score = [&](const Vec2& p_m) {
    int matched = CountMatches(p_m, points, measurements, tolerance_m);
    if (floor_plan) matched += mint::ScorePosition(*known_vas_, *plan_, p_m, measurements, visible_scoring).matched;
    return matched;
  };
  const Vec2 estimate_m = state_.Mean(kPosition);
  const auto restart = recovery_.Check(t_s, estimate_m, anchors, score, measurements);
  if (!restart) return false;
  // Restart the agent as at the start, at the recovered position with the candidates' velocity,
  // uncorrelated with the map: the correlations were built along the lost track. The map keeps
  // its marginal; the discovery's groups and candidates hold positions of the lost track.
  const double sp2 = options_.initial_position_sigma_m * options_.initial_position_sigma_m;
  const double sv2 = options_.initial_velocity_sigma_mps * options_.initial_velocity_sigma_mps;
  estimation::CovarianceOps::Reinitialize(state_, kPosition, restart->position_m,
                                          Eigen::Matrix2d::Identity() * sp2);
  estimation::CovarianceOps::Reinitialize(state_, kVelocity, restart->velocity_mps,
                                          Eigen::Matrix2d::Identity() * sv2);
  discovery_.Reset();
  for (auto& e : map_) {  // both taken along the lost track
    e.innovation_scale.Reset();
    e.startup.Clear();
  }
  return true;
}

std::vector<MapVa> SlamTracker::Map() const {
  std::vector<MapVa> out;
  out.reserve(map_.size());
  for (std::size_t i = 0; i < map_.size(); ++i) {
    MapVa va = map_[i].va;
    if (InState(i)) {
      const BlockKey key(blocks::kVirtualAnchor, va.id);
      va.position_m = state_.Mean(key);
      va.covariance_m2 = state_.Covariance(key);
    }
    va.filtered = Filtered(i);
    if (const auto v = variance_.LastEstimatedVariance(va.id)) va.sigma_m = std::sqrt(*v);
    out.push_back(va);
  }
  return out;
}

}  // namespace mirage::methods::slam
