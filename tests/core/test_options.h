// SPDX-License-Identifier: MIT
// A test-only options struct that uses every kind of descriptor field: numbers with open,
// closed and one-sided ranges, a derived default, integers, a boolean, an enum and a string
// choice, a nested section whose defaults the outer struct overrides, and cross-field checks at
// both levels. Shared by tests/core/options_descriptor_test.cc and tests/io/options_yaml_test.cc.
#pragma once

#include <string>
#include <vector>

#include "mirage/core/options_descriptor.h"

namespace mirage::test {

/// The nested section.
struct TestMotionOptions {
  double accel_sigma_mps2 = 1.0;
  double max_accel_mps2 = 3.0;
  bool enabled = true;
};

enum class TestModel { kCir, kRanges };

/// The outer struct; every default is inside its range.
struct TestTrackerOptions {
  double gate_m = 0.3;  // derived: speed_mps * dt_s + 2 * range_sigma_m
  double lost_score = 0.4;
  double window_min_m = 0.9;
  double window_max_m = 1.0;
  double threshold_db = -30.0;
  int lost_steps = 3;
  int max_order = 2;
  std::size_t window_steps = 10;
  bool reassociate = true;
  TestModel model = TestModel::kCir;
  std::string weight = "huber";
  // Not the nested struct's own default (1.0): the outer struct's default is the one that counts.
  TestMotionOptions motion{.accel_sigma_mps2 = 0.5};
};

inline const core::OptionsDescriptor<TestMotionOptions>& TestMotionDescriptor() {
  static const auto descriptor = [] {
    using M = TestMotionOptions;
    core::OptionsDescriptor<M> d("test::TestMotionOptions");
    d.Number(&M::accel_sigma_mps2, {.key = "accel_sigma_mps2",
                                    .unit = "m/s^2",
                                    .range = core::ValueRange::Above(0.0),
                                    .doc = "White acceleration std."});
    d.Number(&M::max_accel_mps2, {.key = "max_accel_mps2",
                                  .unit = "m/s^2",
                                  .range = core::ValueRange::Above(0.0),
                                  .doc = "Largest acceleration."});
    d.Boolean(&M::enabled, {.key = "enabled", .doc = "Use the motion model."});
    d.Check("max_accel_mps2 >= accel_sigma_mps2", [](const M& o) -> std::vector<std::string> {
      if (o.max_accel_mps2 < o.accel_sigma_mps2) return {"max_accel_mps2: must be >= accel_sigma_mps2"};
      return {};
    });
    return d;
  }();
  return descriptor;
}

inline const core::OptionsDescriptor<TestTrackerOptions>& TestTrackerDescriptor() {
  static const auto descriptor = [] {
    using T = TestTrackerOptions;
    using core::PhysicalKey;
    core::OptionsDescriptor<T> d("test::TestTrackerOptions");
    d.Number(&T::gate_m,
             {.key = "gate_m",
              .unit = "m",
              .range = core::ValueRange::Above(0.0),
              .doc = "Association gate | half-width.",
              .derived = core::DerivedDefault{
                  .formula = "speed_mps * dt_s + 2 * range_sigma_m",
                  .needs = {PhysicalKey::kSpeed, PhysicalKey::kStepTime, PhysicalKey::kRangeSigma},
                  .compute = [](const core::PhysicalKeys& k) { return *k.speed_mps * *k.dt_s + 2.0 * *k.range_sigma_m; }}});
    d.Number(&T::lost_score,
             {.key = "lost_score", .range = core::ValueRange::Closed(0.0, 1.0), .doc = "Score below which a step is lost."});
    d.Number(&T::window_min_m,
             {.key = "window_min_m", .unit = "m", .range = core::ValueRange::AtLeast(0.0), .doc = "Shortest window."});
    d.Number(&T::window_max_m,
             {.key = "window_max_m", .unit = "m", .range = core::ValueRange::AtLeast(0.0), .doc = "Longest window."});
    d.Number(&T::threshold_db,
             {.key = "threshold_db", .unit = "dB", .range = core::ValueRange::Below(0.0), .doc = "Detection threshold."});
    d.Integer(&T::lost_steps, {.key = "lost_steps",
                               .unit = "steps",
                               .range = core::ValueRange::AtLeast(1.0),
                               .doc = "Lost steps before a search."});
    d.Integer(&T::max_order,
              {.key = "max_order", .range = core::ValueRange::Closed(0.0, 6.0), .doc = "Highest VA order."});
    d.Integer(&T::window_steps,
              {.key = "window_steps", .range = core::ValueRange::AtLeast(3.0), .doc = "Steps in the window."});
    d.Boolean(&T::reassociate, {.key = "reassociate", .doc = "Associate again at the LOS estimate."});
    d.Choice(&T::model, {.key = "model", .doc = "Measurement model."},
             std::vector<std::pair<std::string, TestModel>>{{"cir", TestModel::kCir}, {"ranges", TestModel::kRanges}});
    d.Choice(&T::weight, {.key = "weight", .doc = "Robust weight."}, {"huber", "cauchy"});
    d.Section(&T::motion, {.key = "motion", .doc = "Motion model."}, TestMotionDescriptor());
    d.Check("window_max_m >= window_min_m", [](const T& o) -> std::vector<std::string> {
      if (o.window_max_m < o.window_min_m) {
        return {"window_max_m: " + core::FormatNumber(o.window_max_m) + " m must be >= window_min_m (" +
                core::FormatNumber(o.window_min_m) + " m)"};
      }
      return {};
    });
    return d;
  }();
  return descriptor;
}

}  // namespace mirage::test
