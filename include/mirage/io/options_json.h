// SPDX-License-Identifier: MIT
// The effective options of a run as JSON, for the report: one key per field, nested objects for
// sections, through the struct's descriptor (core/options_descriptor.h).
#pragma once

#include <nlohmann/json.hpp>

#include "mirage/core/options_descriptor.h"

namespace mirage::io {

/// OptionsToJson() without the struct's type: `options` points to an object of the descriptor's
/// struct.
nlohmann::json OptionsObjectToJson(const core::OptionsDescriptorBase& descriptor, const void* options);

/// {"key": value, "section": {...}}: numbers as JSON numbers (SI, the unit is the key's suffix),
/// integers as integers, booleans, choices by name. The JSON text is valid YAML that ReadOptions()
/// reads back to the same values.
template <typename T>
nlohmann::json OptionsToJson(const core::OptionsDescriptor<T>& descriptor, const T& options) {
  return OptionsObjectToJson(descriptor, &options);
}

}  // namespace mirage::io
