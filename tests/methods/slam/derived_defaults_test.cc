// SPDX-License-Identifier: MIT
// The derived defaults of the SLAM and MINT options (core/derived_defaults.h): at the seminar
// room's physical keys they are the thesis's (and mirage's seminar-tuned) values bit for bit, so
// the seminar examples' results do not change; elsewhere they scale with the keys as their
// formulas say.
#include <cmath>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "mirage/core/options_descriptor.h"
#include "mirage/core/physical_keys.h"
#include "mirage/methods/mint/mint_tracker.h"
#include "mirage/methods/slam/slam_tracker.h"

namespace mirage::methods {
namespace {

using core::OptionField;
using core::PhysicalKeys;

// Every field with a derived default, by key path, with the struct's own default.
struct Derived {
  const OptionField* field;
  double struct_default;
};
std::map<std::string, Derived> DerivedFields(const core::OptionsDescriptorBase& d) {
  std::map<std::string, Derived> out;
  d.ForEachField(d.default_object(), [&](const std::string& path, const OptionField& f, const void* owner) {
    if (f.kind() == core::OptionKind::kNumber && f.derived()) out[path] = {&f, std::get<double>(f.Get(owner))};
  });
  return out;
}

// What PhysicalKeysOf gives the seminar examples: the CIR scenarios state no range noise (it
// follows from each path's SINR), the trajectories walk 0.5 m/s at 0.1 s.
PhysicalKeys SeminarKeys() {
  PhysicalKeys k;
  k.speed_mps = 0.5;
  k.dt_s = 0.1;
  return k;
}

// The hold-out benchmark (examples/slam_holdout.yaml).
PhysicalKeys HoldoutKeys() {
  PhysicalKeys k;
  k.range_sigma_m = 0.1;
  k.speed_mps = 0.01;
  k.dt_s = 1.0;
  k.detection_probability = 0.95;
  k.clutter_rate = 1.0;
  return k;
}

double At(const std::map<std::string, Derived>& fields, const std::string& path, const PhysicalKeys& keys) {
  const auto it = fields.find(path);
  EXPECT_NE(it, fields.end()) << path << " has no derived default";
  if (it == fields.end()) return std::nan("");
  const auto v = it->second.field->derived()->Evaluate(keys);
  EXPECT_TRUE(v.has_value()) << path;
  return v.value_or(std::nan(""));
}

class DerivedDefaults : public ::testing::TestWithParam<const core::OptionsDescriptorBase*> {};

TEST_P(DerivedDefaults, AtTheSeminarKeysEqualTheStructDefaultsExactly) {
  int evaluated = 0;
  for (const auto& [path, d] : DerivedFields(*GetParam())) {
    PhysicalKeys keys = SeminarKeys();
    // The range-level seminar example states detection probability and clutter rate too.
    keys.detection_probability = 0.95;
    keys.clutter_rate = 1.0;
    const auto v = d.field->derived()->Evaluate(keys);
    if (!v) continue;  // needs range_sigma_m, which the seminar examples do not state
    ++evaluated;
    EXPECT_EQ(*v, d.struct_default) << path << " = " << d.field->derived()->formula;
  }
  EXPECT_GE(evaluated, 2);
}

TEST_P(DerivedDefaults, EveryFormulaNeedsOnlyPhysicalKeysAndEvaluatesWhenAllAreKnown) {
  for (const auto& [path, d] : DerivedFields(*GetParam())) {
    const auto v = d.field->derived()->Evaluate(HoldoutKeys());
    ASSERT_TRUE(v.has_value()) << path;
    EXPECT_TRUE(std::isfinite(*v) && *v > 0.0) << path;
    EXPECT_FALSE(d.field->CheckValue(*v).has_value()) << path;
  }
}

INSTANTIATE_TEST_SUITE_P(SlamAndMint, DerivedDefaults,
                         ::testing::Values(&slam::SlamOptionsDescriptor(), &mint::MintOptionsDescriptor()),
                         // Named by method, not by the pointer's value: ctest's names stay the same
                         // from build to build.
                         [](const auto& param_info) { return param_info.index == 0 ? std::string("slam") : std::string("mint"); });

TEST(SlamDerivedDefaults, SpeedDerivedLimitsAreTheSeminarValues) {
  const auto f = DerivedFields(slam::SlamOptionsDescriptor());
  const PhysicalKeys k = SeminarKeys();
  // Lafer Tab. 3.1: v_max 0.5 m/s; mirage's seminar-tuned limits in steps of 0.1 s.
  EXPECT_EQ(At(f, "initial_velocity_sigma_mps", k), 0.5);
  EXPECT_EQ(At(f, "max_speed_mps", k), 1.5);
  EXPECT_EQ(At(f, "discovery.candidate_timeout_s", k), 2.0);   // 20 steps
  EXPECT_EQ(At(f, "discovery.candidate_max_age_s", k), 15.0);  // 150 steps
  EXPECT_EQ(At(f, "discovery.sweep.window_s", k), 6.0);        // 60 steps
  EXPECT_EQ(At(f, "recovery.floor_plan_watch_s", k), 1.0);     // 10 steps
  EXPECT_EQ(At(f, "recovery.follow_gate_m", k), 0.3);
}

TEST(SlamDerivedDefaults, RangeNoiseLimitsScaleLinearlyWithTheNoise) {
  const auto f = DerivedFields(slam::SlamOptionsDescriptor());
  PhysicalKeys a = HoldoutKeys();
  PhysicalKeys b = a;
  b.range_sigma_m = 2.0 * *a.range_sigma_m;
  for (const char* path :
       {"range_sigma_m", "discovery.max_agent_sigma_m", "discovery.max_fit_rms_m", "discovery.verify_fit_rms_m",
        "discovery.verify_residual_cap_m", "discovery.verify_max_sigma_m", "discovery.verify_far_fit_rms_m",
        "discovery.sweep.gate_m", "recovery.match_tolerance_m", "recovery.circle_slack_m", "variance.default_sigma_m"}) {
    EXPECT_DOUBLE_EQ(At(f, path, b), 2.0 * At(f, path, a)) << path;
  }
  EXPECT_DOUBLE_EQ(At(f, "discovery.verify_residual_cap_m", a), 0.5);  // 5 sigma
}

TEST(SlamDerivedDefaults, WalkingTimesScaleInverselyWithSpeed) {
  const auto f = DerivedFields(slam::SlamOptionsDescriptor());
  const PhysicalKeys k = HoldoutKeys();  // 0.01 m/s: 50 times slower than the seminar room
  EXPECT_DOUBLE_EQ(At(f, "discovery.candidate_timeout_s", k), 100.0);
  EXPECT_DOUBLE_EQ(At(f, "discovery.candidate_max_age_s", k), 750.0);
  EXPECT_DOUBLE_EQ(At(f, "discovery.sweep.window_s", k), 300.0);
  EXPECT_DOUBLE_EQ(At(f, "recovery.floor_plan_watch_s", k), 50.0);
  EXPECT_DOUBLE_EQ(At(f, "max_speed_mps", k), 0.03);
}

TEST(SlamDerivedDefaults, GatesAddOneStepOfMotionToTheNoise) {
  const auto f = DerivedFields(slam::SlamOptionsDescriptor());
  const PhysicalKeys k = HoldoutKeys();
  EXPECT_DOUBLE_EQ(At(f, "cutoff_m", k), 3 * 0.1 + 0.01);
  EXPECT_DOUBLE_EQ(At(f, "discovery.group_gate_m", k), 0.01 + 2 * std::sqrt(2.0) * 0.1);
  EXPECT_DOUBLE_EQ(At(f, "recovery.follow_gate_m", k), 0.01 + 0.25);
}

TEST(SlamDerivedDefaults, RetiredStepKeysNameTheirReplacements) {
  std::map<std::string, std::string> retired;
  slam::SlamOptionsDescriptor().ForEachField(
      slam::SlamOptionsDescriptor().default_object(),
      [&](const std::string& path, const OptionField& field, const void*) {
        if (field.kind() != core::OptionKind::kSection) return;
        for (const auto& r : field.section()->retired()) retired[path + "." + r.key] = path + "." + r.replacement;
      });
  EXPECT_EQ(retired["discovery.candidate_timeout_steps"], "discovery.candidate_timeout_s");
  EXPECT_EQ(retired["discovery.candidate_max_age_steps"], "discovery.candidate_max_age_s");
  EXPECT_EQ(retired["discovery.sweep.window_steps"], "discovery.sweep.window_s");
  EXPECT_EQ(retired["recovery.floor_plan_watch_steps"], "recovery.floor_plan_watch_s");
}

}  // namespace
}  // namespace mirage::methods
