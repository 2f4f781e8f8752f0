// SPDX-License-Identifier: MIT
// The acoustic estimator's behaviour: the TDOA bound (Eq. 5.5) removes the stamp that breaks it,
// the filter tracks the emission time through a drifting sender clock (the interval error in the
// state), the REKF's weights isolate one microphone's NLOS bias that pulls the plain EKF away, and
// the snapshot NLLS finds the sender from random starts.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/core/medium.h"
#include "mirage/core/rng.h"
#include "mirage/methods/acoustic/acoustic_estimator.h"

namespace mirage::methods::acoustic {
namespace {

constexpr double kC = 343.0;

World Hall() {
  World world;
  world.anchors = {{"M1", Vec3(1.0, 1.0, 4.85)}, {"M2", Vec3(14.0, 1.0, 4.83)}, {"M3", Vec3(14.0, 10.0, 4.87)},
                   {"M4", Vec3(1.0, 10.0, 4.84)}, {"M5", Vec3(7.5, 5.5, 3.40)}, {"M6", Vec3(7.5, 1.0, 4.86)},
                   {"M7", Vec3(4.0, 7.0, 3.40)}};
  world.agents = {"phone"};
  world.agent_height_m = 1.2;
  world.channel.medium = core::Medium{core::MediumKind::kSound, kC};
  return world;
}

// One emission's stamps: each microphone's direct path at t_emit plus noise, plus bias_m / c on
// microphone `biased`.
core::Epoch Emission(const World& world, const Vec3& sender_m, double t_emit_s, double sigma_s, core::Rng& rng,
                     int biased = -1, double bias_m = 0.0) {
  core::Epoch epoch;
  epoch.t_s = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < world.anchors.size(); ++i) {
    core::ToaStamps stamps;
    stamps.receiver_id = world.anchors[i].id;
    stamps.receiver_index = static_cast<int>(i);
    double t = t_emit_s + (sender_m - world.anchors[i].position_m).norm() / kC + rng.Normal(0.0, sigma_s);
    if (static_cast<int>(i) == biased) t += bias_m / kC;
    stamps.toa_s = {t};
    epoch.t_s = std::min(epoch.t_s, t);
    epoch.toas.push_back(stamps);
  }
  for (auto& s : epoch.toas) s.t_s = epoch.t_s;
  return epoch;
}

TEST(AcousticTdoaBound, RemovesTheStampThatBreaksTheBound) {
  const World world = Hall();
  const Vec3 sender(5.0, 4.0, 1.2);
  std::vector<ChosenStamp> chosen;
  for (std::size_t i = 0; i < world.anchors.size(); ++i) {
    chosen.push_back({static_cast<int>(i), (sender - world.anchors[i].position_m).norm()});
  }
  // Consistent stamps pass untouched.
  EXPECT_EQ(ApplyTdoaBound(chosen, world.anchors, 0.3).size(), chosen.size());
  // A stamp 20 m late breaks the bound with every other microphone and goes.
  chosen[2].z_m += 20.0;
  const auto kept = ApplyTdoaBound(chosen, world.anchors, 0.3);
  ASSERT_EQ(kept.size(), chosen.size() - 1);
  for (const auto& c : kept) EXPECT_NE(c.receiver, 2);
}

// Tracks a static sender for `emissions` emissions whose clock runs drift_ppm fast; returns the
// final 2-D error.
double StaticError(AcousticOptions options, double drift_ppm, int emissions, int biased = -1, double bias_m = 0.0) {
  const World world = Hall();
  options.emission_interval_s = 0.1;
  options.range_sigma_m = kC * 0.1e-3;
  const Vec3 sender(6.0, 4.0, 1.2);
  AcousticEstimator estimator(options, world);
  estimator.Initialize({0.0, {sender + Vec3(0.3, -0.2, 0.0)}});
  core::Rng rng(7);
  double error_m = 0.0;
  for (int k = 0; k < emissions; ++k) {
    const double t_emit_s = 0.0123 + k * 0.1 * (1.0 + 1e-6 * drift_ppm);
    const auto out = estimator.Process(Emission(world, sender, t_emit_s, 0.1e-3, rng, biased, bias_m));
    error_m = (out.agents.front().position_m.head<2>() - sender.head<2>()).norm();
  }
  return error_m;
}

TEST(AcousticEstimator, FollowsADriftingSenderClock) {
  AcousticOptions options;
  options.estimator = "ekf";
  // 50 ppm over 60 s of 0.1 s intervals: the emission time walks 3 ms (1 m) off the nominal
  // interval; the interval error in the state absorbs it.
  EXPECT_LT(StaticError(options, 50.0, 600), 0.05);
  // Without room for an interval error (a rate prior of 0 ppm) the same clock drags the fix.
  options.clock_drift_ppm = 0.0;
  options.emission_jitter_s = 0.0;
  EXPECT_GT(StaticError(options, 50.0, 600), 0.05);
}

TEST(AcousticEstimator, RobustWeightsIsolateOneBiasedMicrophone) {
  AcousticOptions options;
  options.estimator = "rekf";
  const double rekf_m = StaticError(options, 0.0, 100, 4, 2.0);
  options.estimator = "ekf";
  const double ekf_m = StaticError(options, 0.0, 100, 4, 2.0);
  EXPECT_LT(rekf_m, 0.05);
  EXPECT_GT(ekf_m, 3.0 * rekf_m);
}

TEST(AcousticEstimator, SnapshotNllsFindsTheSender) {
  AcousticOptions options;
  options.estimator = "nlls";
  options.range_sigma_m = kC * 0.05e-3;
  const World world = Hall();
  AcousticEstimator estimator(options, world);
  estimator.Initialize({0.0, {Vec3(1.0, 1.0, 1.2)}});  // a wrong start: the snapshot ignores it
  core::Rng rng(3);
  const Vec3 sender(11.0, 7.5, 1.2);
  const auto out = estimator.Process(Emission(world, sender, 0.5, 0.05e-3, rng));
  EXPECT_LT((out.agents.front().position_m - sender).norm(), 0.1);
  EXPECT_EQ(out.associations, static_cast<int>(world.anchors.size()));
}

}  // namespace
}  // namespace mirage::methods::acoustic
