// SPDX-License-Identifier: MIT
// Pedestrian dead reckoning for the loose IMU coupling of Bordoy 2020 (PhD thesis, Univ.
// Freiburg), Sec. 5.2, Eq. (5.35)-(5.39): the REKF stacks an "IMU position" row block (O_t of
// Eq. 5.39); we provide the position increment since the last acoustic update and its
// covariance, so the caller forms S_IMU = S_prev + delta. The thesis integrated ZUPT positions
// (Ojeda & Borenstein) computed by a co-author and simulated its IMU as a constant heading error
// only; both are here: PdrIntegrator (steps from IMU samples) and ConstantHeadingErrorIncrement
// (truth rotated by a fixed angle, the thesis's Sec. 5.3 synthetic IMU). Choices:
//  - steps are peaks of the accelerometer norm above step_peak_threshold_mps2, at least
//    min_step_interval_s apart; each credits a FIXED step length (Weinberg's k (amax-amin)^(1/4)
//    needs a per-person k and the simulator's bounce does not depend on the step length);
//  - the phone is level: the heading integrates gyro z alone, from the heading the caller sets
//    (from the acoustic track's velocity); no bias is estimated;
//  - an increment taken between steps credits the step in progress by time, (t - last step) /
//    last step period (at most one step, only while the walker keeps stepping), and the next
//    step adds the rest, because acoustic updates (0.1-0.3 s apart) are shorter than a step;
//  - covariance: the errors of (delta_x, delta_y, heading, gyro bias) are propagated jointly
//    (linearised), so the heading error shared by all steps of an increment, and its growth with
//    the gyro's white noise, bias and bias walk, correlate the steps properly. A step of length L
//    at heading h adds L u(h), u = (cos h, sin h): its errors are u e_L + L u_perp e_h with
//    u_perp = (-sin h, cos h), e_L ~ N(0, sigma_L^2) per step. Between samples (dt) the heading
//    error gains e_b dt plus white noise (q dt + s^2 dt^3 / 3, q = gyro noise density^2,
//    s = bias walk), the bias error the walk s^2 dt (the exact discretisation). An increment
//    returns the delta block and restarts it at 0; heading and bias errors carry on, so
//    consecutive increments are correlated, which a filter that uses them independently ignores.
//  - Starting and stopping credit up to a quarter step too much (a step is credited at its
//    heel-strike peak); this is not in the covariance.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mirage/core/options_descriptor.h"
#include "mirage/core/records.h"
#include "mirage/core/types.h"

namespace mirage::estimation {

/// Parameters of the step-and-heading dead reckoning. The gyro defaults match
/// channel::ImuOptions (a smartphone-grade MEMS gyroscope, uncompensated).
struct PdrOptions {
  /// A step is a local maximum of the accelerometer norm above this (m/s^2), > 0. 11.0, about
  /// 1.2 m/s^2 above g: below the 2-4 m/s^2 peaks of walking, far above the sensor noise.
  double step_peak_threshold_mps2 = 11.0;
  /// Minimum time between two steps (s), > 0. 0.3 s: cadence up to 3.3 Hz (a run), while the
  /// norm's samples above the threshold within one step (about 0.2 s) count once.
  double min_step_interval_s = 0.3;
  /// Longest step period (s) that still counts as walking on, > min_step_interval_s. 1.5 s;
  /// beyond it the walker is taken to have stopped and no step in progress is credited.
  double max_step_interval_s = 1.5;
  /// Length credited per step (m), > 0. 0.7 m, an adult's walking step.
  double step_length_m = 0.7;
  /// Standard deviation of one step's length (m), >= 0. 0.05 m (7 %): step-to-step variability
  /// plus some mismatch of the fixed length to the walker.
  double step_length_sigma_m = 0.05;
  /// Gyro white-noise density = heading random walk (rad/s/sqrt(Hz) = rad/sqrt(s)), >= 0.
  /// 2.6e-4 (0.015 deg/s/sqrt(Hz)).
  double gyro_noise_density_radps_per_sqrt_hz = 2.6e-4;
  /// Standard deviation of the gyro's (unestimated) bias (rad/s), >= 0. 8.7e-3 (0.5 deg/s).
  double gyro_bias_sigma_radps = 8.7e-3;
  /// Random walk of the gyro bias (rad/s/sqrt(s)), >= 0. 5e-5.
  double gyro_bias_random_walk_radps_per_sqrt_s = 5e-5;
};

/// The options' descriptor (keys, units, ranges, docs; core/options_descriptor.h).
const core::OptionsDescriptor<PdrOptions>& PdrOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const PdrOptions& options);

