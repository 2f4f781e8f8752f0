// SPDX-License-Identifier: MIT
#include "mirage/channel/specular_path.h"

#include <algorithm>
#include <cmath>

#include "mirage/core/constants.h"
#include "mirage/geometry/visibility.h"

namespace mirage::channel {

std::vector<SpecularPath> ComputeSpecularPaths(const geometry::VirtualAnchorSet& vas, int anchor_index,
                                               const geometry::FloorPlan& plan, const Vec2& agent_m,
                                               double carrier_hz, const core::Medium& medium) {
  std::vector<SpecularPath> paths;
  for (const int id : geometry::VisibleVirtualAnchors(vas, anchor_index, plan, agent_m)) {
    const auto& va = vas[id];
    // Paths shorter than 1 cm are outside every model here (near field); clamp the 1/d.
    const double distance_m = std::max((va.position_m - agent_m).norm(), 0.01);
    SpecularPath path;
    path.va_id = id;
    path.order = va.order;
    path.delay_s = distance_m / medium.speed_mps;
    path.amplitude = va.reflection_gain / distance_m * std::polar(1.0, -2.0 * core::kPi * carrier_hz * path.delay_s);
    paths.push_back(path);
  }
  return paths;
}

}  // namespace mirage::channel
