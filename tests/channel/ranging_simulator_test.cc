// SPDX-License-Identifier: MIT
// The ranging simulator's options: descriptor and validation.
#include "mirage/channel/ranging_simulator.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/options_descriptor_expectations.h"

namespace mirage::channel {
namespace {

TEST(RangingOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMember) {
  test::ExpectDescribesEveryMember(RangingOptionsDescriptor(),
                                   {"range_sigma_m", "detection_probability", "clutter_rate", "max_range_m"});
}

TEST(RangingOptions, ValidateNamesTheKeyTheValueAndTheRange) {
  RangingOptions options;
  options.detection_probability = 1.5;
  options.max_range_m = 0.0;

  EXPECT_EQ(Validate(options),
            (std::vector<std::string>{"detection_probability: 1.5 is out of range, expected a number in [0, 1]",
                                      "max_range_m: 0 m is out of range, expected a number > 0 m"}));
}

}  // namespace
}  // namespace mirage::channel
