// SPDX-License-Identifier: MIT
// The ranging simulator: its options' descriptor and validation, and the draws: one range per
// path around its length with the stated noise, detections at the stated probability, clutter
// on [0, max_range_m], one stream per anchor.
#include "mirage/channel/ranging_simulator.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/options_descriptor_expectations.h"

namespace mirage::channel {
namespace {

TEST(RangingOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMember) {
  test::ExpectDescribesEveryMember(RangingOptionsDescriptor(),
                                   {"range_sigma_m", "detection_probability", "clutter_rate", "max_range_m", "multipath"});
}

TEST(RangingOptions, ValidateNamesTheKeyTheValueAndTheRange) {
  RangingOptions options;
  options.detection_probability = 1.5;
  options.max_range_m = 0.0;

  EXPECT_EQ(Validate(options),
            (std::vector<std::string>{"detection_probability: 1.5 is out of range, expected a number in [0, 1]",
                                      "max_range_m: 0 m is out of range, expected a number > 0 m"}));
}

TEST(SimulateRanging, DrawsEachPathsLengthWithTheStatedNoiseAndDetectionProbability) {
  RangingOptions options;
  options.range_sigma_m = 0.1;
  options.detection_probability = 0.8;
  core::Rng rng(4);
  const std::vector<double> truth{3.0, 7.5};
  int detected = 0, trials = 4000;
  double sum = 0.0, sum_sq = 0.0;
  for (int k = 0; k < trials; ++k) {
    for (const auto& r : SimulateRanging(options, truth, rng)) {
      const double error = r.range_m - (r.range_m < 5.0 ? 3.0 : 7.5);
      sum += error;
      sum_sq += error * error;
      ++detected;
      EXPECT_FALSE(r.amplitude.has_value());
    }
  }
  const double p = static_cast<double>(detected) / (2.0 * trials);
  EXPECT_NEAR(p, 0.8, 0.02);                                   // 4 sigma of the binomial
  EXPECT_NEAR(sum / detected, 0.0, 0.01);                      // unbiased
  EXPECT_NEAR(std::sqrt(sum_sq / detected), 0.1, 0.005);      // the stated sigma
}

TEST(SimulateRanging, AddsClutterUniformOverTheRange) {
  RangingOptions options;
  options.clutter_rate = 2.0;
  options.max_range_m = 20.0;
  core::Rng rng(9);
  int clutter = 0;
  double largest = 0.0;
  const int trials = 2000;
  for (int k = 0; k < trials; ++k) {
    const auto ranges = SimulateRanging(options, std::vector<double>{}, rng);
    clutter += static_cast<int>(ranges.size());
    for (const auto& r : ranges) largest = std::max(largest, r.range_m);
  }
  EXPECT_NEAR(static_cast<double>(clutter) / trials, 2.0, 0.15);
  EXPECT_LE(largest, 20.0);
  EXPECT_GT(largest, 19.0);
}

}  // namespace
}  // namespace mirage::channel
