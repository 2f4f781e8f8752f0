// SPDX-License-Identifier: MIT
#include "mirage/pipeline/experiment.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

namespace mirage::pipeline {

Vec3 TrajectoryPositionAt(const TrajectorySpec& t, const geometry::TrajectorySample& s) {
  const double z_m = t.height_m + t.height_amplitude_m * std::sin(2.0 * std::numbers::pi * s.t_s / t.height_period_s);
  return {s.position_m.x(), s.position_m.y(), z_m};
}

MethodSpec BindMethod(const methods::MethodInfo& info, std::shared_ptr<const void> options) {
  const methods::MethodInfo* method = &info;
  MethodSpec spec;
  spec.name = info.name;
  spec.input = info.input;
  spec.joint = info.joint;
  spec.create = [method, options](const methods::World& world) { return method->create(options.get(), world); };
  if (info.links) {
    spec.links = [method, options](const methods::World& world) { return method->links(options.get(), world); };
  }
  if (info.start_sigma_m) spec.start_sigma_m = info.start_sigma_m(options.get());
  spec.options = std::move(options);
  return spec;
}

std::vector<std::string> Validate(const Experiment& e) {
  std::vector<std::string> problems;
  if (e.runs < 1) problems.push_back("runs must be >= 1");
  if (!e.method.create) problems.push_back("no method");
  if (e.in_plan.size() != e.plan.walls().size()) problems.push_back("in_plan must have one flag per wall");
  if (e.recording) {
    if (e.runs != 1) problems.push_back("recorded data are one run");
    return problems;
  }
  if (e.trajectories.empty()) problems.push_back("no trajectory");
  if (e.method.joint) {
    if (e.method.input == methods::MethodInput::kLinkCirs && !e.method.links) problems.push_back("a link method without links");
    if (e.method.input == methods::MethodInput::kLinkCirs && (e.channel_max_order < 0 || e.channel_max_order > 3)) {
      problems.push_back("the links' paths are enumerated up to order 3: channel max_order must be in [0, 3]");
    }
    if (e.agents < 0 || e.agents > static_cast<int>(e.trajectories.size())) {
      problems.push_back(fmt::format("agents must be in [0, {}] (the trajectories)", e.trajectories.size()));
    }
    for (const auto& t : e.trajectories) {
      if (t.dt_s != e.trajectories.front().dt_s) problems.push_back("the trajectories of a joint method must share dt_s");
    }
  }
  if (e.plan_error.biased_wall >= static_cast<int>(e.plan.walls().size()) ||
      (e.plan_error.biased_wall >= 0 && !e.in_plan[static_cast<std::size_t>(e.plan_error.biased_wall)])) {
    problems.push_back("the biased wall must be a wall of the given plan");
  }
  return problems;
}

core::PhysicalKeys PhysicalKeysOf(const Experiment& e) {
  core::PhysicalKeys keys;
  switch (e.measurement_model) {
    case MeasurementModel::kRanging:
      keys.range_sigma_m = e.ranging.range_sigma_m;
      keys.detection_probability = e.ranging.detection_probability;
      keys.clutter_rate = e.ranging.clutter_rate;
      break;
    case MeasurementModel::kAcoustic:
      // A stamp's noise as a range at the speed the estimator assumes.
      keys.range_sigma_m = e.medium.speed_mps * e.acoustic.stamp_sigma_s;
      keys.detection_probability = e.acoustic.detection_probability;
      keys.clutter_rate = e.acoustic.false_alarm_rate;
      break;
    case MeasurementModel::kUwbTdoa:
      // The noise of one reported difference takes the range noise's place.
      if (e.uwb_tdoa.sigma_m > 0.0) keys.range_sigma_m = e.uwb_tdoa.sigma_m;
      keys.detection_probability = e.uwb_tdoa.detection_probability;
      break;
    case MeasurementModel::kRangeLevel:
      keys.detection_probability = e.range_level.detection_probability;
      keys.clutter_rate = e.range_level.clutter_rate;
      break;
    case MeasurementModel::kRecorded:
      keys.range_sigma_m = e.recorded_range_sigma_m;
      keys.speed_mps = e.recorded_speed_mps;
      keys.detection_probability = e.recorded_detection_probability;
      keys.clutter_rate = e.recorded_clutter_rate;
      keys.dt_s = e.recorded_dt_s;
      if (!keys.dt_s && e.recording && e.recording->steps.size() > 1) {
        std::vector<double> intervals;
        for (std::size_t k = 1; k < e.recording->steps.size(); ++k) {
          intervals.push_back(e.recording->steps[k].t_s - e.recording->steps[k - 1].t_s);
        }
        std::nth_element(intervals.begin(), intervals.begin() + static_cast<long>(intervals.size() / 2), intervals.end());
        keys.dt_s = intervals[intervals.size() / 2];
      }
      return keys;
    case MeasurementModel::kCir:
      break;
  }
  if (!e.trajectories.empty()) {
    bool common_dt = true;
    double speed = 0.0;
    for (const auto& t : e.trajectories) {
      common_dt = common_dt && t.dt_s == e.trajectories.front().dt_s;
      speed = std::max(speed, t.speed_mps);
    }
    if (common_dt) keys.dt_s = e.trajectories.front().dt_s;
    keys.speed_mps = speed;
  }
  return keys;
}

}  // namespace mirage::pipeline
