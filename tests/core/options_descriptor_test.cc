// SPDX-License-Identifier: MIT
// Options descriptors: ranges as text, validation of every field kind (nested sections and
// cross-field checks included) with key, value, unit and expected range in each problem,
// type-erased access, the field walk, and derived defaults.
#include "mirage/core/options_descriptor.h"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/test_options.h"

namespace mirage::core {
namespace {

using test::TestModel;
using test::TestTrackerDescriptor;
using test::TestTrackerOptions;

TEST(ValueRange, TextReadsAsPeopleWriteRanges) {
  EXPECT_EQ(ValueRange::Above(0.0).Text("m"), "> 0 m");
  EXPECT_EQ(ValueRange::AtLeast(1.0).Text(), ">= 1");
  EXPECT_EQ(ValueRange::Below(0.0).Text("dB"), "< 0 dB");
  EXPECT_EQ(ValueRange::AtMost(0.5).Text(), "<= 0.5");
  EXPECT_EQ(ValueRange::Closed(0.0, 1.0).Text(), "[0, 1]");
  EXPECT_EQ(ValueRange::LeftOpen(0.0, 1.0).Text(), "(0, 1]");
  EXPECT_EQ(ValueRange::RightOpen(0.0, 1.0).Text(), "[0, 1)");
  EXPECT_EQ(ValueRange::Open(0.0, 1e-9).Text("s"), "(0, 1e-09) s");
  EXPECT_EQ(ValueRange::Finite().Text(), "finite");
}

TEST(ValueRange, ContainsRespectsOpenAndClosedEndsAndRejectsNonFiniteValues) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(ValueRange::Above(0.0).Contains(0.0));
  EXPECT_TRUE(ValueRange::Above(0.0).Contains(1e-300));
  EXPECT_TRUE(ValueRange::AtLeast(0.0).Contains(0.0));
  EXPECT_TRUE(ValueRange::Closed(0.0, 1.0).Contains(1.0));
  EXPECT_FALSE(ValueRange::RightOpen(0.0, 1.0).Contains(1.0));
  EXPECT_FALSE(ValueRange::LeftOpen(0.0, 1.0).Contains(0.0));
  EXPECT_FALSE(ValueRange::Above(0.0).Contains(inf));
  EXPECT_FALSE(ValueRange::Finite().Contains(nan));
  EXPECT_TRUE(ValueRange::Finite().Contains(-1e300));
}

TEST(ValueRange, PositiveAndNonNegativeStopAtTheSanityBound) {
  EXPECT_FALSE(ValueRange::Positive().Contains(0.0));
  EXPECT_TRUE(ValueRange::Positive().Contains(kTinyOption));
  EXPECT_TRUE(ValueRange::Positive().Contains(kHugeOption));
  EXPECT_FALSE(ValueRange::Positive().Contains(2.0 * kHugeOption));
  EXPECT_TRUE(ValueRange::NonNegative().Contains(0.0));
  EXPECT_FALSE(ValueRange::NonNegative().Contains(-kTinyOption));
  EXPECT_EQ(ValueRange::NonNegative().Text("m"), "[0, 1e+09] m");
}

TEST(FormatNumber, GivesTheShortestTextThatReadsBackToTheSameDouble) {
  EXPECT_EQ(FormatNumber(0.1), "0.1");
  EXPECT_EQ(FormatNumber(128e-9), "1.28e-07");
  EXPECT_EQ(FormatNumber(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(FormatNumber(std::numeric_limits<double>::quiet_NaN()), "nan");
}

TEST(OptionsDescriptor, AcceptsTheStructsDefaults) {
  EXPECT_TRUE(TestTrackerDescriptor().Validate(TestTrackerOptions{}).empty());
}

using Problems = std::vector<std::string>;

// The problems of the default options after `change`.
template <typename Change>
Problems ProblemsAfter(Change change) {
  TestTrackerOptions o;
  change(o);
  return TestTrackerDescriptor().Validate(o);
}

TEST(OptionsDescriptor, NamesKeyValueUnitAndExpectedRangeOfAnOutOfRangeNumber) {
  const auto problems = ProblemsAfter([](TestTrackerOptions& o) {
    o.gate_m = 0.0;
    o.lost_score = 1.5;
  });

  EXPECT_EQ(problems, (Problems{"gate_m: 0 m is out of range, expected a number > 0 m",
                                "lost_score: 1.5 is out of range, expected a number in [0, 1]"}));
}

TEST(OptionsDescriptor, RejectsNanAndInfinityEvenWithoutBounds) {
  const auto problems = ProblemsAfter([](TestTrackerOptions& o) {
    o.threshold_db = std::numeric_limits<double>::quiet_NaN();
    o.window_max_m = std::numeric_limits<double>::infinity();
  });

  EXPECT_EQ(problems, (Problems{"window_max_m: inf m is not a finite number, expected a number >= 0 m",
                                "threshold_db: nan dB is not a finite number, expected a number < 0 dB"}));
}

TEST(OptionsDescriptor, ChecksIntegerRangesAndTheMemberTypesLimits) {
  const OptionField& window_steps = *TestTrackerDescriptor().Find("window_steps");

  const auto problems = ProblemsAfter([](TestTrackerOptions& o) {
    o.lost_steps = 0;
    o.max_order = 7;
  });
  // window_steps is a std::size_t: a negative value cannot be stored.
  const auto negative = window_steps.CheckValue(std::int64_t{-1});

  EXPECT_EQ(problems, (Problems{"lost_steps: 0 steps is out of range, expected an integer >= 1 steps",
                                "max_order: 7 is out of range, expected an integer in [0, 6]"}));
  ASSERT_TRUE(negative.has_value());
  EXPECT_NE(negative->find("does not fit"), std::string::npos) << *negative;
  EXPECT_FALSE(window_steps.CheckValue(std::int64_t{3}).has_value());
}

TEST(OptionsDescriptor, PrefixesTheProblemsOfANestedSectionWithItsKey) {
  const auto problems = ProblemsAfter([](TestTrackerOptions& o) { o.motion.accel_sigma_mps2 = -1.0; });

  EXPECT_EQ(problems, (Problems{"motion.accel_sigma_mps2: -1 m/s^2 is out of range, expected a number > 0 m/s^2"}));
}

TEST(OptionsDescriptor, RunsTheCrossFieldChecksOfEveryLevel) {
  const auto problems = ProblemsAfter([](TestTrackerOptions& o) {
    o.window_min_m = 2.0;
    o.motion.max_accel_mps2 = 0.1;
  });

  EXPECT_EQ(problems, (Problems{"motion.max_accel_mps2: must be >= accel_sigma_mps2",
                                "window_max_m: 1 m must be >= window_min_m (2 m)"}));
}

TEST(OptionsDescriptor, ReportsAnUnnamedEnumValueAndAStringThatIsNotAChoice) {
  const auto problems = ProblemsAfter([](TestTrackerOptions& o) {
    o.model = static_cast<TestModel>(7);
    o.weight = "tukey";
  });

  EXPECT_EQ(problems, (Problems{"model: '(unnamed value 7)' is not a known choice, expected one of: cir, ranges",
                                "weight: 'tukey' is not a known choice, expected one of: huber, cauchy"}));
}

TEST(OptionField, ReadsAndWritesTheBoundMembersWithoutKnowingTheirStruct) {
  const auto& d = TestTrackerDescriptor();
  TestTrackerOptions o;
  void* erased = &o;

  d.Find("gate_m")->Set(erased, 0.25);
  d.Find("window_steps")->Set(erased, std::int64_t{12});
  d.Find("reassociate")->Set(erased, false);
  d.Find("model")->Set(erased, std::string("ranges"));
  d.Find("weight")->Set(erased, std::string("cauchy"));
  const OptionField& motion = *d.Find("motion");
  motion.section()->Find("accel_sigma_mps2")->Set(motion.SectionIn(erased), 2.5);

  EXPECT_EQ(o.gate_m, 0.25);
  EXPECT_EQ(o.window_steps, 12U);
  EXPECT_FALSE(o.reassociate);
  EXPECT_EQ(o.model, TestModel::kRanges);
  EXPECT_EQ(o.weight, "cauchy");
  EXPECT_EQ(o.motion.accel_sigma_mps2, 2.5);
  EXPECT_EQ(std::get<std::string>(d.Find("model")->Get(erased)), "ranges");
  EXPECT_EQ(std::get<std::int64_t>(d.Find("lost_steps")->Get(erased)), 3);
}

TEST(OptionsDescriptor, VisitsEachSectionBeforeItsFieldsWithFullKeyPaths) {
  std::vector<std::string> paths;
  double motion_accel_default = 0.0;

  TestTrackerDescriptor().ForEach(TestTrackerDescriptor().defaults(), [&](const std::string& path,
                                                                          const OptionField& field, const void* owner) {
    paths.push_back(path);
    if (path == "motion.accel_sigma_mps2") motion_accel_default = std::get<double>(field.Get(owner));
  });

  const std::vector<std::string> expected = {
      "gate_m",      "lost_score",  "window_min_m", "window_max_m",           "threshold_db",
      "lost_steps",  "max_order",   "window_steps", "reassociate",            "model",
      "weight",      "motion",      "motion.accel_sigma_mps2", "motion.max_accel_mps2", "motion.enabled"};
  EXPECT_EQ(paths, expected);
  // The outer struct's default of the nested member, not TestMotionOptions' own 1.0.
  EXPECT_EQ(motion_accel_default, 0.5);
}

TEST(DerivedDefault, EvaluatesOnlyWhenEveryKeyItNeedsIsKnown) {
  const DerivedDefault& derived = *TestTrackerDescriptor().Find("gate_m")->derived();
  PhysicalKeys keys;
  keys.speed_mps = 0.5;
  keys.dt_s = 0.1;

  EXPECT_FALSE(derived.Evaluate(keys).has_value());
  keys.range_sigma_m = 0.07;
  ASSERT_TRUE(derived.Evaluate(keys).has_value());
  EXPECT_DOUBLE_EQ(*derived.Evaluate(keys), 0.5 * 0.1 + 2.0 * 0.07);
  EXPECT_EQ(derived.NeedsText(), "speed_mps, dt_s, range_sigma_m");
}

}  // namespace
}  // namespace mirage::core
