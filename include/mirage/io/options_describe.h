// SPDX-License-Identifier: MIT
// Human-readable listings of an options struct, generated from its descriptor
// (core/options_descriptor.h): plain text for `mirage describe METHOD` and Markdown tables for
// docs/scenario.md. Each option shows its key path, type, unit, default (or the formula of its
// derived default), valid range and doc; the cross-field checks follow. No YAML involved.
#pragma once

#include <string>

#include "mirage/core/options_descriptor.h"

namespace mirage::io {

/// One block per option, depth first:
///
///   motion.accel_sigma_mps2  number, m/s^2
///       default: 1 m/s^2
///       valid:   a number > 0 m/s^2
///       Standard deviation of the white acceleration...
///
/// headed "name: type_name" and followed by the cross-field checks. Defaults are those of a
/// default-constructed struct (a section's defaults as its containing struct sets them).
std::string DescribeText(const core::OptionsDescriptorBase& descriptor, const std::string& name);

/// A Markdown section "## `name` (`type_name`)" with one table row per option (key, type, unit,
/// default, valid, meaning), the cross-field checks below it, then one "### `name.section`" table
/// per nested section.
std::string DescribeMarkdown(const core::OptionsDescriptorBase& descriptor, const std::string& name);

}  // namespace mirage::io
