// SPDX-License-Identifier: MIT
// Anchorless cooperative tracking with the floor plan in the state (Kulmer et al., "Anchorless
// cooperative tracking using multipath channel information", Sec. III, Algorithm 1; digest
// anchorless_coop_kulmer.md Sec. 1.2, 2.4-2.10). One centralised EKF holds the position and
// velocity of every agent and, with the wall update on, the offset of every wall along its normal;
// all cross-covariances are kept (Sec. III-D: they spread the information of an associated MPC to
// the walls and agents it does not touch).
//
// Per step (Algorithm 1): constant-velocity prediction of the agents, walls static without
// process noise (Eq. 16 with its typo fixed: identity, not zero); for every link the expected
// paths of orders 1..max_order (and the line of sight between different antennas) at the
// predicted agents and current walls, visible by ray tracing (Eq. 8-9); expected paths closer
// than d_c to another one on the same link are dropped (Sec. IV-B); round(1.5 |K|) components are
// extracted from the link's CIR (Eq. 6-7); Hungarian assignment with cut-off d_c = c T_p
// (Sec. III-B3); one stacked EKF update of all links with the CRLB range variances (Eq. 13-15,
// 17); then every expected path's amplitude is projected at its delay at the updated state and
// fed to the method-of-moments SINR estimate over a 0.2 m window (Sec. III-C).
//
// Choices where the paper is silent or differs (docs/methods/coop.md):
// - a wall's state is its offset along its normal, not its 2-D reference point: only the normal
//   component enters any path length (digest Sec. 2.2 "Consequence"), so the paper's second
//   coordinate per wall is unobservable and would only carry its prior;
// - the agents start at rest with velocity standard deviation velocity_sigma_mps [GAP 8];
// - on a self link the TX-RX antenna coupling is one extra extracted component, and extracted
//   ranges shorter than self_gate_m are dropped [GAP Sec. 2.3];
// - the amplitude window of an MPC follows the receiving agent (self and anchor links) or the
//   midpoint of the two agents (relative links) [GAP Sec. 2.7].
#pragma once

#include <map>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "mirage/core/medium.h"
#include "mirage/core/options_descriptor.h"
#include "mirage/core/types.h"
#include "mirage/estimation/ekf_update.h"
#include "mirage/estimation/measurement_row.h"
#include "mirage/estimation/motion/constant_velocity.h"
#include "mirage/estimation/state.h"
#include "mirage/geometry/floor_plan.h"
#include "mirage/geometry/image_source.h"
#include "mirage/methods/coop/coop_link.h"
#include "mirage/estimation/range_variance_estimator.h"

