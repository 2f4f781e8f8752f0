// SPDX-License-Identifier: MIT
// The valid range of a numeric option: an interval whose ends are each closed, open or absent
// (unbounded). Every value must also be finite, so "> 0" excludes +inf and NaN.
#pragma once

#include <optional>
#include <string>

namespace mirage::core {

/// Upper bound of options that only have to be positive or non-negative (lengths, times,
/// standard deviations): large enough for any room, small enough that products of two such values
/// stay finite. The scenario readers' limit since the first loader (io's kHuge).
inline constexpr double kHugeOption = 1e9;
/// Lower bound of such options that must be positive: far below any meaningful length, time or
/// standard deviation, it keeps their squares and reciprocals finite.
inline constexpr double kTinyOption = 1e-9;

/// One end of a ValueRange.
struct RangeBound {
  double value = 0.0;
  /// true: the end belongs to the range (>=, <=); false: it does not (>, <).
  bool inclusive = true;
};

/// The finite values an option may take.
struct ValueRange {
  std::optional<RangeBound> lower;  ///< empty: no lower bound
  std::optional<RangeBound> upper;  ///< empty: no upper bound

  /// Any finite number.
  static ValueRange Finite() { return {}; }
  /// > lo.
  static ValueRange Above(double lo) { return {RangeBound{lo, false}, std::nullopt}; }
  /// >= lo.
  static ValueRange AtLeast(double lo) { return {RangeBound{lo, true}, std::nullopt}; }
  /// < hi.
  static ValueRange Below(double hi) { return {std::nullopt, RangeBound{hi, false}}; }
  /// <= hi.
  static ValueRange AtMost(double hi) { return {std::nullopt, RangeBound{hi, true}}; }
  /// [lo, hi].
  static ValueRange Closed(double lo, double hi) { return {RangeBound{lo, true}, RangeBound{hi, true}}; }
  /// (lo, hi].
  static ValueRange LeftOpen(double lo, double hi) { return {RangeBound{lo, false}, RangeBound{hi, true}}; }
  /// [lo, hi).
  static ValueRange RightOpen(double lo, double hi) { return {RangeBound{lo, true}, RangeBound{hi, false}}; }
  /// (lo, hi).
  static ValueRange Open(double lo, double hi) { return {RangeBound{lo, false}, RangeBound{hi, false}}; }
  /// [kTinyOption, kHugeOption]: a value that only has to be positive.
  static ValueRange Positive() { return Closed(kTinyOption, kHugeOption); }
  /// [0, kHugeOption]: a value that only has to be non-negative.
  static ValueRange NonNegative() { return Closed(0.0, kHugeOption); }

  /// True if value is finite and inside the range.
  [[nodiscard]] bool Contains(double value) const;

  /// The range as people write it: "> 0", ">= 1", "[0, 1]", "(0, 1]", "finite"; with a unit
  /// ("m") it follows each bound ("> 0 m", "[0, 1] m").
  [[nodiscard]] std::string Text(const std::string& unit = "") const;
};

/// A number in the shortest form that reads back to the same double ("0.1", "1.28e-07",
/// "nan", "inf").
std::string FormatNumber(double value);

/// value followed by " unit" when unit is not empty.
std::string WithUnit(const std::string& value, const std::string& unit);

}  // namespace mirage::core
