// SPDX-License-Identifier: MIT
#include "mirage/channel/range_level_simulator.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/options_descriptor_expectations.h"
#include "mirage/core/constants.h"

namespace mirage::channel {
namespace {

ChannelOptions NoDiffuse() {
  ChannelOptions o;
  o.diffuse.enabled = false;
  return o;
}

// One path at 3 m whose amplitude gives the wanted SINR against the synthesizer's N0.
SpecularPath PathWithSinr(const CirSynthesizer& synth, double sinr, double range_m = 3.0) {
  SpecularPath p;
  p.delay_s = range_m / core::kSpeedOfLight_mps;
  p.amplitude = Complex(std::sqrt(sinr * synth.noise_psd()), 0.0);
  return p;
}

TEST(RangeLevelSimulator, RangeNoiseFollowsTheCrlbOfTheTrueSinr) {
  const CirSynthesizer synth(NoDiffuse());
  RangeLevelOptions o;
  o.detection_probability = 1.0;
  o.clutter_rate = 0.0;
  const RangeLevelSimulator sim(o, synth);
  const std::vector<SpecularPath> paths{PathWithSinr(synth, 10.0)};
  core::Rng rng(3, 0);
  double sum = 0.0, sum2 = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const auto r = sim.Simulate(0, paths, 3.0, rng);
    ASSERT_EQ(r.ranges.size(), 1u);
    const double e = r.ranges[0].range_m - 3.0;
    sum += e;
    sum2 += e * e;
  }
  const double sigma = std::sqrt(sum2 / n - (sum / n) * (sum / n));
  const double crlb = synth.pulse().range_sigma_at_unit_sinr_m(synth.options().medium.speed_mps) / std::sqrt(10.0);
  EXPECT_NEAR(sigma / crlb, 1.0, 0.05);
  EXPECT_NEAR(sum / n, 0.0, 4.0 * crlb / std::sqrt(n));
}

TEST(RangeLevelSimulator, DetectionRateAndPoissonClutterMatchTheOptions) {
  const CirSynthesizer synth(NoDiffuse());
  RangeLevelOptions o;
  o.detection_probability = 0.8;
  o.clutter_rate = 2.0;
  const RangeLevelSimulator sim(o, synth);
  const std::vector<SpecularPath> paths{PathWithSinr(synth, 100.0)};
  core::Rng rng(4, 0);
  const int n = 20000;
  int detected = 0;
  double clutter_sum = 0.0, clutter_sum2 = 0.0, clutter_range_sum = 0.0;
  int clutter_total = 0;
  const double window_m = synth.options().window_length_s * core::kSpeedOfLight_mps;
  for (int i = 0; i < n; ++i) {
    const auto r = sim.Simulate(0, paths, 3.0, rng);
    int clutter = 0;
    for (const auto& m : r.ranges) {
      if (std::abs(m.range_m - 3.0) < 0.05) {
        ++detected;
      } else {
        ++clutter;
        clutter_range_sum += m.range_m;
        EXPECT_GE(m.range_m, 0.0);
        EXPECT_LT(m.range_m, window_m);
      }
    }
    clutter_sum += clutter;
    clutter_sum2 += clutter * clutter;
    clutter_total += clutter;
  }
  EXPECT_NEAR(static_cast<double>(detected) / n, 0.8, 0.01);
  const double mean = clutter_sum / n;
  EXPECT_NEAR(mean, 2.0, 0.05);
  EXPECT_NEAR(clutter_sum2 / n - mean * mean, 2.0, 0.1);  // Poisson: variance = mean
  EXPECT_NEAR(clutter_range_sum / clutter_total, window_m / 2.0, 0.02 * window_m);
}

TEST(RangeLevelSimulator, WeakPathsAreNeverDetectedAndClosePathsMerge) {
  const CirSynthesizer synth(NoDiffuse());
  RangeLevelOptions o;
  o.detection_probability = 1.0;
  o.clutter_rate = 0.0;
  const RangeLevelSimulator sim(o, synth);
  core::Rng rng(5, 0);
  const std::vector<SpecularPath> weak{PathWithSinr(synth, 0.01)};  // -20 dB < -10 dB
  EXPECT_TRUE(sim.Simulate(0, weak, 3.0, rng).ranges.empty());
  const std::vector<SpecularPath> close{PathWithSinr(synth, 100.0, 3.0), PathWithSinr(synth, 50.0, 3.01)};
  EXPECT_EQ(sim.Simulate(0, close, 3.0, rng).ranges.size(), 1u);
  const std::vector<SpecularPath> apart{PathWithSinr(synth, 100.0, 3.0), PathWithSinr(synth, 50.0, 3.5)};
  EXPECT_EQ(sim.Simulate(0, apart, 3.0, rng).ranges.size(), 2u);
}

TEST(RangeLevelSimulator, SameSeedSameRanges) {
  const CirSynthesizer synth(ChannelOptions{});
  const RangeLevelSimulator sim(RangeLevelOptions{}, synth);
  const std::vector<SpecularPath> paths{PathWithSinr(synth, 10.0)};
  core::Rng a(9, 1), b(9, 1);
  for (int i = 0; i < 10; ++i) {
    const auto ra = sim.Simulate(0, paths, 3.0, a);
    const auto rb = sim.Simulate(0, paths, 3.0, b);
    ASSERT_EQ(ra.ranges.size(), rb.ranges.size());
    for (std::size_t k = 0; k < ra.ranges.size(); ++k) EXPECT_EQ(ra.ranges[k].range_m, rb.ranges[k].range_m);
  }
}

TEST(RangeLevelSimulator, ValidateNamesTheBadOption) {
  RangeLevelOptions o;
  o.detection_probability = 1.5;
  const auto problems = Validate(o);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].rfind("detection_probability", 0), 0u);
}

TEST(RangeLevelOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMember) {
  test::ExpectDescribesEveryMember(RangeLevelOptionsDescriptor(), {"detection_probability", "clutter_rate",
                                                                   "min_sinr_db", "resolution_m", "max_range_sigma_m"});
}

}  // namespace
}  // namespace mirage::channel
