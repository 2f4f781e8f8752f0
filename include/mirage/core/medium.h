// SPDX-License-Identifier: MIT
// The propagation medium: the one place the signal speed comes from. Every simulator and every
// measurement model reads the speed from a Medium instead of a constant, so that the same code
// serves radio (UWB) and sound.
#pragma once

#include <cmath>
#include <string>

#include "mirage/core/constants.h"

namespace mirage::core {

/// What carries the signal.
enum class MediumKind {
  kRadio,  ///< electromagnetic waves indoors, taken at the vacuum speed of light
  kSound,  ///< sound in air; the speed follows from the temperature
};

/// A propagation medium and its signal speed.
struct Medium {
  MediumKind kind = MediumKind::kRadio;
  /// Signal speed (m/s), > 0.
  double speed_mps = kSpeedOfLight_mps;

  /// Radio: the vacuum speed of light (the refractive index of indoor air, 1.0003, shifts a 10 m
  /// range by 3 mm, below the resolution of the pulses simulated here).
  static Medium Radio() { return {MediumKind::kRadio, kSpeedOfLight_mps}; }

  /// Sound in dry air at theta_c degrees Celsius: 331.3 sqrt(1 + theta_c / 273.15) m/s (Bordoy
  /// 2020 Eq. 3.31; 343.2 m/s at 20 C). Humidity changes it by at most 0.6 % (Eq. 3.32), left out.
  static Medium Sound(double theta_c) { return {MediumKind::kSound, 331.3 * std::sqrt(1.0 + theta_c / 273.15)}; }

  /// Name for reports: "radio" or "sound".
  [[nodiscard]] std::string name() const { return kind == MediumKind::kRadio ? "radio" : "sound"; }
};

}  // namespace mirage::core
