// SPDX-License-Identifier: MIT
// Test helper of the end-to-end tests: a grid variant's summary by its name.
#pragma once

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/pipeline/summary.h"

namespace mirage::pipeline::testing {

/// The summary of the variant called `name` (fails the test and returns the first if none is).
inline const VariantSummary& FindVariant(const std::vector<VariantSummary>& summaries, const std::string& name) {
  for (const auto& v : summaries) {
    if (v.name == name) return v;
  }
  ADD_FAILURE() << "no variant " << name;
  return summaries.front();
}

}  // namespace mirage::pipeline::testing
