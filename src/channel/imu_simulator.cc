// SPDX-License-Identifier: MIT
#include "mirage/channel/imu_simulator.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "mirage/core/constants.h"

namespace mirage::channel {
namespace {

// The path interpolated linearly at times t_out (t_in increasing, t_out increasing within it).
std::vector<Vec3> Interpolate(std::span<const double> t_in, std::span<const Vec3> p_in, const std::vector<double>& t_out) {
  std::vector<Vec3> out;
  out.reserve(t_out.size());
  std::size_t i = 0;
  for (const double t : t_out) {
    while (i + 2 < t_in.size() && t_in[i + 1] <= t) ++i;
    const double w = std::clamp((t - t_in[i]) / (t_in[i + 1] - t_in[i]), 0.0, 1.0);
    out.push_back((1.0 - w) * p_in[i] + w * p_in[i + 1]);
  }
  return out;
}

// Central differences of x at spacing dt_s (one-sided at the ends).
std::vector<Vec3> Differentiate(const std::vector<Vec3>& x, double dt_s) {
  const std::size_t n = x.size();
  std::vector<Vec3> d(n, Vec3::Zero());
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t lo = k == 0 ? 0 : k - 1;
    const std::size_t hi = k + 1 == n ? k : k + 1;
    d[k] = (x[hi] - x[lo]) / (static_cast<double>(hi - lo) * dt_s);
  }
  return d;
}

// Centred moving average with half-width `half` samples, shrunk symmetrically near the ends so
// that it never lags.
std::vector<Vec3> Smooth(const std::vector<Vec3>& x, std::size_t half) {
  const std::size_t n = x.size();
  if (half == 0) return x;
  std::vector<Vec3> prefix(n + 1, Vec3::Zero());
  for (std::size_t k = 0; k < n; ++k) prefix[k + 1] = prefix[k] + x[k];
  std::vector<Vec3> out(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t m = std::min({half, k, n - 1 - k});
    out[k] = (prefix[k + m + 1] - prefix[k - m]) / static_cast<double>(2 * m + 1);
  }
  return out;
}

double WrapToPi(double angle_rad) { return std::remainder(angle_rad, 2.0 * core::kPi); }

}  // namespace

