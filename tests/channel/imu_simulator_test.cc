// SPDX-License-Identifier: MIT
// The IMU simulator: gravity and white noise at rest, one turn-on bias per run, specific force and
// yaw rate on a circle (also from a slowly sampled path), one bounce per step at speed / step
// length, none while standing, and the yaw held through a stop.
#include "mirage/channel/imu_simulator.h"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/options_descriptor_expectations.h"
#include "mirage/core/constants.h"

namespace mirage::channel {
namespace {

ImuOptions NoiseFree() {
  ImuOptions o;
  o.accel_noise_density_mps2_per_sqrt_hz = 0.0;
  o.gyro_noise_density_radps_per_sqrt_hz = 0.0;
  o.accel_bias_sigma_mps2 = 0.0;
  o.gyro_bias_sigma_radps = 0.0;
  o.gyro_bias_random_walk_radps_per_sqrt_s = 0.0;
  o.step_length_sigma_m = 0.0;
  return o;
}

// Counter-clockwise circle of radius r_m around the origin at speed v_mps, starting at (r, 0).
Vec3 Circle(double t_s, double r_m, double v_mps) {
  const double angle = v_mps / r_m * t_s;
  return {r_m * std::cos(angle), r_m * std::sin(angle), 1.2};
}

TEST(ImuOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMember) {
  test::ExpectDescribesEveryMember(
      ImuOptionsDescriptor(),
      {"rate_hz", "accel_noise_density_mps2_per_sqrt_hz", "gyro_noise_density_radps_per_sqrt_hz", "accel_bias_sigma_mps2",
       "gyro_bias_sigma_radps", "gyro_bias_random_walk_radps_per_sqrt_s", "step_length_m", "step_length_sigma_m",
       "step_accel_amplitude_mps2", "smoothing_window_s"});
}

TEST(ImuOptions, ValidateRejectsAStepSigmaThatAllowsNegativeSteps) {
  ImuOptions options;
  options.step_length_sigma_m = 0.5;
  EXPECT_EQ(Validate(options).size(), 1u);
}

TEST(SimulateImu, ReadsGravityUpAtRestWithTheStatedWhiteNoise) {
  ImuOptions options = NoiseFree();
  options.accel_noise_density_mps2_per_sqrt_hz = 2e-3;
  options.gyro_noise_density_radps_per_sqrt_hz = 3e-4;
  core::Rng rng(1);
  const auto samples = SimulateImu(options, [](double) { return Vec3(1.0, 2.0, 1.0); }, 0.0, 40.0, rng);
  ASSERT_EQ(samples.size(), 4001u);
  Vec3 sum_a = Vec3::Zero(), sum_sq_a = Vec3::Zero(), sum_sq_g = Vec3::Zero();
  for (const auto& s : samples) {
    sum_a += s.accel_mps2;
    sum_sq_a += (s.accel_mps2 - Vec3(0.0, 0.0, kStandardGravity_mps2)).cwiseAbs2();
    sum_sq_g += s.gyro_radps.cwiseAbs2();
  }
  const double n = static_cast<double>(samples.size());
  EXPECT_NEAR(sum_a.z() / n, 9.80665, 1e-3);
  EXPECT_NEAR(sum_a.x() / n, 0.0, 1e-3);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(std::sqrt(sum_sq_a[i] / n), 2e-3 * 10.0, 0.05 * 2e-3 * 10.0);  // density * sqrt(100 Hz)
    EXPECT_NEAR(std::sqrt(sum_sq_g[i] / n), 3e-4 * 10.0, 0.05 * 3e-4 * 10.0);
  }
}

TEST(SimulateImu, DrawsOneTurnOnBiasPerRun) {
  ImuOptions options = NoiseFree();
  options.accel_bias_sigma_mps2 = 0.1;
  options.gyro_bias_sigma_radps = 0.01;
  core::Rng rng(2);
  double sum_sq_a = 0.0, sum_sq_g = 0.0;
  const int runs = 1000;
  for (int r = 0; r < runs; ++r) {
    const auto samples = SimulateImu(options, [](double) { return Vec3::Zero(); }, 0.0, 0.1, rng);
    ASSERT_EQ(samples.size(), 11u);
    // Constant within the run.
    EXPECT_EQ(samples.front().accel_mps2, samples.back().accel_mps2);
    EXPECT_EQ(samples.front().gyro_radps, samples.back().gyro_radps);
    sum_sq_a += std::pow(samples.front().accel_mps2.x(), 2);
    sum_sq_g += std::pow(samples.front().gyro_radps.z(), 2);
  }
  // 1000 runs: the sample sigma is within about 2 % (1 sigma) of the truth.
  EXPECT_NEAR(std::sqrt(sum_sq_a / runs), 0.1, 0.008);
  EXPECT_NEAR(std::sqrt(sum_sq_g / runs), 0.01, 0.0008);
}

TEST(SimulateImu, OnACircleReadsTheYawRateAndTheCentripetalForceToTheLeft) {
  ImuOptions options = NoiseFree();
  options.step_accel_amplitude_mps2 = 0.0;
  const double r_m = 3.0, v_mps = 1.5;
  core::Rng rng(3);
  const auto samples = SimulateImu(options, [&](double t) { return Circle(t, r_m, v_mps); }, 0.0, 10.0, rng);
  ASSERT_EQ(samples.size(), 1001u);
  // Away from the ends, where the smoothing window is cut short.
  for (std::size_t k = 100; k < 900; ++k) {
    const auto& s = samples[k];
    EXPECT_NEAR(s.gyro_radps.z(), v_mps / r_m, 1e-6);
    EXPECT_NEAR(s.accel_mps2.x(), 0.0, 1e-3);                     // no forward acceleration
    EXPECT_NEAR(s.accel_mps2.y(), v_mps * v_mps / r_m, 0.01);     // to the centre, the body's left
    EXPECT_NEAR(s.accel_mps2.z(), kStandardGravity_mps2, 1e-9);
    EXPECT_EQ(s.gyro_radps.x(), 0.0);
  }
}

TEST(SimulateImu, InterpolatesASlowlySampledPathWithoutAccelerationSpikes) {
  ImuOptions options = NoiseFree();
  options.step_accel_amplitude_mps2 = 0.0;
  const double r_m = 3.0, v_mps = 1.5;
  std::vector<double> t_s;
  std::vector<Vec3> p_m;
  for (int i = 0; i <= 100; ++i) {  // 10 Hz ground truth
    t_s.push_back(0.1 * i);
    p_m.push_back(Circle(0.1 * i, r_m, v_mps));
  }
  core::Rng rng(4);
  const auto samples = SimulateImu(options, t_s, p_m, rng);
  ASSERT_EQ(samples.size(), 1001u);
  double mean_rate = 0.0, mean_lateral = 0.0;
  for (std::size_t k = 100; k < 900; ++k) {
    mean_rate += samples[k].gyro_radps.z() / 800.0;
    mean_lateral += samples[k].accel_mps2.y() / 800.0;
    // The chords turn by 0.05 rad every 0.1 s: a 0.075 m/s velocity jump, 3.75 m/s^2 in one
    // central difference; smoothed over 0.2 s it ripples by less than 0.2 m/s^2 around v^2 / r.
    EXPECT_NEAR(samples[k].accel_mps2.y(), v_mps * v_mps / r_m, 0.2);
    EXPECT_NEAR(samples[k].accel_mps2.x(), 0.0, 0.05);
  }
  EXPECT_NEAR(mean_rate, v_mps / r_m, 0.01 * v_mps / r_m);
  EXPECT_NEAR(mean_lateral, v_mps * v_mps / r_m, 0.01 * v_mps * v_mps / r_m);
}

TEST(SimulateImu, BouncesOncePerStepAtSpeedOverStepLengthAndNotWhenStanding) {
  ImuOptions options = NoiseFree();
  // Stand 2 s, speed up at 1.4 m/s^2 (0.7 m), walk 12.6 m at 1.4 m/s (9 s), slow down (0.7 m),
  // stand 2 s: 14 m east.
  const auto path = [](double t) {
    const double a = std::clamp(t - 2.0, 0.0, 1.0), c = std::clamp(t - 3.0, 0.0, 9.0), d = std::clamp(t - 12.0, 0.0, 1.0);
    return Vec3(0.7 * a * a + 1.4 * c + 1.4 * d - 0.7 * d * d, 0.0, 1.2);
  };
  core::Rng rng(5);
  const auto samples = SimulateImu(options, path, 0.0, 15.0, rng);
  std::vector<double> peak_times_s;
  for (std::size_t k = 1; k + 1 < samples.size(); ++k) {
    const double n = samples[k].accel_mps2.norm();
    if (n > samples[k - 1].accel_mps2.norm() && n >= samples[k + 1].accel_mps2.norm() && n > 11.0) {
      peak_times_s.push_back(samples[k].t_s);
      if (samples[k].t_s > 3.2 && samples[k].t_s < 11.8) {
        EXPECT_NEAR(n, kStandardGravity_mps2 + 2.5, 0.01);
      }
    }
  }
  // 14 m / 0.7 m = 20 steps, each peaking at 3/4 of the step: at 0.525 m (at 1.4 m/s^2 from rest,
  // after sqrt(0.75) s), then every 0.7 m, 0.5 s apart at 1.4 m/s: a cadence of 2 Hz.
  ASSERT_EQ(peak_times_s.size(), 20u);
  EXPECT_NEAR(peak_times_s.front(), 2.0 + std::sqrt(0.75), 0.02);
  for (std::size_t i = 1; i < peak_times_s.size(); ++i) {
    if (peak_times_s[i - 1] > 3.2 && peak_times_s[i] < 11.8) {
      EXPECT_NEAR(peak_times_s[i] - peak_times_s[i - 1], 0.5, 0.011);
    }
  }
  for (const auto& s : samples) {
    if (s.t_s < 1.8 || s.t_s > 13.2) {
      EXPECT_NEAR(s.accel_mps2.norm(), kStandardGravity_mps2, 1e-9) << s.t_s;
    }
  }
}

TEST(SimulateImu, HoldsTheYawThroughAStop) {
  ImuOptions options = NoiseFree();
  // North 3 s at 1 m/s, stand 2 s, then east 3 s: the gyro turns by -pi/2 in total, and not at all
  // while standing.
  const auto path = [](double t) {
    if (t < 3.0) return Vec3(0.0, t, 1.0);
    if (t < 5.0) return Vec3(0.0, 3.0, 1.0);
    return Vec3(t - 5.0, 3.0, 1.0);
  };
  core::Rng rng(6);
  const auto samples = SimulateImu(options, path, 0.0, 8.0, rng);
  double turned_rad = 0.0;
  for (std::size_t k = 1; k < samples.size(); ++k) {
    turned_rad += samples[k].gyro_radps.z() * (samples[k].t_s - samples[k - 1].t_s);
    if (samples[k].t_s > 3.3 && samples[k].t_s < 4.7) {
      EXPECT_EQ(samples[k].gyro_radps.z(), 0.0);
    }
  }
  EXPECT_NEAR(turned_rad, -core::kPi / 2.0, 1e-9);
  // Stopping while heading north: the braking (world -y) is on the body's -x axis, none on y.
  const auto& braking = samples[300];
  EXPECT_NEAR(braking.t_s, 3.0, 1e-9);
  EXPECT_LT(braking.accel_mps2.x(), -1.0);
  EXPECT_NEAR(braking.accel_mps2.y(), 0.0, 1e-9);
}

TEST(SimulateImu, ReturnsNothingForAnUnusablePath) {
  core::Rng rng(7);
  const std::vector<double> t{0.0, 1.0};
  const std::vector<Vec3> one{Vec3::Zero()};
  const std::vector<Vec3> two{Vec3::Zero(), Vec3::Ones()};
  const std::vector<double> not_increasing{1.0, 1.0};
  EXPECT_TRUE(SimulateImu(ImuOptions{}, t, one, rng).empty());
  EXPECT_TRUE(SimulateImu(ImuOptions{}, not_increasing, two, rng).empty());
  EXPECT_EQ(SimulateImu(ImuOptions{}, t, two, rng).size(), 101u);
}

}  // namespace
}  // namespace mirage::channel
