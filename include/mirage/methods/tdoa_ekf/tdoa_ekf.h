// SPDX-License-Identifier: MIT
// tdoa_ekf: a 3-D constant-velocity filter on pairwise time differences of arrival in metres,
// tdoa_m = |p - a_j| - |p - a_i| (core::TdoaMeasurement; UWB TDOA systems such as Bitcraze's Loco
// Positioning, tdoa.csv). Row of the Jacobian: d tdoa / d p = (u_j - u_i)^T, u = (p - a) / |p - a|
// (estimation/meas/tdoa.h); the velocity columns are (t_row - t_state) (u_j - u_i)^T for a row at
// another time than the state's (the window below), else 0. Three updates, for the comparison of
// Bordoy 2020 ch. 5 carried to UWB TDOA:
//   - ekf: every difference enters the plain EKF update;
//   - gated_ekf: a difference whose innovation lies outside a chi-square gate on h P h^T + R is
//     dropped (the standard safeguard);
//   - rekf: the robust EKF of Bordoy Sec. 5.2 (Eq. 5.25-5.30, estimation/robust/irls_update.h):
//     the prior and the differences of one time stamp are stacked into one whitened regression
//     solved by IRLS with Hampel weights (Eq. 5.24), so a biased or gross difference loses its
//     weight gradually, and a wrong prediction can lose to the measurements.
// Each difference is one row with its own variance tdoa_sigma_m^2: the simulator's and the
// recorders' noise is per reported difference, so R is diagonal and the weights can isolate one
// bad row (issue 26: "keep a diagonal R").
// The physical bound |tdoa| <= |a_i - a_j| (the triangle inequality; Bordoy Eq. 5.5 for stamps)
// holds for every true difference; with noise it is widened by 3 tdoa_sigma_m. It drops most
// gross outliers (a 50 m outlier in a room of 10 m baselines) before any statistics and is on for
// every update (baseline_gate).
// Self-initialisation (no start point): once the usable differences span window_s (the time in
// which the agent moves one standard deviation of a difference) and number at least 7, they are
// solved for the position by Gauss-Newton with Hampel weights from several starts
// (estimation/init/tdoa_position_fix.h); the fix is taken when it is no less certain than the
// anchors' spread and lies inside the given floor plan, between floor and ceiling.
// Event-driven: ekf and gated_ekf propagate to each difference's time and update with the rows of
// that time stamp (as Bitcraze's kalman_core does). rekf collects the rows of window_s (at
// least 7) and updates with all of them at once: a lone row can never outvote the six prior rows of Eq. 5.26,
// so per-row IRLS would keep a wrong prediction forever; each row is predicted at its own time
// from the state's mean and velocity (the constant-velocity model), its Jacobian carrying
// d (t - t_state) in the velocity columns and its variance the motion model's over the offset.
#pragma once

#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "mirage/core/options_descriptor.h"
#include "mirage/estimation/init/position_fix.h"
#include "mirage/estimation/motion/constant_velocity.h"
#include "mirage/estimation/robust/irls_update.h"
#include "mirage/estimation/state.h"
#include "mirage/methods/estimator.h"
#include "mirage/methods/world.h"

