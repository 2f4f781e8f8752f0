// SPDX-License-Identifier: MIT
// Derived defaults (options_descriptor.h) that many options share, each a physical quantity of
// the scenario (physical_keys.h) times a stated constant: k standard deviations of one range,
// the time the walker takes for a distance, one step of motion plus a margin. The formula text
// is what `mirage describe` prints.
#pragma once

#include <string>

#include "mirage/core/options_descriptor.h"
#include "mirage/core/physical_keys.h"
#include "mirage/core/value_range.h"

namespace mirage::core {

/// "k * name", or "name" when k is 1.
inline std::string TimesText(double k, const std::string& name) {
  return k == 1.0 ? name : FormatNumber(k) + " * " + name;
}

/// k * range_sigma_m: a gate or a residual bound of k standard deviations of one range.
inline DerivedDefault RangeSigmas(double k) {
  return {.formula = TimesText(k, "range_sigma_m"),
          .needs = {PhysicalKey::kRangeSigma},
          .compute = [k](const PhysicalKeys& keys) { return k * *keys.range_sigma_m; }};
}

/// distance_m / speed_mps (s): the time the walker takes for distance_m, for limits that are
/// about how far the agent has walked (what is visible changes with position, not with time).
inline DerivedDefault WalkingTime(double distance_m) {
  return {.formula = FormatNumber(distance_m) + " m / speed_mps",
          .needs = {PhysicalKey::kSpeed},
          .compute = [distance_m](const PhysicalKeys& keys) { return distance_m / *keys.speed_mps; }};
}

/// range_sigma_m / speed_mps (s): the time in which the walker moves one standard deviation of a
/// range, for windows within which its motion stays below the noise; at most max_s (a walker at
/// rest would make it infinite).
inline DerivedDefault RangeSigmaWalkingTime(double max_s) {
  return {.formula = "range_sigma_m / speed_mps, at most " + FormatNumber(max_s) + " s",
          .needs = {PhysicalKey::kRangeSigma, PhysicalKey::kSpeed},
          .compute = [max_s](const PhysicalKeys& keys) {
            return *keys.speed_mps * max_s > *keys.range_sigma_m ? *keys.range_sigma_m / *keys.speed_mps : max_s;
          }};
}

/// speed_mps * dt_s + margin_m (m): one step of motion plus a margin.
inline DerivedDefault StepLengthPlus(double margin_m) {
  return {.formula = "speed_mps * dt_s + " + FormatNumber(margin_m) + " m",
          .needs = {PhysicalKey::kSpeed, PhysicalKey::kStepTime},
          .compute = [margin_m](const PhysicalKeys& keys) { return *keys.speed_mps * *keys.dt_s + margin_m; }};
}

/// k * speed_mps (m/s): a speed limit k times the walker's speed.
inline DerivedDefault SpeedTimes(double k) {
  return {.formula = TimesText(k, "speed_mps"),
          .needs = {PhysicalKey::kSpeed},
          .compute = [k](const PhysicalKeys& keys) { return k * *keys.speed_mps; }};
}

}  // namespace mirage::core
