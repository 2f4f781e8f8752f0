// SPDX-License-Identifier: MIT
// Reading options through their descriptor (io/options_yaml.h): values of every kind, defaults
// and derived defaults, and an InputError naming file, line, key path, value, expected range and
// unit for each kind of bad input; the JSON of the effective options reads back to the same
// values.
#include "mirage/io/options_yaml.h"

#include <memory>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/test_options.h"
#include "mirage/io/input_error.h"
#include "mirage/io/options_json.h"
#include "mirage/methods/mint/relocalization.h"

namespace mirage::io {
namespace {

using core::PhysicalKeys;
using test::TestModel;
using test::TestTrackerDescriptor;
using test::TestTrackerOptions;
using ::testing::HasSubstr;

// The `tracker` section of a YAML document named test.yaml.
TestTrackerOptions Read(const std::string& yaml, const PhysicalKeys& keys = {}) {
  YamlMap root(LoadYamlString(yaml, "test.yaml"), "", std::make_shared<YamlOrigins>("test.yaml"));
  TestTrackerOptions options;
  ReadOptions(root.Map("tracker"), TestTrackerDescriptor(), keys, options);
  return options;
}

std::string ErrorOf(const std::string& yaml, const PhysicalKeys& keys = {}) {
  try {
    Read(yaml, keys);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError for:\n" << yaml;
  return "";
}

PhysicalKeys WalkerKeys() {
  PhysicalKeys keys;
  keys.speed_mps = 0.5;
  keys.dt_s = 0.1;
  keys.range_sigma_m = 0.07;
  return keys;
}

TEST(ReadOptions, ReadsEveryKindOfFieldIncludingANestedSection) {
  const auto o = Read(
      "tracker:\n"
      "  gate_m: 0.25\n"
      "  lost_score: 0.5\n"
      "  window_min_m: 0.5\n"
      "  window_max_m: 2\n"
      "  threshold_db: -20\n"
      "  lost_steps: 5\n"
      "  max_order: 6\n"
      "  window_steps: 40\n"
      "  reassociate: false\n"
      "  model: ranges\n"
      "  weight: cauchy\n"
      "  motion:\n"
      "    accel_sigma_mps2: 2\n"
      "    max_accel_mps2: 4\n"
      "    enabled: false\n");

  EXPECT_EQ(o.gate_m, 0.25);
  EXPECT_EQ(o.lost_score, 0.5);
  EXPECT_EQ(o.window_min_m, 0.5);
  EXPECT_EQ(o.window_max_m, 2.0);
  EXPECT_EQ(o.threshold_db, -20.0);
  EXPECT_EQ(o.lost_steps, 5);
  EXPECT_EQ(o.max_order, 6);
  EXPECT_EQ(o.window_steps, 40U);
  EXPECT_FALSE(o.reassociate);
  EXPECT_EQ(o.model, TestModel::kRanges);
  EXPECT_EQ(o.weight, "cauchy");
  EXPECT_EQ(o.motion.accel_sigma_mps2, 2.0);
  EXPECT_EQ(o.motion.max_accel_mps2, 4.0);
  EXPECT_FALSE(o.motion.enabled);
}

TEST(ReadOptions, KeepsTheStructsDefaultsForAbsentKeys) {
  const auto o = Read("tracker:\n  lost_steps: 4\n");

  TestTrackerOptions expected;
  expected.lost_steps = 4;
  EXPECT_EQ(OptionsToJson(TestTrackerDescriptor(), o), OptionsToJson(TestTrackerDescriptor(), expected));
  EXPECT_EQ(o.motion.accel_sigma_mps2, 0.5);  // the outer struct's default of its section
}

TEST(ReadOptions, AppliesADerivedDefaultWhenTheKeyIsAbsentAndItsPhysicalKeysAreKnown) {
  const auto o = Read("tracker: {}\n", WalkerKeys());

  EXPECT_DOUBLE_EQ(o.gate_m, 0.5 * 0.1 + 2.0 * 0.07);
}

TEST(ReadOptions, KeepsTheStaticDefaultWhenAPhysicalKeyTheFormulaNeedsIsUnknown) {
  PhysicalKeys keys = WalkerKeys();
  keys.range_sigma_m.reset();

  const auto o = Read("tracker: {}\n", keys);

  EXPECT_EQ(o.gate_m, 0.3);
}

TEST(ReadOptions, PrefersAValueInTheFileToTheDerivedDefault) {
  const auto o = Read("tracker:\n  gate_m: 0.7\n", WalkerKeys());

  EXPECT_EQ(o.gate_m, 0.7);
}

TEST(ReadOptions, RejectsADerivedDefaultOutsideTheRangeNamingItsFormula) {
  PhysicalKeys keys = WalkerKeys();
  keys.speed_mps = 0.0;
  keys.range_sigma_m = 0.0;

  const std::string error = ErrorOf("tracker:\n  lost_steps: 4\n", keys);

  EXPECT_THAT(error, HasSubstr("test.yaml:2: tracker.gate_m: the derived default speed_mps * dt_s + 2 * "
                               "range_sigma_m gives 0 m is out of range, expected a number > 0 m"));
}

TEST(ReadOptions, RejectsAnOutOfRangeNumberWithFileLineKeyValueRangeAndUnit) {
  EXPECT_EQ(ErrorOf("tracker:\n  lost_steps: 4\n  motion:\n    accel_sigma_mps2: 0\n"),
            "test.yaml:4: tracker.motion.accel_sigma_mps2: 0 m/s^2 is out of range, expected a number > 0 m/s^2");
  EXPECT_EQ(ErrorOf("tracker:\n  lost_score: 1.5\n"),
            "test.yaml:2: tracker.lost_score: 1.5 is out of range, expected a number in [0, 1]");
}

TEST(ReadOptions, RejectsNanAndInfinityWithTheExpectedRangeAndUnit) {
  EXPECT_EQ(ErrorOf("tracker:\n  gate_m: .nan\n"), "test.yaml:2: tracker.gate_m: expected a number > 0 m, got '.nan'");
  EXPECT_EQ(ErrorOf("tracker:\n  threshold_db: -.inf\n"),
            "test.yaml:2: tracker.threshold_db: expected a number < 0 dB, got '-.inf'");
}

TEST(ReadOptions, RejectsAValueOfTheWrongTypeWithWhatTheKeyExpects) {
  EXPECT_EQ(ErrorOf("tracker:\n  gate_m: wide\n"), "test.yaml:2: tracker.gate_m: expected a number > 0 m, got 'wide'");
  EXPECT_EQ(ErrorOf("tracker:\n  gate_m: [1, 2]\n"),
            "test.yaml:2: tracker.gate_m: expected a number > 0 m, got a list of 2");
  EXPECT_EQ(ErrorOf("tracker:\n  lost_steps: 2.5\n"),
            "test.yaml:2: tracker.lost_steps: expected an integer >= 1 steps, got 2.5");
  EXPECT_EQ(ErrorOf("tracker:\n  reassociate: maybe\n"),
            "test.yaml:2: tracker.reassociate: expected true or false, got 'maybe'");
  EXPECT_EQ(ErrorOf("tracker:\n  model: wifi\n"),
            "test.yaml:2: tracker.model: 'wifi' is not a known choice, expected one of: cir, ranges");
  EXPECT_THAT(ErrorOf("tracker:\n  motion: 3\n"), HasSubstr("test.yaml:2: tracker.motion: expected a map of keys"));
}

TEST(ReadOptions, RejectsAnIntegerOutsideItsRangeOrItsMemberType) {
  EXPECT_EQ(ErrorOf("tracker:\n  max_order: 7\n"),
            "test.yaml:2: tracker.max_order: 7 is out of range, expected an integer in [0, 6]");
  EXPECT_EQ(ErrorOf("tracker:\n  lost_steps: 0\n"),
            "test.yaml:2: tracker.lost_steps: 0 steps is out of range, expected an integer >= 1 steps");
  EXPECT_THAT(ErrorOf("tracker:\n  lost_steps: 3e9\n"),
              HasSubstr("test.yaml:2: tracker.lost_steps: 3000000000 steps does not fit"));
  EXPECT_THAT(ErrorOf("tracker:\n  lost_steps: 1e30\n"), HasSubstr("test.yaml:2: tracker.lost_steps: expected an integer"));
}

TEST(ReadOptions, RejectsAnUnknownKeyNamingTheKnownOnes) {
  const std::string top = ErrorOf("tracker:\n  gate: 0.2\n");
  const std::string nested = ErrorOf("tracker:\n  motion:\n    accel_sigma: 1\n");

  EXPECT_THAT(top, HasSubstr("test.yaml:2: tracker.gate: unknown key"));
  EXPECT_THAT(top, HasSubstr("gate_m"));
  EXPECT_THAT(nested, HasSubstr("test.yaml:3: tracker.motion.accel_sigma: unknown key"));
  EXPECT_THAT(nested, HasSubstr("accel_sigma_mps2"));
}

TEST(ReadOptions, RejectsACrossFieldProblemAtTheKeyItNames) {
  EXPECT_EQ(ErrorOf("tracker:\n  window_min_m: 0.1\n  window_max_m: 0.05\n"),
            "test.yaml:3: tracker.window_max_m: 0.05 m must be >= window_min_m (0.1 m)");
  EXPECT_EQ(ErrorOf("tracker:\n  motion:\n    accel_sigma_mps2: 1\n    max_accel_mps2: 0.5\n"),
            "test.yaml:4: tracker.motion.max_accel_mps2: must be >= accel_sigma_mps2");
}

TEST(ReadOptions, ReadsARealOptionsStructWithItsCrossFieldCheck) {
  YamlMap root(LoadYamlString("relocalization:\n  search_radius_m: 100\n  search_step_m: 0.001\n", "r.yaml"), "",
               std::make_shared<YamlOrigins>("r.yaml"));
  methods::mint::RelocalizationOptions options;

  try {
    ReadOptions(root.Map("relocalization"), methods::mint::RelocalizationOptionsDescriptor(), {}, options);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "r.yaml:3: relocalization.search_step_m: 0.001 m must be at least search_radius_m / 200 (0.5 m)");
  }
}

TEST(ReadOptions, ReadsTheJsonOfTheEffectiveOptionsBackToTheSameValues) {
  TestTrackerOptions o;
  o.gate_m = 0.1 + 0.2;
  o.lost_score = 1.0 / 3.0;
  o.window_max_m = 1e-7 + 1.0;
  o.threshold_db = -123.456;
  o.lost_steps = 17;
  o.window_steps = 3;
  o.reassociate = false;
  o.model = TestModel::kRanges;
  o.weight = "cauchy";
  o.motion.accel_sigma_mps2 = 0.7;
  o.motion.enabled = false;
  const nlohmann::json json = OptionsToJson(TestTrackerDescriptor(), o);

  // JSON is YAML (flow style).
  const auto back = Read("tracker: " + json.dump() + "\n");

  EXPECT_EQ(OptionsToJson(TestTrackerDescriptor(), back), json);
  EXPECT_EQ(back.gate_m, o.gate_m);
  EXPECT_EQ(back.lost_score, o.lost_score);
  EXPECT_EQ(back.window_max_m, o.window_max_m);
  EXPECT_EQ(back.model, TestModel::kRanges);
  EXPECT_EQ(back.motion.accel_sigma_mps2, 0.7);
}

}  // namespace
}  // namespace mirage::io
