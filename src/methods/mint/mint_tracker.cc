// SPDX-License-Identifier: MIT
#include "mirage/methods/mint/mint_tracker.h"

#include <cmath>
#include <limits>

#include "mirage/estimation/gates/chi2_gate.h"
#include "mirage/estimation/meas/va_range.h"
#include "mirage/estimation/range_association.h"
#include "mirage/geometry/feasible_region.h"
#include "mirage/geometry/visibility.h"
#include "mirage/methods/tracker_options.h"

namespace mirage::methods::mint {

namespace blocks = estimation::blocks;

constexpr estimation::BlockKey kPosition(blocks::kPosition, 0);
constexpr estimation::BlockKey kVelocity(blocks::kVelocity, 0);

const core::OptionsDescriptor<MintOptions>& MintOptionsDescriptor() {
  using core::ValueRange;
  using O = MintOptions;
  static const auto descriptor = [] {
    const ValueRange order_range = ValueRange::Closed(0.0, geometry::kMaxVirtualAnchorOrder);
    core::OptionsDescriptor<O> d("methods::mint::MintOptions");
    AddTrackerStartFields(d);
    d.Integer(&O::max_order, {.key = "max_order",
                              .range = order_range,
                              .doc = "Highest order of the known VAs the tracker uses. 2 (Lafer Tab. 3.1)."});
    d.Boolean(&O::reassociate,
              {.key = "reassociate",
               .doc = "Two-stage association (mirage): update with the LOS ranges first, associate all VAs at that "
                      "estimate. After a corner the constant-velocity prediction overshoots by up to 10 cm, enough to "
                      "pair reflections with their neighbours."});
    d.Number(&O::innovation_gate_chi2,
             {.key = "innovation_gate_chi2",
              .range = ValueRange::Closed(0.0, 1e6),
              .doc = "Innovation gate inside the assignment (mirage; 0 = off): a pair whose squared innovation exceeds "
                     "this many times its variance is never associated. 9, a 3-sigma gate (chi^2, 1 degree of "
                     "freedom), rejects the diffuse-multipath spikes the cut-off lets through near weak reflections."});
    d.Boolean(&O::constrain_to_room,
              {.key = "constrain_to_room",
               .doc = "Keep the estimate inside the room and out of obstacles (mirage's wall-crossing version of the "
                      "in-room check of Lafer Sec. 4.4.3): a move that crosses a wall stops 1 cm before it."});
    d.Section(&O::motion, {.key = "motion", .doc = "Constant-velocity motion model (Lafer Eq. 3.13-3.16)."},
              estimation::ConstantVelocityOptionsDescriptor());
    d.Section(&O::variance, {.key = "variance", .doc = "Online range-variance estimation per VA (Lafer Sec. 3.6)."},
              estimation::RangeVarianceOptionsDescriptor());
    d.Section(&O::relocalization, {.key = "relocalization", .doc = "Track-loss detection and relocalization (mirage)."},
              RelocalizationOptionsDescriptor());
    d.Check("relocalization.max_order <= max_order when relocalization.enabled",
            [=](const O& o) -> std::vector<std::string> {
              const int order = o.relocalization.max_order;
              if (!o.relocalization.enabled || order <= o.max_order || !order_range.Contains(order) ||
                  !order_range.Contains(o.max_order)) {
                return {};
              }
              return {"relocalization.max_order: " + std::to_string(order) + " must be <= max_order (" +
                      std::to_string(o.max_order) + "): the tracker knows no higher-order VAs"};
            });
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const MintOptions& options) { return MintOptionsDescriptor().Validate(options); }

MintTracker::MintTracker(const MintOptions& options, const geometry::VirtualAnchorSet& vas,
                         const geometry::FloorPlan& plan, double range_sigma_at_unit_sinr_m)
    : options_(options),
      vas_(&vas),
      plan_(&plan),
      variance_(options.variance, range_sigma_at_unit_sinr_m),
      motion_(options.motion) {}

void MintTracker::Initialize(double t_s, const Vec2& p0_m) {
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
  previous_position_m_ = p0_m;
  lost_steps_ = 0;
}

std::vector<MintTracker::Pairing> MintTracker::Associate(const Reference& reference,
                                                         std::span<const core::RangeSet> measurements,
                                                         int max_order, double gate, int* visible_count) const {
  std::vector<Pairing> pairings;
  const Vec2& at_m = reference.position_m;
  for (const auto& anchor : measurements) {
    // Visibility at the reference position (Sec. 3.4: the predicted p^-), expected ranges
    // (Eq. 3.6) and the innovation variances J P J^T + R of the gate.
    std::vector<int> visible;
    std::vector<double> expected_m;
    std::vector<double> gate_variance_m2;
    for (const int id : geometry::VisibleVirtualAnchors(*vas_, anchor.anchor_index, *plan_, at_m, max_order)) {
      const auto prediction = estimation::PredictVaRange(at_m, (*vas_)[id].position_m);
      if (!prediction) continue;  // agent on top of the VA: no direction
      visible.push_back(id);
      expected_m.push_back(prediction->range_m);
      const auto& J = prediction->J_range_p;
      gate_variance_m2.push_back((J * reference.covariance_m2 * J.transpose())(0, 0) + CurrentVariance(id));
    }
    if (visible_count != nullptr) *visible_count += static_cast<int>(visible.size());
    // Cut-off distances |d_i - z_j| (Eq. 3.8); pairs outside the innovation gate are ruled out.
    const auto n_expected = static_cast<Eigen::Index>(visible.size());
    const auto n_measured = static_cast<Eigen::Index>(anchor.ranges.size());
    Eigen::MatrixXd distance(n_expected, n_measured);
    for (Eigen::Index i = 0; i < n_expected; ++i) {
      const auto k = static_cast<std::size_t>(i);
      for (Eigen::Index j = 0; j < n_measured; ++j) {
        const double nu = anchor.ranges[static_cast<std::size_t>(j)].range_m - expected_m[k];
        distance(i, j) = estimation::InsideChi2Gate(nu, gate_variance_m2[k], gate) ? std::abs(nu)
                                                                                 : std::numeric_limits<double>::infinity();
      }
    }
    const std::vector<int> assignment = estimation::AssociateWithCutoff(distance, options_.cutoff_m);
    for (std::size_t i = 0; i < visible.size(); ++i) {
      if (assignment[i] < 0) continue;
      Pairing p;
      p.anchor_index = anchor.anchor_index;
      p.va_id = visible[i];
      p.measurement = &anchor.ranges[static_cast<std::size_t>(assignment[i])];
      for (std::size_t k = 0; k < visible.size(); ++k) {
        if (k != i && std::abs(expected_m[k] - expected_m[i]) < options_.variance.overlap_distance_m) p.overlapped = true;
      }
      pairings.push_back(p);
    }
  }
  return pairings;
}

estimation::UpdateResult MintTracker::Update(estimation::State& state, const std::vector<Pairing>& pairings,
                                             const std::vector<double>& variances_m2,
                                             const std::vector<std::optional<double>>& sinrs,
                                             std::vector<MintAssociation>* associations) const {
  std::vector<estimation::MeasurementRow> rows;  // Eq. (3.18), (3.19)
  std::vector<double> innovations;
  rows.reserve(pairings.size());
  innovations.reserve(pairings.size());
  for (std::size_t k = 0; k < pairings.size(); ++k) {
    const Pairing& p = pairings[k];
    const auto row = VaRow(state, p.va_id, variances_m2[k]);
    if (!row) continue;
    rows.push_back(*row);
    innovations.push_back(p.measurement->range_m - row->predicted);  // Eq. (3.20)
    if (associations != nullptr) {
      MintAssociation a;
      a.anchor_index = p.anchor_index;
      a.va_id = p.va_id;
      a.expected_range_m = row->predicted;
      a.measured_range_m = p.measurement->range_m;
      a.variance_m2 = variances_m2[k];
      if (k < sinrs.size()) a.sinr = sinrs[k];
      a.overlapped = p.overlapped;
      associations->push_back(a);
    }
  }
  return estimation::Update(state, rows, innovations);
}

std::optional<estimation::MeasurementRow> MintTracker::VaRow(const estimation::State& state, int va_id,
                                                             double variance_m2) const {
  return estimation::VaRangeRow(state, state.layout().At(kPosition), (*vas_)[va_id].position_m, std::nullopt,
                                variance_m2);
}

double MintTracker::CurrentVariance(int va_id) const {
  if (!options_.variance.enabled) return options_.range_sigma_m * options_.range_sigma_m;
  return variance_.CurrentVariance(va_id);
}

bool MintTracker::CheckTrackLoss(const Vec2& position_m, std::span<const core::RangeSet> measurements) {
  const auto& reloc = options_.relocalization;
  const MatchScore score = ScorePosition(*vas_, *plan_, position_m, measurements, reloc);
  if (score.visible < reloc.min_visible || score.fraction() >= reloc.lost_score) {
    lost_steps_ = 0;
    return false;
  }
  if (++lost_steps_ < reloc.lost_steps) return false;
  lost_steps_ = 0;
  const auto found = SearchPosition(*vas_, *plan_, position_m, measurements, reloc);
  if (!found) return false;
  // Restart at the found position as at the start: at rest, initial covariance. The variance
  // history was gathered along the lost track, so it is dropped too.
  Initialize(state_.t_s(), *found);
  return true;
}

MintStepResult MintTracker::Step(double t_s, std::span<const core::RangeSet> measurements) {
  estimation::Propagate(state_, t_s, {&motion_});
  MintStepResult result;
  Reference reference{state_.Mean(kPosition), state_.Covariance(kPosition)};

  if (options_.reassociate) {
    // Stage 1: the LOS ranges alone, with the variances known so far. Their posterior is the
    // reference at which all VAs are associated in stage 2. No innovation gate here: right
    // after a corner the prediction is off by more than its covariance admits, and the LOS,
    // the strongest and earliest path, is the range that can tell.
    const auto los = Associate(reference, measurements, 0, 0.0, nullptr);
    if (!los.empty()) {
      std::vector<double> variances;
      for (const auto& p : los) variances.push_back(CurrentVariance(p.va_id));
      estimation::State trial = state_;
      if (Update(trial, los, variances, {}, nullptr).applied) {
        reference = {trial.Mean(kPosition), trial.Covariance(kPosition)};
      }
    }
  }

  const auto pairings =
      Associate(reference, measurements, options_.max_order, options_.innovation_gate_chi2, &result.visible_count);
  std::vector<double> variances;
  std::vector<std::optional<double>> sinrs;
  for (const auto& p : pairings) {
    if (options_.variance.enabled) {
      // Sec. 3.6: amplitudes of overlapping paths are not used, their variance falls back.
      const auto& amplitude = p.measurement->amplitude;
      if (amplitude && !p.overlapped) variance_.AddSample(p.va_id, reference.position_m, *amplitude);
      const estimation::RangeVariance v = variance_.Variance(p.va_id, !p.overlapped && amplitude.has_value());
      variances.push_back(v.variance_m2);
      sinrs.push_back(v.sinr);
    } else {
      variances.push_back(options_.range_sigma_m * options_.range_sigma_m);
      sinrs.emplace_back();
    }
  }
  result.update = Update(state_, pairings, variances, sinrs, &result.associations);

  if (options_.constrain_to_room && previous_position_m_) {
    const Vec2 estimate_m = state_.Mean(kPosition);
    const Vec2 feasible_m = geometry::ConstrainMove(*plan_, *previous_position_m_, estimate_m);
    if (feasible_m != estimate_m) {
      state_.SetMean(kPosition, feasible_m);
      result.constrained = true;
    }
  }
  if (options_.relocalization.enabled) {
    result.relocalized = CheckTrackLoss(state_.Mean(kPosition), measurements);
  }
  previous_position_m_ = state_.Mean(kPosition);

  result.position_m = state_.Mean(kPosition);
  result.velocity_mps = state_.Mean(kVelocity);
  result.position_covariance = state_.Covariance(kPosition);
  return result;
}

}  // namespace mirage::methods::mint