const core::OptionsDescriptor<ImuOptions>& ImuOptionsDescriptor() {
  using core::ValueRange;
  using O = ImuOptions;
  static const auto descriptor = [] {
    const ValueRange non_negative = ValueRange::Closed(0.0, core::kHugeOption);
    core::OptionsDescriptor<O> d("channel::ImuOptions");
    d.Number(&O::rate_hz, {.key = "rate_hz",
                           .unit = "Hz",
                           .range = ValueRange::Positive(),
                           .doc = "Output rate. 100 Hz, a phone's usual sensor rate."});
    d.Number(&O::accel_noise_density_mps2_per_sqrt_hz,
             {.key = "accel_noise_density_mps2_per_sqrt_hz",
              .unit = "m/s^2/sqrt(Hz)",
              .range = non_negative,
              .doc = "Accelerometer white-noise density; per-sample sigma = density * sqrt(rate_hz). 2e-3 "
                     "(about 200 ug/sqrt(Hz)), a smartphone MEMS accelerometer."});
    d.Number(&O::gyro_noise_density_radps_per_sqrt_hz,
             {.key = "gyro_noise_density_radps_per_sqrt_hz",
              .unit = "rad/s/sqrt(Hz)",
              .range = non_negative,
              .doc = "Gyroscope white-noise density (= heading random walk in rad/sqrt(s)). 2.6e-4 "
                     "(0.015 deg/s/sqrt(Hz)), a smartphone MEMS gyroscope."});
    d.Number(&O::accel_bias_sigma_mps2,
             {.key = "accel_bias_sigma_mps2",
              .unit = "m/s^2",
              .range = non_negative,
              .doc = "Standard deviation of the accelerometer's turn-on bias per axis, constant per run. 0.1 "
                     "(about 10 mg), a factory-trimmed phone accelerometer."});
    d.Number(&O::gyro_bias_sigma_radps,
             {.key = "gyro_bias_sigma_radps",
              .unit = "rad/s",
              .range = non_negative,
              .doc = "Standard deviation of the gyroscope's turn-on bias per axis. 8.7e-3 (0.5 deg/s), an "
                     "uncompensated phone gyroscope."});
    d.Number(&O::gyro_bias_random_walk_radps_per_sqrt_s,
             {.key = "gyro_bias_random_walk_radps_per_sqrt_s",
              .unit = "rad/s/sqrt(s)",
              .range = non_negative,
              .doc = "Random walk of the gyro bias. 5e-5, the in-run drift of consumer MEMS."});
    d.Number(&O::step_length_m, {.key = "step_length_m",
                                 .unit = "m",
                                 .range = ValueRange::Positive(),
                                 .doc = "Mean step length; the cadence is speed / step_length_m. 0.7 m, an "
                                        "adult's walking step."});
    d.Number(&O::step_length_sigma_m,
             {.key = "step_length_sigma_m",
              .unit = "m",
              .range = non_negative,
              .doc = "Standard deviation of each step's length. 0.03 m, the step-to-step variability of "
                     "steady walking."});
    d.Number(&O::step_accel_amplitude_mps2,
             {.key = "step_accel_amplitude_mps2",
              .unit = "m/s^2",
              .range = non_negative,
              .doc = "Peak vertical acceleration of a step (one peak per step, at 3/4 of it). 2.5 m/s^2, "
                     "a hand-held phone in normal walking. 0: no bounce."});
    d.Number(&O::smoothing_window_s,
             {.key = "smoothing_window_s",
              .unit = "s",
              .range = non_negative,
              .doc = "Width of the centred moving average of the finite-difference velocity. 0.2 s: "
                     "longer than a 0.1 s ground-truth sampling, shorter than a turn. 0: none."});
    d.Check("step_length_sigma_m < step_length_m / 3", [](const O& o) {
      std::vector<std::string> problems;
      if (o.step_length_m > 0.0 && o.step_length_sigma_m >= o.step_length_m / 3.0) {
        problems.push_back("step_length_sigma_m: must be below step_length_m / 3 (steps of positive length)");
      }
      return problems;
    });
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const ImuOptions& options) { return ImuOptionsDescriptor().Validate(options); }

std::vector<core::ImuSample> SimulateImu(const ImuOptions& options, std::span<const double> t_s,
                                         std::span<const Vec3> positions_m, core::Rng& rng) {
  if (t_s.size() < 2 || t_s.size() != positions_m.size()) return {};
  for (std::size_t i = 1; i < t_s.size(); ++i) {
    if (!(t_s[i] > t_s[i - 1])) return {};
  }
  const double dt_s = 1.0 / options.rate_hz;
  std::vector<double> t_imu;
  for (std::size_t k = 0;; ++k) {
    const double t = t_s.front() + static_cast<double>(k) * dt_s;
    if (t > t_s.back() + 1e-9) break;
    t_imu.push_back(t);
  }
  const std::size_t n = t_imu.size();
  const std::vector<Vec3> p = Interpolate(t_s, positions_m, t_imu);
  const auto half = static_cast<std::size_t>(std::lround(0.5 * options.smoothing_window_s * options.rate_hz));
  const std::vector<Vec3> v = Smooth(Differentiate(p, dt_s), half);
  const std::vector<Vec3> a = Differentiate(v, dt_s);

  // Yaw of the direction of motion, held while standing, unwrapped so that it is continuous.
  std::vector<double> yaw_rad(n, 0.0);
  std::size_t first_moving = n;
  for (std::size_t k = 0; k < n; ++k) {
    if (v[k].head<2>().norm() >= kMinWalkingSpeed_mps) {
      first_moving = k;
      break;
    }
  }
  double held_rad = first_moving < n ? std::atan2(v[first_moving].y(), v[first_moving].x()) : 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    if (v[k].head<2>().norm() >= kMinWalkingSpeed_mps) {
      held_rad += WrapToPi(std::atan2(v[k].y(), v[k].x()) - held_rad);
    }
    yaw_rad[k] = held_rad;
  }

  // One draw of `rng` seeds this run, so successive calls differ; one stream per purpose inside.
  const core::Rng run_rng(rng.NextU64());
  core::Rng step_rng = run_rng.Substream("imu_steps");
  core::Rng bias_rng = run_rng.Substream("imu_bias");
  core::Rng accel_rng = run_rng.Substream("imu_accel_noise");
  core::Rng gyro_rng = run_rng.Substream("imu_gyro_noise");

  const auto draw_step = [&] {
    return std::max(options.step_length_m + step_rng.Normal(0.0, options.step_length_sigma_m),
                    0.1 * options.step_length_m);
  };
  Vec3 accel_bias_mps2, gyro_bias_radps;
  for (int i = 0; i < 3; ++i) accel_bias_mps2[i] = bias_rng.Normal(0.0, options.accel_bias_sigma_mps2);
  for (int i = 0; i < 3; ++i) gyro_bias_radps[i] = bias_rng.Normal(0.0, options.gyro_bias_sigma_radps);
  const double accel_sigma = options.accel_noise_density_mps2_per_sqrt_hz * std::sqrt(options.rate_hz);
  const double gyro_sigma = options.gyro_noise_density_radps_per_sqrt_hz * std::sqrt(options.rate_hz);
  const double bias_step_sigma = options.gyro_bias_random_walk_radps_per_sqrt_s * std::sqrt(dt_s);

  double walked_m = 0.0;      // horizontal distance since the start of the current step
  double step_m = draw_step();
  std::vector<core::ImuSample> out;
  out.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0) walked_m += (p[k] - p[k - 1]).head<2>().norm();
    while (walked_m >= step_m) {
      walked_m -= step_m;
      step_m = draw_step();
    }
    const double speed_mps = v[k].head<2>().norm();
    const double fade = std::clamp((speed_mps - kMinWalkingSpeed_mps) / 0.2, 0.0, 1.0);
    const double bounce_mps2 = -options.step_accel_amplitude_mps2 * fade * std::sin(2.0 * core::kPi * walked_m / step_m);

    const Vec3 f_world = a[k] + Vec3(0.0, 0.0, bounce_mps2 + kStandardGravity_mps2);
    const double c = std::cos(yaw_rad[k]), s = std::sin(yaw_rad[k]);
    // R_body_to_world = Rz(yaw); f_body = Rz(yaw)^T f_world.
    const Vec3 f_body(c * f_world.x() + s * f_world.y(), -s * f_world.x() + c * f_world.y(), f_world.z());
    const double yaw_rate_radps = k == 0 ? 0.0 : (yaw_rad[k] - yaw_rad[k - 1]) / dt_s;

    core::ImuSample sample;
    sample.t_s = t_imu[k];
    sample.sensor_id = "imu";
    sample.sensor_index = 0;
    for (int i = 0; i < 3; ++i) {
      sample.accel_mps2[i] = f_body[i] + accel_bias_mps2[i] + accel_rng.Normal(0.0, accel_sigma);
      sample.gyro_radps[i] = (i == 2 ? yaw_rate_radps : 0.0) + gyro_bias_radps[i] + gyro_rng.Normal(0.0, gyro_sigma);
    }
    out.push_back(std::move(sample));
    for (int i = 0; i < 3; ++i) gyro_bias_radps[i] += bias_rng.Normal(0.0, bias_step_sigma);
  }
  return out;
}

std::vector<core::ImuSample> SimulateImu(const ImuOptions& options, const std::function<Vec3(double)>& position_m,
                                         double t_begin_s, double t_end_s, core::Rng& rng) {
  std::vector<double> t_s;
  std::vector<Vec3> p_m;
  const double dt_s = 1.0 / options.rate_hz;
  for (std::size_t k = 0;; ++k) {
    const double t = t_begin_s + static_cast<double>(k) * dt_s;
    if (t > t_end_s + 1e-9) break;
    t_s.push_back(t);
    p_m.push_back(position_m(t));
  }
  return SimulateImu(options, t_s, p_m, rng);
}

}  // namespace mirage::channel
