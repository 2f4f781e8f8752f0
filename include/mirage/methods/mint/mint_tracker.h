// SPDX-License-Identifier: MIT
// MINT: multipath-assisted tracking with a known floor plan (Lafer 2014 ch. 3). Per step:
// constant-velocity prediction; visibility of the known VAs; per-anchor optimal assignment of
// the measured ranges to the expected VA ranges with cut-off d_c; online range variance per VA;
// one EKF update with all associated ranges.
//
// mirage adds four switchable safeguards the thesis does not have (docs/methods/mint.md shows
// what each one does to the seminar-room results): a two-stage association (LOS first), an
// innovation gate inside the assignment, a feasible-region constraint (the in-room check of
// Sec. 4.4.3 done as a wall-crossing test) and track-loss relocalization.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mirage/core/records.h"
#include "mirage/core/options_descriptor.h"
#include "mirage/estimation/ekf_update.h"
#include "mirage/estimation/measurement_row.h"
#include "mirage/estimation/motion/constant_velocity.h"
#include "mirage/estimation/state.h"
#include "mirage/geometry/floor_plan.h"
#include "mirage/geometry/virtual_anchor.h"
#include "mirage/methods/mint/relocalization.h"
#include "mirage/estimation/range_variance_estimator.h"

namespace mirage::methods::mint {

/// Parameters of the MINT tracker (defaults from Lafer 2014 Tab. 3.1 where it gives them).
struct MintOptions {
  /// Cut-off distance d_c of the data association (m), in [1e-9, 1e9]. 0.15 m (Tab. 3.1).
  /// Derived (methods/tracker_options.h): 3 range sigmas plus one step of motion.
  double cutoff_m = 0.15;
  /// Range standard deviation sigma_z used when variance estimation is off (m), in [1e-9, 1e9].
  /// 0.07 m (Tab. 3.1: sigma_z^2 = 0.0049 m^2); derived: the scenario's range noise.
  double range_sigma_m = 0.07;
  /// Standard deviation of the initial position sigma_i (m), in [1e-9, 1e9]. 0.1 m (Tab. 3.1:
  /// 0.01 m^2).
  double initial_position_sigma_m = 0.1;
  /// Standard deviation of the initial velocity (m/s), in [1e-9, 1e9]; the filter starts at rest
  /// [GAP]. 0.5 m/s, the maximum walking speed v_max of Tab. 3.1; derived: the walker's speed.
  double initial_velocity_sigma_mps = 0.5;
  /// Highest order of the known VAs used by the tracker, in [0, 6]. 2 (Tab. 3.1).
  int max_order = 2;
  /// Two-stage association (mirage): update with the LOS ranges first, associate all VAs at that
  /// estimate instead of at the prediction, then update the prediction with all of them. After
  /// a corner the constant-velocity prediction overshoots by up to 10 cm, enough to pair
  /// reflections with their neighbours.
  bool reassociate = true;
  /// Innovation gate inside the assignment (mirage; 0 switches it off), in [0, 1e6]: a pair whose
  /// squared innovation exceeds this many times its variance J P J^T + R is never associated. 9 is a
  /// 3-sigma gate (chi^2 with 1 degree of freedom: 99.7 %). It rejects the diffuse-multipath
  /// spikes the fixed cut-off d_c lets through around weak reflections.
  double innovation_gate_chi2 = 9.0;
  /// Keep the estimate inside the room and out of obstacles (mirage's version of Sec. 4.4.3's
  /// in-room check, as a segment-crossing test between consecutive estimates): a move from the
  /// previous estimate that crosses a wall or enters an obstacle is stopped 1 cm before it. Only
  /// the mean moves.
  bool constrain_to_room = true;
  /// Motion model.
  estimation::ConstantVelocityOptions motion;
  /// Online variance estimation (Sec. 3.6).
  estimation::RangeVarianceOptions variance;
  /// Track-loss detection and relocalization (mirage); its max_order is at most max_order.
  RelocalizationOptions relocalization;
};

/// The options' descriptor (keys, units, ranges, docs, the relocalization order check;
/// core/options_descriptor.h). The number of VAs that max_order gives depends on the floor plan
/// and is checked where the plan is known.
const core::OptionsDescriptor<MintOptions>& MintOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const MintOptions& options);

