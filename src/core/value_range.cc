// SPDX-License-Identifier: MIT
#include "mirage/core/value_range.h"

#include <charconv>
#include <cmath>

namespace mirage::core {

bool ValueRange::Contains(double value) const {
  if (!std::isfinite(value)) return false;
  if (lower && (lower->inclusive ? value < lower->value : value <= lower->value)) return false;
  if (upper && (upper->inclusive ? value > upper->value : value >= upper->value)) return false;
  return true;
}

std::string ValueRange::Text(const std::string& unit) const {
  if (lower && upper) {
    return WithUnit(std::string(lower->inclusive ? "[" : "(") + FormatNumber(lower->value) + ", " +
                        FormatNumber(upper->value) + (upper->inclusive ? "]" : ")"),
                    unit);
  }
  if (lower) return WithUnit(std::string(lower->inclusive ? ">= " : "> ") + FormatNumber(lower->value), unit);
  if (upper) return WithUnit(std::string(upper->inclusive ? "<= " : "< ") + FormatNumber(upper->value), unit);
  return "finite";
}

std::string FormatNumber(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0.0 ? "inf" : "-inf";
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

std::string WithUnit(const std::string& value, const std::string& unit) {
  return unit.empty() ? value : value + " " + unit;
}

}  // namespace mirage::core
