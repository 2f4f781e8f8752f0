// SPDX-License-Identifier: MIT
// The effective options as JSON (io/options_json.h); that it reads back is tested in
// options_yaml_test.cc.
#include "mirage/io/options_json.h"

#include <gtest/gtest.h>

#include "core/test_options.h"

namespace mirage::io {
namespace {

using test::TestTrackerDescriptor;
using test::TestTrackerOptions;

TEST(OptionsToJson, WritesEveryFieldWithSectionsAsNestedObjects) {
  const nlohmann::json json = OptionsToJson(TestTrackerDescriptor(), TestTrackerOptions{});

  EXPECT_EQ(json.size(), 12U);
  EXPECT_EQ(json["gate_m"], 0.3);
  EXPECT_TRUE(json["lost_steps"].is_number_integer());
  EXPECT_EQ(json["lost_steps"], 3);
  EXPECT_EQ(json["reassociate"], true);
  EXPECT_EQ(json["model"], "cir");
  EXPECT_EQ(json["motion"].size(), 3U);
  EXPECT_EQ(json["motion"]["accel_sigma_mps2"], 0.5);
}

}  // namespace
}  // namespace mirage::io
