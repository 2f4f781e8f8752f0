// SPDX-License-Identifier: MIT
// Deterministic (specular) multipath components: one per VA visible from the agent, with delay
// d/c (c the medium's signal speed), free-space amplitude, the product of the walls' reflection coefficients and the carrier
// phase (Lafer 2014 Eq. 2.2, 2.5; digest Sec. 6.2 item 3).
#pragma once

#include <vector>

#include "mirage/core/medium.h"
#include "mirage/core/types.h"
#include "mirage/geometry/floor_plan.h"
#include "mirage/geometry/virtual_anchor.h"

namespace mirage::channel {

/// One specular path between the agent and one physical anchor.
struct SpecularPath {
  int va_id = 0;         ///< id of the VA in its VirtualAnchorSet
  int order = 0;         ///< reflection order (0 = LOS)
  double delay_s = 0.0;  ///< propagation delay |agent - VA| / c (s)
  /// Complex amplitude: gain * (1 m / d) * e^{-j 2 pi f_c tau}, normalised so that the LOS at
  /// 1 m has unit energy.
  Complex amplitude;
};

/// The specular paths of all VAs of one anchor visible from agent_m, by ray tracing.
/// @param agent_m    agent position (m).
/// @param carrier_hz carrier frequency f_c of the phase (Hz).
/// @param medium     carries the signal: delay = distance / medium.speed_mps.
std::vector<SpecularPath> ComputeSpecularPaths(const geometry::VirtualAnchorSet& vas, int anchor_index,
                                               const geometry::FloorPlan& plan, const Vec2& agent_m,
                                               double carrier_hz, const core::Medium& medium);

}  // namespace mirage::channel
