// SPDX-License-Identifier: MIT
// Physical and mathematical constants, SI units.
#pragma once

namespace mirage::core {

/// Speed of light in vacuum (m/s); radio propagation indoors is taken as vacuum speed.
inline constexpr double kSpeedOfLight_mps = 299'792'458.0;
/// Pi.
inline constexpr double kPi = 3.14159265358979323846;

}  // namespace mirage::core
