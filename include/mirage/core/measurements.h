// SPDX-License-Identifier: MIT
// Transitional name of the range-set record (records.h); the code still spells it AnchorRanges.
#pragma once

#include "mirage/core/records.h"

namespace mirage::core {

using AnchorRanges = RangeSet;

}  // namespace mirage::core
