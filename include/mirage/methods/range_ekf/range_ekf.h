// SPDX-License-Identifier: MIT
// range_ekf: a 3-D range EKF, the plain baseline of range-based positioning (UWB two-way
// ranging, a real-time location system's tags). Position and velocity in 3-D under a
// constant-velocity model, or in the plane at the world's known agent height; one range per
// anchor and epoch, the nearest to the prediction in normalised distance among the anchor's
// ranges, inside a chi-square gate on the innovation variance. Event-driven: the filter
// propagates to each record's time before its update. It uses no floor plan and no multipath.
// When the gate rejects a range, the epoch's least-squares fix decides between a bad range and a
// lost track: if the fix's residuals pass the same gate, it explains more anchors than the track
// and the prediction lies outside the fix's confidence region (the gate's tail probability in 2
// or 3 dimensions), it restarts at the fix.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mirage/core/options_descriptor.h"
#include "mirage/estimation/init/robust_position_fix.h"
#include "mirage/estimation/measurement_row.h"
#include "mirage/estimation/motion/constant_velocity.h"
#include "mirage/estimation/state.h"
#include "mirage/methods/estimator.h"
#include "mirage/methods/world.h"

namespace mirage::methods::range_ekf {

/// Options of the range EKF.
struct RangeEkfOptions {
  /// "3d": position and velocity in 3-D (anchors that are not coplanar, or coplanar ones with
  /// the agent below them); "planar": x, y at the world's known agent height (a tag worn at a
  /// fixed height), which makes the height error zero and halves the unknowns per axis.
  std::string mode = "3d";
  /// Range standard deviation (m), > 0. Derived from the scenario's range noise when it has one.
  double range_sigma_m = 0.1;
  /// Chi-square gate on one range's innovation (1 degree of freedom), >= 0; 0 = off. 9 = 3 sigma
  /// of the innovation variance h P h^T + R, 99.7 % of consistent ranges.
  double gate_chi2 = 9.0;
  /// Position standard deviation of a given start point (m), > 0. 0.5 m: a start known to the
  /// room's scale. A self-initialised start uses its fix's covariance instead.
  double initial_position_sigma_m = 0.5;
  /// Velocity standard deviation at the start, at rest (m/s), > 0. Derived from the walker's
  /// speed when the scenario states it.
  double initial_velocity_sigma_mps = 1.0;
  /// The agent's motion.
  estimation::ConstantVelocityOptions motion;
};

/// The options' descriptor (keys, units, ranges, docs; core/options_descriptor.h).
const core::OptionsDescriptor<RangeEkfOptions>& RangeEkfOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const RangeEkfOptions& options);

class RangeEkf final : public Estimator {
 public:
  RangeEkf(const RangeEkfOptions& options, const World& world);

  void Initialize(const Prior& prior) override;
  /// Starts from a least-squares fix of the epoch's ranges (the earliest range of each anchor):
  /// 4 anchors in 3-D (3 when coplanar, the mirror above them rejected), 3 in the plane.
  bool InitializeFromEpoch(const core::Epoch& epoch) override;
  StepOutput Process(const core::Epoch& epoch) override;
  /// The filter's covariance recursion along the true trajectory with every anchor's range at
  /// range_sigma_m (the posterior Cramer-Rao bound of its model, Tichavsky et al. 1998).
  [[nodiscard]] std::vector<std::vector<double>> PosteriorBound(const BoundInput& truth) const override;

  /// The filter's state: position then velocity of agent 0, in 3-D or in the plane.
  [[nodiscard]] const estimation::State& state() const { return state_; }
  /// The linearised range to anchor anchor_index at `state` (empty when the agent sits on it).
  [[nodiscard]] std::optional<estimation::MeasurementRow> AnchorRow(const estimation::State& state,
                                                                    int anchor_index) const;

 private:
  [[nodiscard]] bool planar() const { return options_.mode == "planar"; }
  [[nodiscard]] double AgentHeight() const;
  void Start(double t_s, const Vec3& position_m, const Eigen::Matrix3d& position_covariance_m2);
  /// The fix of the sets' ranges whose every residual passes the gate (estimation/init/
  /// robust_position_fix.h): wrong ranges and anchors with only wrong ranges are left out.
  [[nodiscard]] std::optional<estimation::RobustPositionFix> Fix(std::span<const core::RangeSet> sets) const;
  /// Restarts at the fix of the sets when their ranges agree with each other (RMS residual inside
  /// the gate), the fix explains more anchors (a range inside the gate) than the track's
  /// `explained_by_track`, and the prediction lies outside the fix's confidence region: the
  /// track is lost.
  bool Reacquire(std::span<const core::RangeSet> sets, int explained_by_track);
  [[nodiscard]] AgentEstimate Estimate() const;

  RangeEkfOptions options_;
  World world_;
  estimation::ConstantVelocity motion_;
  estimation::State state_;
};

}  // namespace mirage::methods::range_ekf
