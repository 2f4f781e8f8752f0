// SPDX-License-Identifier: MIT
// Pedestrian dead reckoning: distance, step count and heading from simulated IMU walks, exact
// results without noise, the increment covariance against a hand-derived golden value, against
// central differences of the heading Jacobian and against 200 seeded runs, and the thesis's
// constant-heading-error increments.
#include "mirage/estimation/imu/pdr.h"

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "core/options_descriptor_expectations.h"
#include "mirage/channel/imu_simulator.h"
#include "mirage/core/constants.h"

namespace mirage::estimation {
namespace {

using channel::ImuOptions;
constexpr double kPi = core::kPi;

// Stand 1 s, speed up at 1 m/s^2 to 1.2 m/s, walk, slow down at 1 m/s^2, stop exactly 20 m east
// of the start, stand 1 s.
Vec3 StraightWalk(double t_s) {
  const double v = 1.2, ramp_s = 1.2, ramp_m = 0.72, cruise_s = (20.0 - 2.0 * ramp_m) / v;
  double x = 0.0;
  double t = t_s - 1.0;
  if (t > 0.0) x += 0.5 * std::pow(std::min(t, ramp_s), 2);
  t -= ramp_s;
  if (t > 0.0) x += v * std::min(t, cruise_s);
  t -= cruise_s;
  if (t > 0.0) {
    const double tt = std::min(t, ramp_s);
    x += v * tt - 0.5 * tt * tt;
  }
  return {x, 0.0, 1.3};
}
constexpr double kStraightWalkEnd_s = 1.0 + 2.4 + (20.0 - 1.44) / 1.2 + 1.0;

// A unicycle walk at constant speed with a yaw-rate profile, integrated at 1 ms and returned at
// 100 Hz (times and positions).
struct Path {
  std::vector<double> t_s;
  std::vector<Vec3> p_m;
  Vec3 At(double t) const { return p_m[static_cast<std::size_t>(std::lround(t * 100.0))]; }
};
Path Unicycle(double speed_mps, const std::function<double(double)>& yaw_rate_radps, double end_s) {
  Path path;
  Vec3 p(0.0, 0.0, 1.3);
  double yaw = 0.0;
  for (int k = 0; k <= static_cast<int>(std::lround(end_s * 1000.0)); ++k) {
    const double t = k * 1e-3;
    if (k % 10 == 0) {
      path.t_s.push_back(t);
      path.p_m.push_back(p);
    }
    yaw += yaw_rate_radps(t + 0.5e-3) * 1e-3;
    p += speed_mps * 1e-3 * Vec3(std::cos(yaw), std::sin(yaw), 0.0);
  }
  return path;
}

// East 4 s, a 90-degree left turn over 2 s, north: at 1.2 m/s for `end_s`.
Path TurnWalk(double end_s) {
  return Unicycle(1.2, [](double t) { return t > 4.0 && t < 6.0 ? kPi / 4.0 : 0.0; }, end_s);
}

ImuOptions NoiseFreeImu() {
  ImuOptions o;
  o.accel_noise_density_mps2_per_sqrt_hz = 0.0;
  o.gyro_noise_density_radps_per_sqrt_hz = 0.0;
  o.accel_bias_sigma_mps2 = 0.0;
  o.gyro_bias_sigma_radps = 0.0;
  o.gyro_bias_random_walk_radps_per_sqrt_s = 0.0;
  o.step_length_sigma_m = 0.0;
  return o;
}

PdrOptions NoiseFreePdr() {
  PdrOptions o;
  o.step_length_sigma_m = 0.0;
  o.gyro_noise_density_radps_per_sqrt_hz = 0.0;
  o.gyro_bias_sigma_radps = 0.0;
  o.gyro_bias_random_walk_radps_per_sqrt_s = 0.0;
  return o;
}

// A sample at t_s with the given accelerometer norm (on z) and yaw rate.
core::ImuSample Sample(double t_s, double norm_mps2, double yaw_rate_radps = 0.0) {
  core::ImuSample s;
  s.t_s = t_s;
  s.accel_mps2 = Vec3(0.0, 0.0, norm_mps2);
  s.gyro_radps = Vec3(0.0, 0.0, yaw_rate_radps);
  return s;
}

TEST(PdrOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMember) {
  test::ExpectDescribesEveryMember(PdrOptionsDescriptor(),
                                   {"step_peak_threshold_mps2", "min_step_interval_s", "max_step_interval_s",
                                    "step_length_m", "step_length_sigma_m", "gyro_noise_density_radps_per_sqrt_hz",
                                    "gyro_bias_sigma_radps", "gyro_bias_random_walk_radps_per_sqrt_s"});
  test::ExpectDescribesEveryMember(ConstantHeadingErrorOptionsDescriptor(),
                                   {"constant_heading_error_rad", "sigma_per_distance", "sigma_floor_m"});
  PdrOptions bad;
  bad.max_step_interval_s = 0.2;
  EXPECT_EQ(Validate(bad), std::vector<std::string>{"max_step_interval_s: must exceed min_step_interval_s"});
}

TEST(PdrIntegrator, CountsTheStepsAndTheDistanceOfAStraightWalk) {
  core::Rng rng(11);
  const auto samples = channel::SimulateImu(ImuOptions{}, StraightWalk, 0.0, kStraightWalkEnd_s, rng);
  PdrIntegrator pdr{PdrOptions{}};
  pdr.Reset(0.0, 0.0);
  for (const auto& s : samples) pdr.Add(s);
  const auto inc = pdr.TakeIncrement();

  RecordProperty("steps", inc.steps);
  RecordProperty("distance_m", std::to_string(inc.delta_m.norm()));
  EXPECT_NEAR(inc.steps, 20.0 / 0.7, 1.0);
  EXPECT_NEAR(inc.delta_m.norm(), 20.0, 0.05 * 20.0);
  EXPECT_EQ(inc.steps, pdr.total_steps());
  // The sideways drift of the uncompensated gyro bias is within the covariance (99.9 %).
  const Vec2 error = inc.delta_m - Vec2(20.0, 0.0);
  EXPECT_LT(error.dot(inc.covariance_m2.ldlt().solve(error)), 13.8);
}

TEST(PdrIntegrator, FollowsANinetyDegreeTurn) {
  ImuOptions imu;
  PdrOptions pdr_options;
  // A gyro calibrated at rest (0.05 deg/s): with the uncompensated 0.5 deg/s the heading's
  // standard deviation after 10 s would be 5 deg itself.
  imu.gyro_bias_sigma_radps = pdr_options.gyro_bias_sigma_radps = 8.7e-4;
  const Path path = TurnWalk(10.0);
  core::Rng rng(12);
  const auto samples = channel::SimulateImu(imu, path.t_s, path.p_m, rng);
  PdrIntegrator pdr(pdr_options);
  pdr.Reset(0.0, 0.0);
  for (const auto& s : samples) pdr.Add(s);

  EXPECT_NEAR(pdr.t_s(), 10.0, 1e-9);
  RecordProperty("heading_error_deg", std::to_string((pdr.heading_rad() - kPi / 2.0) * 180.0 / kPi));
  EXPECT_NEAR(pdr.heading_rad(), kPi / 2.0, 5.0 * kPi / 180.0);
  EXPECT_LT(pdr.heading_sigma_rad(), 1.0 * kPi / 180.0);
}

TEST(PdrIntegrator, IsExactWithoutNoise) {
  core::Rng rng(13);
  {
    const auto samples = channel::SimulateImu(NoiseFreeImu(), StraightWalk, 0.0, kStraightWalkEnd_s, rng);
    PdrIntegrator pdr(NoiseFreePdr());
    pdr.Reset(0.0, 0.0);
    for (const auto& s : samples) pdr.Add(s);
    const auto inc = pdr.TakeIncrement();
    // Peaks at 3/4 of each 0.7 m step: 0.525 m, ..., 19.425 m; the walker stops 2 s later.
    EXPECT_EQ(inc.steps, 28);
    EXPECT_NEAR(inc.delta_m.x(), 28 * 0.7, 1e-9);
    EXPECT_EQ(inc.delta_m.y(), 0.0);
    EXPECT_EQ(inc.covariance_m2, Eigen::Matrix2d::Zero());
  }
  {
    const Path path = TurnWalk(12.0);
    const auto samples = channel::SimulateImu(NoiseFreeImu(), path.t_s, path.p_m, rng);
    PdrIntegrator pdr(NoiseFreePdr());
    pdr.Reset(0.0, 0.0);
    for (const auto& s : samples) {
      pdr.Add(s);
      if (std::abs(s.t_s - 8.0) < 1e-9) pdr.TakeIncrement();
    }
    EXPECT_NEAR(pdr.heading_rad(), kPi / 2.0, 1e-9);
    // Walking north 8-12 s at constant cadence: the increment, steps in progress included, is
    // the truth (4.8 m north) up to the rounding of the step times to the 10 ms samples.
    const auto inc = pdr.TakeIncrement();
    EXPECT_NEAR(inc.t_from_s, 8.0, 1e-9);
    EXPECT_NEAR(inc.delta_m.x(), 0.0, 1e-9);
    EXPECT_NEAR(inc.delta_m.y(), (path.At(12.0) - path.At(8.0)).y(), 0.02);
  }
}

// Steps every 0.5 s (norm peaks at samples 50, 100, ...), heading 0, then an increment at
// t_take_s; the heading errors at the credited pieces' times t_i (lengths l_i) give the cross-track
// variance sum_ij l_i l_j K(t_i, t_j), K(s, t) = sigma_b^2 s t + q min(s, t), and the length errors
// the along-track variance sum_i (l_i / L)^2 sigma_L^2.
TEST(PdrIntegrator, IncrementCovarianceMatchesTheHandDerivedHeadingAndLengthErrors) {
  PdrOptions options = NoiseFreePdr();
  options.gyro_bias_sigma_radps = 0.01;
  options.gyro_noise_density_radps_per_sqrt_hz = 0.003;
  options.step_length_sigma_m = 0.05;
  PdrIntegrator pdr(options);
  pdr.Reset(0.0, 0.0);
  const double t_take_s = 2.26;
  for (int k = 0; k <= 226; ++k) pdr.Add(Sample(0.01 * k, k > 0 && k % 50 == 0 ? 12.0 : 9.8));
  const auto inc = pdr.TakeIncrement();

  // Steps detected at 0.5, 1.0, 1.5, 2.0 s; the period is 0.5 s, so 0.26 s later 0.52 of the next.
  ASSERT_EQ(inc.steps, 4);
  const std::vector<double> t_i{0.5, 1.0, 1.5, 2.0, t_take_s};
  const std::vector<double> l_i{0.7, 0.7, 0.7, 0.7, 0.52 * 0.7};
  double cross = 0.0, along = 0.0;
  for (std::size_t i = 0; i < t_i.size(); ++i) {
    along += std::pow(l_i[i] / 0.7 * 0.05, 2);
    for (std::size_t j = 0; j < t_i.size(); ++j) {
      cross += l_i[i] * l_i[j] * (1e-4 * t_i[i] * t_i[j] + 9e-6 * std::min(t_i[i], t_i[j]));
    }
  }
  EXPECT_NEAR(inc.delta_m.x(), 4.52 * 0.7, 1e-9);
  EXPECT_NEAR(inc.covariance_m2(0, 0), along, 1e-12);
  EXPECT_NEAR(inc.covariance_m2(1, 1), cross, 1e-12);
  EXPECT_NEAR(inc.covariance_m2(0, 1), 0.0, 1e-12);
  EXPECT_NEAR(pdr.heading_sigma_rad(), std::sqrt(1e-4 * t_take_s * t_take_s + 9e-6 * t_take_s), 1e-12);

  // The next increment starts uncorrelated at 0 and credits the rest of the step in progress.
  for (int k = 227; k <= 250; ++k) pdr.Add(Sample(0.01 * k, k % 50 == 0 ? 12.0 : 9.8));
  pdr.Add(Sample(2.51, 9.8));
  const auto next = pdr.TakeIncrement();
  EXPECT_EQ(next.steps, 1);
  EXPECT_NEAR(next.delta_m.x(), (0.48 + 0.02) * 0.7, 1e-9);  // the step's rest, then 0.01 s / 0.5 s
}

// With only an initial heading uncertainty, the increment covariance is J J^T sigma_0^2 with
// J = d delta / d heading_0; J by central differences of two runs from perturbed headings.
TEST(PdrIntegrator, HeadingJacobianMatchesCentralDifferences) {
  const auto run = [](double heading0_rad, double sigma0_rad) {
    PdrIntegrator pdr(NoiseFreePdr());
    pdr.Reset(0.0, heading0_rad, sigma0_rad);
    for (int k = 0; k <= 330; ++k) {
      // Turning at 0.4 rad/s, steps every 0.6 s.
      pdr.Add(Sample(0.01 * k, k > 0 && k % 60 == 0 ? 12.0 : 9.8, 0.4));
    }
    return pdr.TakeIncrement();
  };
  const double h0 = 0.7, eps = 1e-6;
  const Vec2 J = (run(h0 + eps, 0.0).delta_m - run(h0 - eps, 0.0).delta_m) / (2.0 * eps);
  const auto inc = run(h0, 0.3);
  EXPECT_EQ(inc.steps, 5);
  EXPECT_TRUE(inc.covariance_m2.isApprox(0.09 * J * J.transpose(), 1e-7)) << inc.covariance_m2 << "\n" << J;
}

TEST(PdrIntegrator, IncrementErrorsOfSimulatedWalksMatchTheCovariance) {
  ImuOptions imu;  // smartphone defaults: 0.5 deg/s turn-on gyro bias, 0.03 m step variability
  PdrOptions options;
  options.step_length_sigma_m = imu.step_length_sigma_m;
  const Path path = Unicycle(1.2, [](double) { return 0.1; }, 7.0);
  core::Rng rng(14);
  const int runs = 200;
  double nees_sum = 0.0;
  for (int r = 0; r < runs; ++r) {
    const auto samples = channel::SimulateImu(imu, path.t_s, path.p_m, rng);
    PdrIntegrator pdr(options);
    pdr.Reset(0.0, 0.0);
    for (const auto& s : samples) {
      pdr.Add(s);
      if (std::abs(s.t_s - 3.0) < 1e-9) pdr.TakeIncrement();
    }
    const auto inc = pdr.TakeIncrement();
    ASSERT_NEAR(inc.t_from_s, 3.0, 1e-9);
    const Vec2 error = inc.delta_m - (path.At(inc.t_to_s) - path.At(inc.t_from_s)).head<2>();
    nees_sum += error.dot(inc.covariance_m2.ldlt().solve(error));
  }
  // Mean NEES / dof; 200 runs of 2 dof give a 1-sigma spread of 0.07 around 1 if consistent.
  const double ratio = nees_sum / runs / 2.0;
  RecordProperty("nees_over_dof", std::to_string(ratio));
  EXPECT_GT(ratio, 0.5);
  EXPECT_LT(ratio, 2.0);
}

TEST(PdrIntegrator, SetHeadingReplacesTheHeadingAndItsUncertainty) {
  PdrIntegrator pdr{PdrOptions{}};
  pdr.Reset(0.0, 0.0);
  for (int k = 0; k <= 500; ++k) pdr.Add(Sample(0.01 * k, 9.8, 0.02));
  EXPECT_NEAR(pdr.heading_rad(), 0.1, 1e-9);
  EXPECT_GT(pdr.heading_sigma_rad(), 0.04);  // 0.5 deg/s bias for 5 s
  pdr.SetHeading(1.0, 0.01);
  EXPECT_EQ(pdr.heading_rad(), 1.0);
  EXPECT_NEAR(pdr.heading_sigma_rad(), 0.01, 1e-12);
  // A sample from the past is ignored.
  pdr.Add(Sample(1.0, 9.8, 5.0));
  EXPECT_EQ(pdr.heading_rad(), 1.0);
  EXPECT_NEAR(pdr.t_s(), 5.0, 1e-9);
}

TEST(ConstantHeadingErrorIncrement, RotatesTheTrueIncrementExactly) {
  ConstantHeadingErrorOptions options;
  options.constant_heading_error_rad = 0.2;
  const Vec2 from(1.0, 2.0), to(4.0, 6.0);  // 5 m at atan2(4, 3)
  const auto inc = ConstantHeadingErrorIncrement(options, from, to, 1.0, 3.5);
  EXPECT_NEAR(inc.delta_m.norm(), 5.0, 1e-12);
  EXPECT_NEAR(std::atan2(inc.delta_m.y(), inc.delta_m.x()), std::atan2(4.0, 3.0) + 0.2, 1e-12);
  EXPECT_NEAR(inc.delta_m.x(), 3.0 * std::cos(0.2) - 4.0 * std::sin(0.2), 1e-12);
  const double sigma = 0.02 + 0.05 * 5.0;
  EXPECT_TRUE(inc.covariance_m2.isApprox(sigma * sigma * Eigen::Matrix2d::Identity(), 1e-12));
  EXPECT_EQ(inc.t_from_s, 1.0);
  EXPECT_EQ(inc.t_to_s, 3.5);
  EXPECT_EQ(inc.steps, 0);
}

}  // namespace
}  // namespace mirage::estimation