/// One association made at a step.
struct MintAssociation {
  int anchor_index = 0;
  int va_id = 0;
  double expected_range_m = 0.0;
  double measured_range_m = 0.0;
  double variance_m2 = 0.0;     ///< range variance used in R (m^2)
  std::optional<double> sinr;   ///< SINR estimated at this step, if any (linear)
  bool overlapped = false;      ///< another visible VA's range was within the overlap distance
};

/// What one step produced.
struct MintStepResult {
  Vec2 position_m = Vec2::Zero();
  Vec2 velocity_mps = Vec2::Zero();
  Eigen::Matrix2d position_covariance = Eigen::Matrix2d::Zero();
  int visible_count = 0;  ///< known VAs visible at the reference position, all anchors
  std::vector<MintAssociation> associations;
  estimation::UpdateResult update;
  bool constrained = false;    ///< the feasible-region constraint moved the estimate
  bool relocalized = false;    ///< the tracker was restarted at a searched position
};

/// The tracker for one agent. Not thread-safe; one instance per run.
class MintTracker {
 public:
  /// @param vas  the known VAs (the tracker uses those up to options.max_order).
  /// @param plan the known floor plan, for visibility.
  /// @param range_sigma_at_unit_sinr_m c / (sqrt(8) pi beta) of the pulse (m), Eq. (3.28).
  MintTracker(const MintOptions& options, const geometry::VirtualAnchorSet& vas, const geometry::FloorPlan& plan,
              double range_sigma_at_unit_sinr_m);

  /// Starts at position p0_m at rest (Tab. 3.1 initial variance).
  void Initialize(double t_s, const Vec2& p0_m);

  /// Predicts to t_s (>= the previous time) and updates with the ranges of all anchors.
  MintStepResult Step(double t_s, std::span<const core::RangeSet> measurements);

  [[nodiscard]] const estimation::State& state() const { return state_; }
  /// The linearised range to known VA va_id at `state` (Eq. 3.18, 3.19): the agent's position
  /// block only, the VA fixed; variance_m2 becomes its R. Every update row is built here. Empty
  /// when the agent sits on the VA.
  [[nodiscard]] std::optional<estimation::MeasurementRow> VaRow(const estimation::State& state, int va_id,
                                                                double variance_m2) const;

 private:
  // One association: a visible VA and the measurement assigned to it.
  struct Pairing {
    int anchor_index = 0;
    int va_id = 0;
    const core::RangeMeasurement* measurement = nullptr;
    bool overlapped = false;
  };
  // Where and how certainly the association is made.
  struct Reference {
    Vec2 position_m = Vec2::Zero();
    Eigen::Matrix2d covariance_m2 = Eigen::Matrix2d::Zero();
  };
  // Visible VAs up to max_order at the reference, assigned per anchor (Eq. 3.6-3.9), with the
  // innovation gate `gate` (chi^2 threshold, 0 = none). Adds the number of visible VAs to
  // *visible_count when given.
  [[nodiscard]] std::vector<Pairing> Associate(const Reference& reference,
                                               std::span<const core::RangeSet> measurements, int max_order,
                                               double gate, int* visible_count) const;
  // EKF update of `state` with the pairings, linearised at its mean (Eq. 3.18-3.24). The
  // optional sinrs (parallel to pairings) are copied into the reported associations.
  estimation::UpdateResult Update(estimation::State& state, const std::vector<Pairing>& pairings,
                                  const std::vector<double>& variances_m2,
                                  const std::vector<std::optional<double>>& sinrs,
                                  std::vector<MintAssociation>* associations) const;
  // Range variance of the VA as it stands, without recording anything (m^2).
  [[nodiscard]] double CurrentVariance(int va_id) const;
  // Loss detection on the score at `position_m`; relocalizes when lost. True if it restarted.
  bool CheckTrackLoss(const Vec2& position_m, std::span<const core::RangeSet> measurements);

  MintOptions options_;
  const geometry::VirtualAnchorSet* vas_;
  const geometry::FloorPlan* plan_;
  estimation::RangeVarianceEstimator variance_;
  estimation::ConstantVelocity motion_;
  estimation::State state_;
  std::optional<Vec2> previous_position_m_;
  int lost_steps_ = 0;
};

}  // namespace mirage::methods::mint
