// SPDX-License-Identifier: MIT
// The physical quantities of a scenario that option defaults may be derived from (ROADMAP.md,
// "Defaults that depend on noise or motion are derived from the physical keys"). Each is
// optional: a recording may not state its walker's speed, a live stream its step time. A
// derived default applies only when every key it needs is known; otherwise the struct's own
// default stays.
#pragma once

#include <optional>
#include <string_view>

namespace mirage::core {

/// One physical key, for declaring which keys a derived default needs.
enum class PhysicalKey {
  kRangeSigma,            ///< range_sigma_m
  kStepTime,              ///< dt_s
  kSpeed,                 ///< speed_mps
  kDetectionProbability,  ///< detection_probability
  kClutterRate,           ///< clutter_rate
};

/// The physical keys of one scenario; unknown ones are empty.
struct PhysicalKeys {
  /// Standard deviation of a range measurement (m), > 0.
  std::optional<double> range_sigma_m;
  /// Time between two steps (s), > 0.
  std::optional<double> dt_s;
  /// Speed of the walker (m/s), >= 0.
  std::optional<double> speed_mps;
  /// Probability that a path present in the channel is detected, in [0, 1].
  std::optional<double> detection_probability;
  /// Mean number of clutter ranges per sensor and step, >= 0.
  std::optional<double> clutter_rate;

  /// The value of `key`, empty when unknown.
  [[nodiscard]] std::optional<double> Get(PhysicalKey key) const {
    switch (key) {
      case PhysicalKey::kRangeSigma: return range_sigma_m;
      case PhysicalKey::kStepTime: return dt_s;
      case PhysicalKey::kSpeed: return speed_mps;
      case PhysicalKey::kDetectionProbability: return detection_probability;
      case PhysicalKey::kClutterRate: return clutter_rate;
    }
    return std::nullopt;
  }
};

/// The name of `key` as it appears in PhysicalKeys and in derived-default formulas ("dt_s").
constexpr std::string_view PhysicalKeyName(PhysicalKey key) {
  switch (key) {
    case PhysicalKey::kRangeSigma: return "range_sigma_m";
    case PhysicalKey::kStepTime: return "dt_s";
    case PhysicalKey::kSpeed: return "speed_mps";
    case PhysicalKey::kDetectionProbability: return "detection_probability";
    case PhysicalKey::kClutterRate: return "clutter_rate";
  }
  return "?";
}

}  // namespace mirage::core
