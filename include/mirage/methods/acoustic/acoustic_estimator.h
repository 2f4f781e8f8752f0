// SPDX-License-Identifier: MIT
// The acoustic sender tracker of Bordoy 2020 ch. 5 on the framework: a smartphone emits chirps
// every I seconds of its own clock; ceiling microphones with one time base stamp every arrival
// they detect (direct path, echoes, false alarms). Each emission is one epoch.
//
// Filters ("rekf", "ekf"). The state is [S, V, b, iota]: the sender's position S and velocity V
// (planar: x, y at the known height; 3d: x, y, z), the emission time as a distance
// b = c (t_emit - t_ref) against a reference time t_ref the filter advances by I per interval,
// and iota = c I epsilon, the distance the emission time gains per interval from the sender's
// clock rate error epsilon. We work on TOA with the emission time in the state (the and
// the digest's recommendation), so that R stays diagonal and the Hampel weights can isolate one
// bad microphone; the TDOA rows of Eq. 5.36 would mix them through R_TD. Prediction: the
// white-acceleration model of Eq. 5.31-5.34 over n I, n the elapsed intervals (Eq. 3.39, counted
// from the emission time the stamps imply, so that a missed emission does not shift the count);
// b gains n iota plus the jitter. Measurement (Eq. 5.1 without the bias): per microphone the
// stamp nearest the prediction, z = c (T - t_ref) = |S - M_i| + b; the stamps that break the
// TDOA bound (Eq. 5.5) against most others are left out first. With echoes (below) the update is
// iterated instead, the association redone at each iterate. Update: IRLS with Hampel weights
// over the whitened prior and stamp rows (Eq. 5.25-5.30, estimation/robust/irls_update.h); the
// plain EKF is the same update with every weight 1.
//
// Inertial fusion (options.inertial): the state gains a clone of the last emission's horizontal
// position, S_prev; a dead-reckoning increment delta over the interval is the row
// S_xy - S_prev = delta with the increment's covariance, stacked with the stamps (Eq. 5.35-5.39
// use an IMU position; an increment on a clone needs no common frame origin and drifts only
// within one interval). Its rows are reweighted like the others.
//
// Combinatorial ("combinatorial"): per emission the 8-step LOS identification of Sec. 5.1
// (los_identification.h) on every stamp, no motion model; an emission without a voted fix has
// no fix.
//
// Echoes (options.echo_order > 0, with a floor plan): the filters predict the echoes off the
// plan's walls, floor and ceiling too, and pair each microphone's stamps with its paths
// (path_association.h); an echo is a row of its virtual receiver. The update is an iterated EKF
// with the association redone at each iterate: pass 0 takes each microphone's earliest stamp as
// its direct path at the prediction, passes 1-3 pair all stamps with all paths at the last
// estimate. The passes run twice, after pass 0 and directly from the prediction, and the outcome
// whose estimate explains more stamps within 3 sigma is kept (docs/methods/acoustic.md). A
// track whose position leaves the floor plan by more than 3 sigma has lost the sender and starts
// again from all the stamps over the whole plan (restart_lost_track).
//
// Floor echoes ("ground_echo", mode 3d): per emission the ch. 8 fix of ground_echo_fix.h, the
// line of sight and the floor echo of each microphone, with its HDOP and VDOP.
//
// Snapshot ("nlls"): per emission a Levenberg-Marquardt fix of [S, b] from random starts, with
// each microphone's earliest stamp that passes the TDOA bound, no motion model (the thesis's
// NLLS comparison "with random initialisation using all measurements").
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "mirage/core/rng.h"
#include "mirage/geometry/reflector_3d.h"
#include "mirage/estimation/imu/pdr.h"
#include "mirage/estimation/robust/irls_update.h"
#include "mirage/methods/acoustic/acoustic_options.h"
#include "mirage/methods/acoustic/multipath_fix.h"
#include "mirage/methods/acoustic/path_association.h"
#include "mirage/methods/estimator.h"
#include "mirage/methods/world.h"

namespace mirage::methods::acoustic {

/// One microphone's stamp chosen for an update, as a distance z = c (T - t_ref) (m).
struct ChosenStamp {
  int receiver = 0;
  double z_m = 0.0;
};

/// The stamps of one epoch per receiver, as c (T - t_ref) (m).
using StampsByReceiver = std::vector<std::vector<double>>;

/// The receivers whose chosen stamps survive the TDOA bound (Eq. 5.5): pairs with
/// |z_i - z_j| > |M_i - M_j| + margin_m cannot both be direct paths; the stamp in the most such
/// pairs is removed until none is left (ties: the later stamp, more likely an echo).
std::vector<ChosenStamp> ApplyTdoaBound(std::vector<ChosenStamp> chosen, std::span<const Anchor> receivers,
                                        double margin_m);

/// The acoustic estimator of one run.
class AcousticEstimator final : public Estimator {
 public:
  AcousticEstimator(const AcousticOptions& options, const World& world);

