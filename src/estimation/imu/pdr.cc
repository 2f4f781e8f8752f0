// SPDX-License-Identifier: MIT
#include "mirage/estimation/imu/pdr.h"

#include <algorithm>
#include <cmath>

#include "mirage/core/constants.h"

namespace mirage::estimation {
namespace {
constexpr int kHeading = 2;  // index of the heading error in the joint error vector
constexpr int kBias = 3;     // index of the gyro bias error
}  // namespace

const core::OptionsDescriptor<PdrOptions>& PdrOptionsDescriptor() {
  using core::ValueRange;
  using O = PdrOptions;
  static const auto descriptor = [] {
    const ValueRange non_negative = ValueRange::Closed(0.0, core::kHugeOption);
    core::OptionsDescriptor<O> d("estimation::PdrOptions");
    d.Number(&O::step_peak_threshold_mps2,
             {.key = "step_peak_threshold_mps2",
              .unit = "m/s^2",
              .range = ValueRange::Positive(),
              .doc = "A step is a local maximum of the accelerometer norm above this. 11.0, about 1.2 m/s^2 "
                     "above g, below the peaks of walking."});
    d.Number(&O::min_step_interval_s,
             {.key = "min_step_interval_s",
              .unit = "s",
              .range = ValueRange::Positive(),
              .doc = "Minimum time between two steps. 0.3 s: cadence up to 3.3 Hz."});
    d.Number(&O::max_step_interval_s,
             {.key = "max_step_interval_s",
              .unit = "s",
              .range = ValueRange::Positive(),
              .doc = "Longest step period that still counts as walking on; beyond it no step in progress is "
                     "credited. 1.5 s."});
    d.Number(&O::step_length_m, {.key = "step_length_m",
                                 .unit = "m",
                                 .range = ValueRange::Positive(),
                                 .doc = "Length credited per step. 0.7 m, an adult's walking step."});
    d.Number(&O::step_length_sigma_m,
             {.key = "step_length_sigma_m",
              .unit = "m",
              .range = non_negative,
              .doc = "Standard deviation of one step's length. 0.05 m: step-to-step variability plus "
                     "mismatch of the fixed length."});
    d.Number(&O::gyro_noise_density_radps_per_sqrt_hz,
             {.key = "gyro_noise_density_radps_per_sqrt_hz",
              .unit = "rad/s/sqrt(Hz)",
              .range = non_negative,
              .doc = "Gyro white-noise density, i.e. the heading random walk in rad/sqrt(s). 2.6e-4 (0.015 "
                     "deg/s/sqrt(Hz)), a smartphone gyroscope."});
    d.Number(&O::gyro_bias_sigma_radps,
             {.key = "gyro_bias_sigma_radps",
              .unit = "rad/s",
              .range = non_negative,
              .doc = "Standard deviation of the unestimated gyro bias. 8.7e-3 (0.5 deg/s), an uncompensated "
                     "phone gyroscope."});
    d.Number(&O::gyro_bias_random_walk_radps_per_sqrt_s,
             {.key = "gyro_bias_random_walk_radps_per_sqrt_s",
              .unit = "rad/s/sqrt(s)",
              .range = non_negative,
              .doc = "Random walk of the gyro bias. 5e-5, consumer MEMS in-run drift."});
    d.Check("min_step_interval_s < max_step_interval_s", [](const O& o) {
      std::vector<std::string> problems;
      if (o.min_step_interval_s > 0.0 && o.max_step_interval_s <= o.min_step_interval_s) {
        problems.push_back("max_step_interval_s: must exceed min_step_interval_s");
      }
      return problems;
    });
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const PdrOptions& options) { return PdrOptionsDescriptor().Validate(options); }

PdrIntegrator::PdrIntegrator(const PdrOptions& options) : options_(options) { Reset(0.0, 0.0); }

void PdrIntegrator::Reset(double t_s, double heading_rad, double heading_sigma_rad) {
  t_s_ = t_s;
  heading_rad_ = heading_rad;
  covariance_.setZero();
  covariance_(kHeading, kHeading) = heading_sigma_rad * heading_sigma_rad;
  covariance_(kBias, kBias) = options_.gyro_bias_sigma_radps * options_.gyro_bias_sigma_radps;
  delta_m_.setZero();
  t_from_s_ = t_s;
  steps_ = 0;
  total_steps_ = 0;
  norms_seen_ = 0;
  norm_prev2_ = norm_prev_ = 0.0;
  t_last_step_s_.reset();
  step_period_s_.reset();
  credited_fraction_ = 0.0;
}

void PdrIntegrator::PropagateHeading(double dt_s) {
  if (dt_s <= 0.0) return;
  // e_h' = e_h + e_b dt + w_h, e_b' = e_b + w_b: the exact discretisation of de_h/dt = e_b + n_g,
  // de_b/dt = n_b with white n_g (density q) and n_b (density s^2).
  Eigen::Matrix4d F = Eigen::Matrix4d::Identity();
  F(kHeading, kBias) = dt_s;
  covariance_ = F * covariance_ * F.transpose();
  const double q = options_.gyro_noise_density_radps_per_sqrt_hz * options_.gyro_noise_density_radps_per_sqrt_hz;
  const double s2 = options_.gyro_bias_random_walk_radps_per_sqrt_s * options_.gyro_bias_random_walk_radps_per_sqrt_s;
  covariance_(kHeading, kHeading) += q * dt_s + s2 * dt_s * dt_s * dt_s / 3.0;
  covariance_(kHeading, kBias) += s2 * dt_s * dt_s / 2.0;
  covariance_(kBias, kHeading) += s2 * dt_s * dt_s / 2.0;
  covariance_(kBias, kBias) += s2 * dt_s;
}

void PdrIntegrator::AddDistance(double length_m, double sigma_m) {
  if (length_m <= 0.0) return;
  const Vec2 u(std::cos(heading_rad_), std::sin(heading_rad_));
  const Vec2 u_perp(-u.y(), u.x());
  // delta' = delta + L u(h): J_delta_heading = L u_perp, J_delta_length = u.
  Eigen::Matrix4d F = Eigen::Matrix4d::Identity();
  F.block<2, 1>(0, kHeading) = length_m * u_perp;
  covariance_ = F * covariance_ * F.transpose();
  covariance_.topLeftCorner<2, 2>() += sigma_m * sigma_m * u * u.transpose();
  delta_m_ += length_m * u;
}

void PdrIntegrator::OnStep(double t_step_s) {
  const bool walking_on = t_last_step_s_ && t_step_s - *t_last_step_s_ <= options_.max_step_interval_s;
  if (walking_on) {
    step_period_s_ = t_step_s - *t_last_step_s_;
  } else {
    step_period_s_.reset();
  }
  // A step after a stop is a new one: what was credited of the last step in progress is lost.
  const double fraction = walking_on ? 1.0 - credited_fraction_ : 1.0;
  AddDistance(fraction * options_.step_length_m, fraction * options_.step_length_sigma_m);
  credited_fraction_ = 0.0;
  t_last_step_s_ = t_step_s;
  ++steps_;
  ++total_steps_;
}

void PdrIntegrator::Add(const core::ImuSample& sample) {
  if (sample.t_s < t_s_ || (norms_seen_ > 0 && sample.t_s <= t_s_)) return;
  const double norm_mps2 = sample.accel_mps2.norm();
  // The previous sample (at t_s_) is a step if it is a peak above the threshold.
  if (norms_seen_ >= 2 && norm_prev_ > options_.step_peak_threshold_mps2 && norm_prev_ > norm_prev2_ &&
      norm_prev_ >= norm_mps2 && (!t_last_step_s_ || t_s_ - *t_last_step_s_ >= options_.min_step_interval_s)) {
    OnStep(t_s_);
  }
  // The level phone's yaw rate is gyro z; the sample's rate holds over the interval ending at it.
  const double dt_s = sample.t_s - t_s_;
  heading_rad_ += sample.gyro_radps.z() * dt_s;
  PropagateHeading(dt_s);
  t_s_ = sample.t_s;
  norm_prev2_ = norm_prev_;
  norm_prev_ = norm_mps2;
  ++norms_seen_;
}

PdrIncrement PdrIntegrator::TakeIncrement() {
  if (t_last_step_s_ && step_period_s_ && t_s_ - *t_last_step_s_ <= options_.max_step_interval_s) {
    const double fraction = std::clamp((t_s_ - *t_last_step_s_) / *step_period_s_, 0.0, 1.0);
    const double extra = std::max(0.0, fraction - credited_fraction_);
    AddDistance(extra * options_.step_length_m, extra * options_.step_length_sigma_m);
    credited_fraction_ = std::max(credited_fraction_, fraction);
  }
  PdrIncrement out;
  out.delta_m = delta_m_;
  out.covariance_m2 = covariance_.topLeftCorner<2, 2>();
  out.t_from_s = t_from_s_;
  out.t_to_s = t_s_;
  out.steps = steps_;
  // The new increment starts exactly at 0: no error, no correlation with heading or bias.
  delta_m_.setZero();
  covariance_.topRows<2>().setZero();
  covariance_.leftCols<2>().setZero();
  t_from_s_ = t_s_;
  steps_ = 0;
  return out;
}

void PdrIntegrator::SetHeading(double heading_rad, double sigma_rad) {
  heading_rad_ = heading_rad;
  covariance_.row(kHeading).setZero();
  covariance_.col(kHeading).setZero();
  covariance_(kHeading, kHeading) = sigma_rad * sigma_rad;
}

double PdrIntegrator::heading_sigma_rad() const { return std::sqrt(covariance_(kHeading, kHeading)); }

const core::OptionsDescriptor<ConstantHeadingErrorOptions>& ConstantHeadingErrorOptionsDescriptor() {
  using core::ValueRange;
  using O = ConstantHeadingErrorOptions;
  static const auto descriptor = [] {
    core::OptionsDescriptor<O> d("estimation::ConstantHeadingErrorOptions");
    d.Number(&O::constant_heading_error_rad,
             {.key = "constant_heading_error_rad",
              .unit = "rad",
              .range = ValueRange::Closed(-core::kPi, core::kPi),
              .doc = "Rotation of every increment, counter-clockwise (Bordoy Sec. 5.3 synthetic IMU; no value "
                     "in the thesis). 0."});
    d.Number(&O::sigma_per_distance,
             {.key = "sigma_per_distance",
              .range = ValueRange::Closed(0.0, core::kHugeOption),
              .doc = "Reported standard deviation per metre travelled. 0.05, a 3-degree heading error's drift."});
    d.Number(&O::sigma_floor_m, {.key = "sigma_floor_m",
                                 .unit = "m",
                                 .range = ValueRange::Positive(),
                                 .doc = "Reported standard deviation floor. 0.02 m."});
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const ConstantHeadingErrorOptions& options) {
  return ConstantHeadingErrorOptionsDescriptor().Validate(options);
}

PdrIncrement ConstantHeadingErrorIncrement(const ConstantHeadingErrorOptions& options, const Vec2& p_from_m,
                                           const Vec2& p_to_m, double t_from_s, double t_to_s) {
  const Vec2 truth_m = p_to_m - p_from_m;
  const double c = std::cos(options.constant_heading_error_rad), s = std::sin(options.constant_heading_error_rad);
  PdrIncrement out;
  out.delta_m = Vec2(c * truth_m.x() - s * truth_m.y(), s * truth_m.x() + c * truth_m.y());
  const double sigma_m = options.sigma_floor_m + options.sigma_per_distance * truth_m.norm();
  out.covariance_m2 = sigma_m * sigma_m * Eigen::Matrix2d::Identity();
  out.t_from_s = t_from_s;
  out.t_to_s = t_to_s;
  out.steps = 0;
  return out;
}

}  // namespace mirage::estimation
