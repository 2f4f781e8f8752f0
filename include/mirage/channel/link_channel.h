// SPDX-License-Identifier: MIT
// The specular paths of a link between two points of a floor plan by the image-source model, for
// links whose transmitter moves (an agent's own channel, the channel between two agents; Kulmer
// et al. Sec. II-B): every wall sequence up to max_order whose path exists, with the free-space
// amplitude, the walls' reflection losses and the carrier phase, and the distance from which the
// diffuse multipath is referred (Eq. 1: it starts with the first arrival).
#pragma once

#include <vector>

#include "mirage/channel/specular_path.h"
#include "mirage/core/types.h"
#include "mirage/geometry/floor_plan.h"

namespace mirage::channel {

/// Paths of one link and their diffuse-multipath reference.
struct LinkPaths {
  std::vector<SpecularPath> paths;  ///< va_id is the index of the path's wall sequence
  /// The distance the diffuse multipath is referred to (m): the line-of-sight distance for a
  /// link between two places (blocked or not, as for MINT's anchors); for an agent's own channel,
  /// which has no line of sight worth the name, the first reflection.
  double dm_reference_m = 0.0;
};

/// Options of a link's paths.
struct LinkPathOptions {
  int max_order = 2;               ///< highest reflection order, in [0, 3]
  double carrier_hz = 7.0e9;       ///< carrier frequency (Hz), for the phase
  double speed_mps = 0.0;          ///< signal speed (m/s), > 0
  /// Energy of the transmit-receive antenna coupling of an agent's own channel, relative to a
  /// free-space path of the antenna spacing (dB).
  double self_coupling_db = -20.0;
  /// Smallest DM reference (m), for an own channel with no reflection at all.
  double min_reference_m = 0.1;
};

/// The paths from tx_m to rx_m over `plan`. `self`: both antennas on one agent (the direct
/// path is the antenna coupling).
LinkPaths ComputeLinkPaths(const geometry::FloorPlan& plan, const Vec2& tx_m, const Vec2& rx_m, bool self,
                           const LinkPathOptions& options);

}  // namespace mirage::channel
