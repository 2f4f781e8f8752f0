// SPDX-License-Identifier: MIT
// One range of the VA discovery with the agent position it was measured from (shared by the
// candidates of methods/slam/va_discovery and the sweep of methods/slam/va_sweep).
#pragma once

#include <optional>

#include "mirage/core/types.h"

namespace mirage::methods::slam {

/// One range used by a candidate, with the agent position it was measured from.
struct DiscoverySample {
  Vec2 agent_m = Vec2::Zero();
  double range_m = 0.0;
  std::optional<double> amplitude;
};

}  // namespace mirage::methods::slam