namespace mirage::methods::tdoa_ekf {

/// Options of the TDOA filter.
struct TdoaEkfOptions {
  /// The measurement update: "rekf" (Hampel IRLS, Bordoy Sec. 5.2), "gated_ekf" (EKF with a
  /// chi-square gate) or "ekf" (every difference, for comparison).
  std::string update = "rekf";
  /// Standard deviation of one reported difference (m), > 0. 0.15 m (Loco Positioning TDOA3);
  /// derived from the scenario's noise.
  double tdoa_sigma_m = 0.15;
  /// Drop a difference larger in magnitude than the anchors' baseline plus 3 tdoa_sigma_m (the
  /// triangle inequality bounds every true difference by the baseline).
  bool baseline_gate = true;
  /// gated_ekf: chi-square gate on one difference's innovation (1 degree of freedom), > 0. 9 = 3
  /// sigma of h P h^T + R, 99.7 % of consistent differences.
  double gate_chi2 = 9.0;
  /// The robust update's reweighting (rekf).
  estimation::IrlsOptions irls;
  /// Position standard deviation of a given start point (m), > 0. 0.5 m: a start known to the
  /// room's scale. A self-initialised start uses its fix's covariance instead.
  double initial_position_sigma_m = 0.5;
  /// Velocity standard deviation at the start (m/s), > 0. Derived from the agent's speed.
  double initial_velocity_sigma_mps = 1.0;
  /// The differences of this long a window are solved together (s), > 0: by the rekf update,
  /// which needs more rows than the state has unknowns to let the rows outvote a wrong
  /// prediction, and by the self-initialisation. 0.1 s; derived as tdoa_sigma_m / speed_mps (at
  /// most 1 s), the time in which the agent moves one standard deviation of a difference. The
  /// rekf predicts each row at its own time with the constant-velocity model, so the window
  /// costs latency, not a bias; the fix assumes the agent still.
  double window_s = 0.1;
  /// The agent's motion.
  estimation::ConstantVelocityOptions motion;
};

/// The options' descriptor (keys, units, ranges, docs; core/options_descriptor.h).
const core::OptionsDescriptor<TdoaEkfOptions>& TdoaEkfOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const TdoaEkfOptions& options);

/// What one update did with its rows.
struct TdoaUpdateCounts {
  int used = 0;      ///< rows that entered with weight > 0 (all of them for ekf)
  int rejected = 0;  ///< rows the baseline bound, the gate, a zero weight or a failed update removed
  bool failed = false;  ///< the update could not be applied (a covariance not positive definite)
};

class TdoaEkf final : public Estimator {
 public:
  /// Throws std::invalid_argument for invalid options or fewer than 4 anchors (3-D needs 4).
  TdoaEkf(const TdoaEkfOptions& options, const World& world);

  void Initialize(const Prior& prior) override;
  /// Collects the differences of the last window_s and starts at their robust fix once it is
  /// determined and plausible (see the file comment).
  bool InitializeFromEpoch(const core::Epoch& epoch) override;
  StepOutput Process(const core::Epoch& epoch) override;

  /// The filter's state: 3-D position then velocity.
  [[nodiscard]] const estimation::State& state() const { return state_; }

  /// The stacked Jacobian (rows x 6) and innovations of `tdoas` at `state`'s mean, and the
  /// indices of the rows kept (the baseline bound and the sender-on-anchor case drop rows).
  /// Public for the finite-difference tests of the assembled H.
  struct Stack {
    Eigen::MatrixXd H;
    Eigen::VectorXd innovation_m;
    Eigen::VectorXd variance_m2;  ///< each row's R: the noise plus the motion model's over its time offset
    std::vector<int> kept;
    int out_of_bound = 0;
  };
  [[nodiscard]] Stack Linearize(const estimation::State& state, const std::vector<core::TdoaMeasurement>& tdoas) const;

 private:
  void Start(double t_s, const Vec3& position_m, const Eigen::Matrix3d& position_covariance_m2);
  /// Updates state_ with the differences (each predicted at its own time from the state's).
  TdoaUpdateCounts Update(const std::vector<core::TdoaMeasurement>& tdoas);
  [[nodiscard]] AgentEstimate Estimate() const;
  /// The row has a time and a finite value, two different anchors, and (with baseline_gate) lies
  /// within the anchors' baseline plus 3 tdoa_sigma_m (estimation/gates/tdoa_bound.h).
  [[nodiscard]] bool Usable(const core::TdoaMeasurement& m) const;
  /// A self-initialisation fix worth starting from: no less certain than the anchors' spread,
  /// inside the given floor plan and between its floor and ceiling.
  [[nodiscard]] bool Plausible(const estimation::PositionFix& fix) const;

  TdoaEkfOptions options_;
  World world_;
  estimation::ConstantVelocity motion_;
  estimation::State state_;
  std::deque<core::TdoaMeasurement> init_rows_;  ///< self-initialisation's window
  std::vector<core::TdoaMeasurement> pending_;   ///< rekf: the rows of the window not yet used
};

}  // namespace mirage::methods::tdoa_ekf
