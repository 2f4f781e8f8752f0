// SPDX-License-Identifier: MIT
// The range EKF's options: descriptor and validation.
#include "mirage/methods/range_ekf/range_ekf.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/options_descriptor_expectations.h"

namespace mirage::methods::range_ekf {
namespace {

TEST(RangeEkfOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMember) {
  test::ExpectDescribesEveryMember(RangeEkfOptionsDescriptor(),
                                   {"mode", "range_sigma_m", "gate_chi2", "initial_position_sigma_m",
                                    "initial_velocity_sigma_mps", "motion"});
}

TEST(RangeEkfOptions, ValidateNamesAnUnknownModeAndANestedProblem) {
  RangeEkfOptions options;
  options.mode = "2d";
  options.motion.accel_sigma_mps2 = 0.0;

  const auto problems = Validate(options);

  ASSERT_EQ(problems.size(), 2u);
  EXPECT_EQ(problems[0].rfind("mode: ", 0), 0u) << problems[0];
  EXPECT_NE(problems[0].find("3d, planar"), std::string::npos) << problems[0];
  EXPECT_EQ(problems[1].rfind("motion.accel_sigma_mps2: ", 0), 0u) << problems[1];
}

}  // namespace
}  // namespace mirage::methods::range_ekf