  void Initialize(const Prior& prior) override;
  bool InitializeFromEpoch(const core::Epoch& epoch) override;
  StepOutput Process(const core::Epoch& epoch) override;
  /// The filters' posterior bound: their covariance recursion along the true track, started at
  /// the truth with the method's start sigma, with a row for every path the filter predicts
  /// (direct, echoes to echo_order) at every microphone and emission, each with range_sigma_m, no
  /// misses, no clutter, no wrong pairs. Empty for the snapshot estimators and with the IMU.
  [[nodiscard]] std::vector<std::vector<double>> PosteriorBound(const BoundInput& truth) const override;

  /// The state [S, V, b, iota] and its covariance (for tests).
  [[nodiscard]] const Eigen::VectorXd& mean() const { return x_; }
  [[nodiscard]] const Eigen::MatrixXd& covariance() const { return P_; }

 private:
  [[nodiscard]] bool planar() const { return options_.mode == "planar"; }
  [[nodiscard]] int dim() const { return planar() ? 2 : 3; }
  /// The sender's position in state x (planar: at the known height).
  [[nodiscard]] Vec3 PositionOf(const Eigen::VectorXd& x) const;
  [[nodiscard]] Vec3 Position() const { return PositionOf(x_); }
  /// The TDOA bound's margin (m): tdoa_bound_sigmas sigmas of a stamp difference.
  [[nodiscard]] double TdoaBoundMargin() const;
  /// Each microphone's earliest stamp, then the TDOA bound (Eq. 5.5) when it is on.
  [[nodiscard]] std::vector<ChosenStamp> EarliestStamps(const StampsByReceiver& stamps) const;
  [[nodiscard]] StampsByReceiver Stamps(const core::Epoch& epoch, double t_ref_s) const;
  /// The emission time (s) the epoch's earliest stamps imply at position p: their median of
  /// T_first - |p - M_i| / c; empty without stamps.
  [[nodiscard]] std::optional<double> ImpliedEmission(const core::Epoch& epoch, const Vec3& position_m) const;
  /// Starts the state at position_m with sigma position_sigma_m per axis, or, with fix_covariance
  /// (of [x, y, z, b], multipath_fix.h), with that covariance of the position and b.
  void Start(const Vec3& position_m, double position_sigma_m,
             const std::optional<Eigen::Matrix4d>& fix_covariance = std::nullopt);
  /// A fix of one emission waiting for the next one's to confirm it.
  struct PendingStart {
    double emission_s = 0.0;  ///< its emission time in the stamps' time base (s)
    MultipathFix fix;
  };
  enum class StartOutcome { kStarted, kPending, kNoFix };
  /// The filters' start from the fixes over all stamps inside the region of two successive
  /// emissions that follow each other (Follows); kPending after the first, kNoFix without a fix.
  /// The emissions' stamps are then used.
  StartOutcome StartFromStamps(const core::Epoch& epoch, const MultipathSearchRegion& region);
  /// second's emission an integer number of intervals after first's (within the clock drift and
  /// the offsets' 3 sigma), its position within the velocity prior's 3 sigma reach plus the fixes'.
  [[nodiscard]] bool Follows(const PendingStart& first, const PendingStart& second) const;
  /// Where the start's search looks: the floor plan (or the microphones' footprint), or with
  /// around_prior the prior's 3 sigma box inside it, moved on by the motion model over the
  /// elapsed_s the start has waited (sigma^2 = P_pos + P_vel elapsed_s^2); in height the known
  /// height (planar), else between the floor and the highest a sender is carried
  /// (ground_echo.max_sender_height_m) below the ceiling.
  [[nodiscard]] MultipathSearchRegion SearchRegion(bool around_prior, double elapsed_s = 0.0) const;
  [[nodiscard]] bool filter() const { return options_.estimator == "rekf" || options_.estimator == "ekf"; }
  void Predict(int intervals);
  /// One stamp paired with a predicted path of its microphone.
  struct Row {
    int receiver = 0;
    double z_m = 0.0;
    PredictedPath path;
  };
  /// Association passes after the first (direct paths at the prediction) when echoes are
  /// predicted; a pass whose pairs equal the last one's ends the iteration early.
  static constexpr int kAssociationPasses = 3;
  /// The highest a sender may be (m): the ceiling, or the highest it is carried above the floor
  /// (ground_echo.max_sender_height_m) if lower. The start searches no higher.
  [[nodiscard]] double HighestSender_m() const;
  /// The state's position lies outside the floor plan (or below its floor, above the heights the
  /// start searches) by more than 3 sigma per axis: the track has lost the sender.
  [[nodiscard]] bool Outside(const Eigen::VectorXd& x, const Eigen::MatrixXd& P) const;
  /// The rows of one association pass at the linearisation point x_lin with covariance P_lin.
  [[nodiscard]] std::vector<Row> AssociateRows(const StampsByReceiver& stamps, const Eigen::VectorXd& x_lin,
                                               const Eigen::MatrixXd& P_lin, int echo_order) const;
  /// Each microphone's earliest stamp as its direct path (the shortest path arrives first), at x_lin.
  [[nodiscard]] std::vector<Row> FirstArrivalRows(const StampsByReceiver& stamps, const Eigen::VectorXd& x_lin) const;
  /// The REKF/EKF update of the prediction (x_, P_) with the rows linearised at x_lin; robust
  /// false: every weight 1 (the EKF update) whatever the estimator.
  [[nodiscard]] std::optional<estimation::IrlsResult> UpdateWithRows(const std::vector<Row>& rows,
                                                                     const std::optional<core::PositionIncrement>& increment,
                                                                     const Eigen::VectorXd& x_lin, bool robust = true) const;
  /// What one emission's direct-path rows (linearised at the prediction) and its update say about
  /// the virtual sender (options.virtual_sender_false_alarm). "Most" stamps: more than half, and
  /// at least d + 2 (more than the unknowns, so that their agreement is evidence).
  struct VirtualSenderCheck {
    bool prediction_exact = false;  ///< most stamps within 3 stamp sigmas of the prediction
    bool update_exact = false;      ///< most stamps within 3 stamp sigmas of the update
    /// The update's position breaks the dead reckoning from the last emission's posterior beyond
    /// the chi-square quantile (2 degrees of freedom) at 1 - virtual_sender_false_alarm.
    bool breaks_dead_reckoning = false;
  };
  [[nodiscard]] VirtualSenderCheck CheckVirtualSender(const std::vector<Row>& rows, const core::PositionIncrement& increment,
                                                      const estimation::IrlsResult& update) const;
  /// The virtual-sender test's track state after this emission (confirmed_, verified_s_): true
  /// when the track coasts on the dead reckoning, its stamps left out.
  bool DecideCoast(const std::optional<core::PositionIncrement>& increment, const std::vector<Row>& rows,
                   const estimation::IrlsResult& update, double t_s);
  /// The rows whose stamp lies within 3 stamp sigmas of its path: at the rows' linearisation
  /// point, or (dx given) after the state step dx.
  [[nodiscard]] int CountExplained(const std::vector<Row>& rows, const Eigen::VectorXd* dx = nullptr) const;
  StepOutput Filter(const core::Epoch& epoch);
  StepOutput Snapshot(const core::Epoch& epoch);
  StepOutput Combinatorial(const core::Epoch& epoch);
  StepOutput GroundEcho(const core::Epoch& epoch);
  [[nodiscard]] AgentEstimate Estimate() const;