namespace mirage::methods::coop {

/// Filter parameters (defaults from Kulmer et al. Sec. IV-B).
struct CoopOptions {
  /// Initial position standard deviation sigma_agent (m), in [1e-9, 1e9]. 0.03 m.
  double agent_sigma_m = 0.03;
  /// Initial velocity standard deviation (m/s), in [1e-9, 1e9] [GAP: not stated]. The agents
  /// start at rest; 0.025 m/s = v_max at one step per second.
  double velocity_sigma_mps = 0.025;
  /// Initial standard deviation of each wall's normal offset sigma_seg (m), in (0, 1]. 3 mm (the
  /// paper also shows 1 and 10 mm: larger adapts faster, smaller is more robust).
  double wall_sigma_m = 0.003;
  /// Walls in the state ("w su"); false keeps them fixed at the provided plan ("w/o su").
  bool wall_update = true;
  /// Maximum speed v_max (m/s), in [1e-9, 1e9]: sigma_a = v_max / (3 dt). 0.025 m per 1 s step.
  double max_speed_mps = 0.025;
  /// Highest reflection order of the expected paths, 1 or 2 (the paper: 2).
  int max_order = 2;
  /// Association cut-off d_c (m), in [0, 1e9]; 0 means c T_p of the pulse (Sec. IV-B).
  double cutoff_m = 0.0;
  /// Components extracted per link = round(factor |K|), in [1, 100]. 1.5 (Sec. IV-B).
  double extraction_factor = 1.5;
  /// Extracted self-link ranges shorter than this are the antenna coupling (m), in [0, 1e9] and
  /// above antenna_spacing_m (where the coupling arrives) when that is > 0. 0.3 m.
  double self_gate_m = 0.3;
  /// Drop an associated range whose innovation exceeds this many standard deviations of its
  /// predicted innovation (h P h^T + r)^(1/2), in [0, 100]; 0 = off (the paper relies on d_c
  /// alone). Our addition [not in the paper]: 3.
  double innovation_gate_sigma = 3.0;
  /// SINR and range variance per MPC (Sec. III-C): window up to 0.2 m of track, default and
  /// fallback sigma 0.07 m (R_0). window_min_m 0.1 m and min_samples 5 are our choices [GAP].
  estimation::RangeVarianceOptions variance = DefaultVariance();
  /// Every agent also measures the channel from the world's first anchor (Sec. IV-D, the
  /// "anchor" variants); off: no anchor at all, the paper's anchorless case.
  bool anchor_links = false;
  /// Distance between an agent's transmit and receive antennas (m), in [0, 0.5]: they sit side by
  /// side along x (coop_link.h). 5 cm, as on the paper's measurement trolley.
  double antenna_spacing_m = 0.05;

  static estimation::RangeVarianceOptions DefaultVariance();
};

/// The options' descriptor (keys, units, ranges, docs, the self-gate check;
/// core/options_descriptor.h). The number of paths that max_order gives depends on the floor
/// plan and is checked where the plan is known.
const core::OptionsDescriptor<CoopOptions>& CoopOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const CoopOptions& options);

/// The agents' constant-velocity model over a step of dt_s (s): sigma_a = v_max / (3 dt), so that
/// a velocity change of v_max within one step is a 3-sigma event (Kulmer Sec. IV-B; digest
/// Sec. 2.4). dt_s <= 0 gives sigma_a = v_max / 3 (a zero step adds no noise whatever sigma_a is).
estimation::ConstantVelocityOptions CoopMotion(const CoopOptions& options, double dt_s);

/// One expected (deterministic) path of a link at the predicted state.
struct ExpectedPath {
  geometry::WallSequence walls;  ///< wall sequence (empty: line of sight)
  geometry::ImagePath path;      ///< predicted length and its derivatives
  int history = 0;               ///< id of its amplitude history
  [[nodiscard]] double range_m() const { return path.length_m; }
};

/// What one step did on one link.
struct LinkStepInfo {
  int visible = 0;     ///< expected paths visible at the prediction
  int expected = 0;    ///< left after the ambiguity pruning (|K|)
  int extracted = 0;   ///< extracted components used (after the self gate)
  int associated = 0;  ///< associated pairs used in the update
  int gated = 0;       ///< associated pairs dropped by the innovation gate
};

/// What one step did.
struct CoopStepInfo {
  std::vector<LinkStepInfo> links;  ///< per link, in links() order
  estimation::UpdateResult update;  ///< the stacked EKF update
};

/// What the filter needs from one link's received signal in one step. Methods work on ranges, not
/// on CIRs (STYLE.md Sec. 1): the pipeline implements this on a simulated or measured CIR with
/// the MPC extractor (methods/coop/cir_link_signal.h). The filter asks for the ranges only after it
/// knows how many paths it expects, and for amplitudes only after its update.
class LinkSignal {
 public:
  virtual ~LinkSignal() = default;
  /// Ranges (m) of the `count` components the search-and-subtract estimator finds first
  /// (Eq. 6-7), in any order.
  [[nodiscard]] virtual std::vector<double> Ranges(int count) const = 0;
  /// |a(tau)|: the magnitude of the received signal projected onto the pulse at delay range / c
  /// (Eq. 6; Sec. III-C uses it at the updated state's delays).
  [[nodiscard]] virtual double AmplitudeAt(double range_m) const = 0;
};