/// The dead-reckoned horizontal displacement over [t_from_s, t_to_s] (world frame).
struct PdrIncrement {
  /// Displacement (m).
  Vec2 delta_m = Vec2::Zero();
  /// Covariance of its error (m^2).
  Eigen::Matrix2d covariance_m2 = Eigen::Matrix2d::Zero();
  /// Start of the interval (s).
  double t_from_s = 0.0;
  /// End of the interval (s).
  double t_to_s = 0.0;
  /// Steps detected in the interval (0 for a synthetic increment).
  int steps = 0;
};

/// Step-and-heading dead reckoning from IMU samples with a joint error covariance (see the file
/// comment). Call Reset first; feed samples in time order; take an increment at each acoustic
/// update.
class PdrIntegrator {
 public:
  /// The increment type (Bordoy's IMU position row block, relative to the last update).
  using Increment = PdrIncrement;

  /// @param options validated options
  explicit PdrIntegrator(const PdrOptions& options);

  /// Restarts at t_s (s) with the given heading (rad, world frame, counter-clockwise from x) and
  /// its standard deviation (rad, >= 0): no steps, an empty increment, the gyro bias uncertainty
  /// at its prior gyro_bias_sigma_radps.
  void Reset(double t_s, double heading_rad, double heading_sigma_rad = 0.0);
  /// Integrates one sample: step detection on the accelerometer norm, heading from gyro z over
  /// the time since the previous sample. Samples not later than the previous one are ignored.
  void Add(const core::ImuSample& sample);
  /// The increment since the previous TakeIncrement (or Reset) up to the last sample's time,
  /// crediting the step in progress by time; restarts the accumulation.
  Increment TakeIncrement();
  /// Replaces the heading (rad) and its standard deviation (rad, >= 0), e.g. from the acoustic
  /// track's velocity; its error becomes independent of the gyro bias and of the increment.
  void SetHeading(double heading_rad, double sigma_rad);

  /// Current heading (rad).
  [[nodiscard]] double heading_rad() const { return heading_rad_; }
  /// Standard deviation of the current heading (rad).
  [[nodiscard]] double heading_sigma_rad() const;
  /// Steps detected since Reset.
  [[nodiscard]] int total_steps() const { return total_steps_; }
  /// Time of the last sample (or of Reset) (s).
  [[nodiscard]] double t_s() const { return t_s_; }

 private:
  // Grows the heading and bias error covariance over dt_s.
  void PropagateHeading(double dt_s);
  // Credits `length_m` along the current heading with length standard deviation `sigma_m`.
  void AddDistance(double length_m, double sigma_m);
  void OnStep(double t_step_s);

  PdrOptions options_;
  double t_s_ = 0.0;
  double heading_rad_ = 0.0;
  // Errors of (delta_x, delta_y, heading, gyro bias).
  Eigen::Matrix4d covariance_ = Eigen::Matrix4d::Zero();
  Vec2 delta_m_ = Vec2::Zero();
  double t_from_s_ = 0.0;
  int steps_ = 0;
  int total_steps_ = 0;
  // Step detector: the last two norms.
  int norms_seen_ = 0;
  double norm_prev2_ = 0.0;
  double norm_prev_ = 0.0;
  std::optional<double> t_last_step_s_;
  std::optional<double> step_period_s_;
  // Fraction of the step in progress already credited to earlier increments.
  double credited_fraction_ = 0.0;
};

/// Parameters of the thesis's synthetic IMU (Sec. 5.3): the true displacement rotated by a
/// constant angle, with a covariance the filter is told.
struct ConstantHeadingErrorOptions {
  /// Rotation of every increment (rad, counter-clockwise), in [-pi, pi]. 0; the thesis does not
  /// state its value (digest Sec. 6.2).
  double constant_heading_error_rad = 0.0;
  /// Reported standard deviation per metre travelled (m/m), >= 0. 0.05: a 3-degree heading
  /// error's cross-track drift.
  double sigma_per_distance = 0.05;
  /// Reported standard deviation floor (m), > 0. 0.02 m, so that a standing walker's increment
  /// keeps a proper covariance.
  double sigma_floor_m = 0.02;
};

/// The options' descriptor (keys, units, ranges, docs; core/options_descriptor.h).
const core::OptionsDescriptor<ConstantHeadingErrorOptions>& ConstantHeadingErrorOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const ConstantHeadingErrorOptions& options);

/// The increment from p_from_m to p_to_m (m, true horizontal positions at t_from_s and t_to_s,
/// s) rotated by constant_heading_error_rad, with covariance s^2 I, s = sigma_floor_m +
/// sigma_per_distance |p_to - p_from|, and 0 steps.
PdrIncrement ConstantHeadingErrorIncrement(const ConstantHeadingErrorOptions& options, const Vec2& p_from_m,
                                           const Vec2& p_to_m, double t_from_s, double t_to_s);

}  // namespace mirage::estimation
