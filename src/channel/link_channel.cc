// SPDX-License-Identifier: MIT
#include "mirage/channel/link_channel.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mirage/core/constants.h"
#include "mirage/core/units.h"
#include "mirage/geometry/image_source.h"

namespace mirage::channel {

LinkPaths ComputeLinkPaths(const geometry::FloorPlan& plan, const Vec2& tx_m, const Vec2& rx_m, bool self,
                           const LinkPathOptions& options) {
  LinkPaths out;
  const auto sequences = geometry::VisibleImagePaths(plan, tx_m, rx_m, options.max_order);
  double first_reflection_m = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < sequences.size(); ++i) {
    const auto& walls = sequences[i];
    const double length_m = geometry::ComputeImagePath(plan, walls, tx_m, rx_m).length_m;
    double gain = 1.0;
    for (const int s : walls) gain *= plan.walls()[static_cast<std::size_t>(s)].reflection_coeff;
    if (self && walls.empty()) {
      gain = std::sqrt(core::DbToPowerRatio(options.self_coupling_db));  // the antenna coupling
    } else if (!walls.empty()) {
      first_reflection_m = std::min(first_reflection_m, length_m);
    }
    SpecularPath path;
    path.va_id = static_cast<int>(i);
    path.order = static_cast<int>(walls.size());
    path.delay_s = length_m / options.speed_mps;
    // Free-space amplitude (1 m reference), reflection losses and the carrier phase.
    path.amplitude = gain / length_m * std::polar(1.0, -2.0 * core::kPi * options.carrier_hz * path.delay_s);
    out.paths.push_back(path);
  }
  out.dm_reference_m = self ? first_reflection_m : (rx_m - tx_m).norm();
  if (!std::isfinite(out.dm_reference_m)) out.dm_reference_m = options.min_reference_m;
  return out;
}

}  // namespace mirage::channel
