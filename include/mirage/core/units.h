// SPDX-License-Identifier: MIT
// Conversions between decibels and linear ratios.
#pragma once

#include <cmath>

namespace mirage::core {

/// Power ratio (linear) from decibels: 10^(db/10).
inline double DbToPowerRatio(double ratio_db) { return std::pow(10.0, ratio_db / 10.0); }
/// Decibels from a power ratio (linear); -inf for 0.
inline double PowerRatioToDb(double ratio) { return 10.0 * std::log10(ratio); }

}  // namespace mirage::core