/// The pulse quantities the filter uses.
struct PulseFacts {
  double duration_s = 0.5e-9;               ///< T_p (s): d_c = c T_p
  double range_sigma_at_unit_sinr_m = 0.0;  ///< c / (sqrt(8) pi beta) (m), Eq. (15)
  core::Medium medium;                      ///< carries the signal: c = medium.speed_mps (m/s)
};

/// The centralised cooperative EKF.
class CoopTracker {
 public:
  /// @param provided_plan the floor plan the filter is given (possibly wrong); its walls are the
  ///                      state's walls.
  /// @param links         the links measured each step (EnumerateLinks).
  /// @param anchor_m      the fixed anchor's position when links include anchor links.
  /// @param pulse         duration (d_c) and CRLB scale of the transmit pulse.
  CoopTracker(const CoopOptions& options, geometry::FloorPlan provided_plan, std::vector<Link> links,
              AntennaLayout antennas, std::optional<Vec2> anchor_m, const PulseFacts& pulse);

  /// Starts at the agents' known positions (Sec. IV-B) at rest, at time t_s.
  void Initialize(std::span<const Vec2> positions_m, double t_s);

  /// One step of Algorithm 1 at time t_s on the links' signals (one per link, in links() order).
  CoopStepInfo Step(double t_s, std::span<const LinkSignal* const> signals);

  [[nodiscard]] int agent_count() const { return agents_; }
  [[nodiscard]] const std::vector<Link>& links() const { return links_; }
  [[nodiscard]] const estimation::State& state() const { return state_; }
  [[nodiscard]] Vec2 Position(int agent) const;
  [[nodiscard]] Eigen::Matrix2d PositionCovariance(int agent) const;
  /// Estimated offset of wall s along its normal relative to the provided plan (m); 0 when the
  /// wall update is off.
  [[nodiscard]] double WallOffset(int wall) const;
  /// Its standard deviation (m); 0 when the wall update is off.
  [[nodiscard]] double WallOffsetSigma(int wall) const;
  /// The provided plan with every wall moved by its estimated offset.
  [[nodiscard]] geometry::FloorPlan CurrentPlan() const;
  /// The association cut-off d_c in use (m).
  [[nodiscard]] double cutoff_m() const { return cutoff_m_; }

  /// The linearised row of an expected path's length at the current state (Eq. 13, 14, 17): the
  /// agents' position blocks and, with the wall update, the offset block of each wall of the
  /// path (a wall met twice sums); `variance_m2` becomes its R.
  [[nodiscard]] estimation::MeasurementRow JacobianRow(const Link& link, const ExpectedPath& path,
                                                       double variance_m2) const;
  /// Expected paths of a link at the given agent positions and the current walls, after the
  /// ambiguity pruning (exposed for tests and the position-error bound).
  [[nodiscard]] std::vector<ExpectedPath> ExpectedPaths(int link, std::span<const Vec2> agents_m,
                                                        const geometry::FloorPlan& plan, int* visible = nullptr);

 private:
  int HistoryId(int link, const geometry::WallSequence& walls);
  [[nodiscard]] Vec2 WindowPoint(const Link& link, std::span<const Vec2> agents_m) const;
  [[nodiscard]] std::vector<Vec2> Positions() const;

  CoopOptions options_;
  geometry::FloorPlan provided_plan_;
  std::vector<Link> links_;
  AntennaLayout antennas_;
  Vec2 anchor_m_ = Vec2::Zero();
  double cutoff_m_ = 0.0;
  int agents_ = 0;
  estimation::State state_;
  estimation::RangeVarianceEstimator variance_;
  std::map<std::pair<int, geometry::WallSequence>, int> history_ids_;
};

}  // namespace mirage::methods::coop
