// SPDX-License-Identifier: MIT
// A smartphone IMU carried by a walker, simulated from the true path: the accelerometer's
// specific force and the gyroscope's rate with white noise, a turn-on bias and a gyro bias random
// walk, plus the vertical bounce of the steps that a step detector counts. It feeds the loose
// IMU coupling of Bordoy 2020 (PhD thesis, Univ. Freiburg), Sec. 5.2, Eq. (5.35)-(5.39), whose
// own simulated IMU is only a constant heading error (digest Sec. 6.2; see estimation/imu/pdr.h
// for that variant). Assumptions, where the thesis is silent:
//  - the phone is held level (roll = pitch = 0) with its body x axis forward along the direction
//    of horizontal motion and z up, so yaw = the direction of motion and the gyro's z axis is the
//    yaw rate; a walker who stands still (horizontal speed < kMinWalkingSpeed_mps) keeps the last
//    yaw (before the first motion, the yaw of the first motion);
//  - specific force f_body = R_body_to_world^T (a_world - g_world), g_world = (0, 0, -g), so a
//    phone at rest reads +g on z;
//  - each step (length drawn per step around step_length_m) adds a vertical acceleration
//    -A sin(2 pi x), x in [0, 1) the progress through the current step by distance walked: one
//    peak per step at 3/4 of it (the heel strike), so the cadence is speed / step length
//    (1.71 Hz at 1.2 m/s with 0.7 m steps; 1.8-2 Hz is the 1.3-1.4 m/s walk). A is faded in
//    linearly between 0.1 and 0.3 m/s, so standing still has no bounce. The horizontal surge and
//    sway of the gait are not modelled; the path's own acceleration is;
//  - the path may come at any rate: it is interpolated linearly to the IMU rate, the velocity is
//    the central difference smoothed by a centred moving average (smoothing_window_s), so a
//    slowly sampled path's corners do not become acceleration spikes, and the acceleration is the
//    central difference of that; each gyro sample is the yaw change over the interval ending at
//    it, so the integrated noise-free gyro reproduces the yaw exactly.
#pragma once

#include <functional>
#include <span>
#include <string>
#include <vector>

#include "mirage/core/options_descriptor.h"
#include "mirage/core/records.h"
#include "mirage/core/rng.h"
#include "mirage/core/types.h"

namespace mirage::channel {

/// Standard gravity (m/s^2); g_world = (0, 0, -kStandardGravity_mps2).
inline constexpr double kStandardGravity_mps2 = 9.80665;
/// Below this horizontal speed (m/s) the walker stands: the yaw is held and there is no bounce.
inline constexpr double kMinWalkingSpeed_mps = 0.1;

/// Parameters of the IMU simulation. The defaults describe a SMARTPHONE-GRADE consumer MEMS IMU
/// (Bosch BMI160 / InvenSense ICM-20600 class datasheets), whose gyro offset is not calibrated
/// out (a walker never stands still long enough for the phone's background calibration).
struct ImuOptions {
  /// Output rate (Hz), > 0. 100 Hz, a phone's usual "game" sensor rate.
  double rate_hz = 100.0;
  /// Accelerometer white-noise density (m/s^2/sqrt(Hz)), >= 0. 2.0e-3, i.e. about 200 ug/sqrt(Hz)
  /// (BMI160: 180, ICM-20600: 100-300 ug/sqrt(Hz)); per-sample sigma = density * sqrt(rate_hz).
  double accel_noise_density_mps2_per_sqrt_hz = 2.0e-3;
  /// Gyroscope white-noise density (rad/s/sqrt(Hz)), >= 0. 2.6e-4, i.e. 0.015 deg/s/sqrt(Hz)
  /// (BMI160: 0.007, ICM-20600/MPU-6500: 0.004-0.01); its integral is the heading random walk
  /// (rad/sqrt(s), same number).
  double gyro_noise_density_radps_per_sqrt_hz = 2.6e-4;
  /// Standard deviation of the accelerometer's turn-on bias per axis (m/s^2), >= 0, constant per
  /// run. 0.1 (about 10 mg): the phone's factory trim of a +-40 mg datasheet zero-g offset.
  double accel_bias_sigma_mps2 = 0.1;
  /// Standard deviation of the gyroscope's turn-on bias per axis (rad/s), >= 0. 8.7e-3, i.e.
  /// 0.5 deg/s, the lower end of an uncompensated phone gyro (datasheet zero-rate offsets of
  /// +-3 deg/s, trimmed at the factory): 5 deg of heading drift per 10 s, the thesis's
  /// "unusable after a certain time" without realignment.
  double gyro_bias_sigma_radps = 8.7e-3;
  /// Random walk of the gyro bias (rad/s/sqrt(s)), >= 0. 5e-5 (0.003 deg/s after 1 s, 0.02 deg/s
  /// after a minute): the in-run drift of consumer MEMS, small beside the turn-on bias.
  double gyro_bias_random_walk_radps_per_sqrt_s = 5e-5;
  /// Mean step length (m), > 0. 0.7 m, an adult's walking step; the cadence is speed / this.
  double step_length_m = 0.7;
  /// Standard deviation of each step's length (m), >= 0. 0.03 m (about 4 %), the step-to-step
  /// variability of steady walking.
  double step_length_sigma_m = 0.03;
  /// Peak vertical acceleration of a step (m/s^2), >= 0. 2.5 m/s^2: the accelerometer norm of a
  /// hand-held phone swings by 2-4 m/s^2 around g in normal walking. 0: no bounce.
  double step_accel_amplitude_mps2 = 2.5;
  /// Width of the centred moving average applied to the finite-difference velocity (s), >= 0.
  /// 0.2 s: longer than the 0.1 s sampling of a typical ground-truth track, much shorter than a
  /// turn. 0: no smoothing (for a path given at the IMU rate).
  double smoothing_window_s = 0.2;
};

/// The options' descriptor (keys, units, ranges, docs; core/options_descriptor.h).
const core::OptionsDescriptor<ImuOptions>& ImuOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const ImuOptions& options);

/// The IMU samples of a walker following the true path (t_s[i], positions_m[i]), at
/// options.rate_hz from t_s.front() to t_s.back(), sensor_id "imu", sensor_index 0. Noise, the
/// turn-on biases and the step lengths come from separate sub-streams seeded by one draw of `rng`.
/// Empty when fewer than two samples are given, the sizes differ or t_s is not increasing.
/// @param t_s         times of the path samples (s), increasing; any rate
/// @param positions_m true positions (m), world frame, z up
std::vector<core::ImuSample> SimulateImu(const ImuOptions& options, std::span<const double> t_s,
                                         std::span<const Vec3> positions_m, core::Rng& rng);

/// The same for a path given as a function of time: it is sampled at the IMU rate on
/// [t_begin_s, t_end_s] (s) and passed to the sampled overload.
std::vector<core::ImuSample> SimulateImu(const ImuOptions& options, const std::function<Vec3(double)>& position_m,
                                         double t_begin_s, double t_end_s, core::Rng& rng);

}  // namespace mirage::channel
