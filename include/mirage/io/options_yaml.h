// SPDX-License-Identifier: MIT
// Reads a YAML section into an options struct through the struct's descriptor
// (core/options_descriptor.h): every key typed and range-checked with file, line, key path,
// value, expected range and unit in the message; derived defaults from the physical keys for
// absent keys; nested sections; unknown keys rejected; cross-field checks last.
#pragma once

#include "mirage/core/options_descriptor.h"
#include "mirage/core/physical_keys.h"
#include "mirage/io/yaml_reader.h"

namespace mirage::io {

/// ReadOptions() without the struct's type: `out` points to an object of the descriptor's struct.
void ReadOptionsObject(YamlMap& section, const core::OptionsDescriptorBase& descriptor, const core::PhysicalKeys& keys,
                       void* out);

/// Reads `section` into `out`, which keeps its values for absent keys (normally a
/// default-constructed T, i.e. the struct's defaults). For each field in declaration order:
/// - present: the value must have the field's type and range, else InputError
///   "file:line: section.key: 0 m/s^2 is out of range, expected a number > 0 m/s^2";
/// - absent with a derived default whose physical keys are all known: the derived value
///   (InputError if it falls outside the range);
/// - a section: read recursively (absent: an empty map, so its derived defaults apply too).
/// Then unknown keys are rejected, and the first problem of descriptor.Validate() (cross-field
/// checks included) is thrown against the key it names.
template <typename T>
void ReadOptions(YamlMap section, const core::OptionsDescriptor<T>& descriptor, const core::PhysicalKeys& keys, T& out) {
  ReadOptionsObject(section, descriptor, keys, &out);
}

}  // namespace mirage::io