  /// The inertial rows of this epoch: the increment since the last emission, if any.
  std::optional<core::PositionIncrement> Increment(const core::Epoch& epoch);
  [[nodiscard]] int clone_offset() const { return 2 * dim() + 2; }

  AcousticOptions options_;
  std::optional<estimation::PdrIntegrator> pdr_;  // started once the heading is known
  bool pdr_started_ = false;
  World world_;
  std::vector<geometry::Reflector3> reflectors_;  // walls, floor, ceiling: the echoes' surfaces
  std::vector<Vec3> mics_m_;                      // the microphones' positions, in anchor order
  LosIdentificationOptions los_;                  // the combinatorial method's options, complete
  double c_mps_ = 343.0;
  double height_m_ = 0.0;
  Eigen::VectorXd x_;
  Eigen::MatrixXd P_;
  double t_ref_s_ = 0.0;
  bool started_ = false;         // a position is known
  bool have_emission_ = false;   // b refers to an emission (set at the first epoch with stamps)
  std::optional<Vec3> start_m_;  // a given start, waiting for its first emission
  std::optional<PendingStart> pending_start_;
  std::optional<double> first_search_s_;  // the time of the first start search around the prior
  /// The virtual-sender test's track state (Filter): confirmed, the time the stamps last
  /// verified it (s), coasting through an episode; its chi-square quantile.
  bool confirmed_ = false;
  double verified_s_ = 0.0;
  bool coasting_ = false;
  double virtual_sender_chi2_ = 0.0;
  bool search_whole_plan_ = false;  // the track was lost: the start searches the whole plan
  MultipathFixOptions start_search_;  // the start's search, set once from the options
  std::optional<GroundEchoFixer> ground_echo_;  // estimator "ground_echo"
  core::Rng rng_;                // the NLLS's random starts (fixed seed: results are reproducible)
  AgentEstimate last_;
};

}  // namespace mirage::methods::acoustic
