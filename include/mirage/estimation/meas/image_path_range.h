// SPDX-License-Identifier: MIT
// Length of a specular path between two antennas, each either fixed (an anchor) or carried by an
// agent whose position is in the state, over walls whose normal offsets may be in the state
// (Kulmer et al. Eq. 13, 14, 17; the derivatives are geometry::ComputeImagePath's, digest
// anchorless_coop_kulmer.md Sec. 2.2). An antenna at a fixed offset from its agent moves with
// it, so its derivative is the agent position's. The agent's own channel (transmitter and
// receiver on one agent) gets the total derivative d_tx + d_rx on that agent (App. C).
#pragma once

#include <optional>
#include <span>

#include "mirage/estimation/measurement_row.h"
#include "mirage/estimation/state.h"
#include "mirage/geometry/image_source.h"

namespace mirage::estimation {

/// The row of one path. tx_agent / rx_agent: the position blocks carrying the antennas (empty:
/// fixed); wall_blocks: one entry per wall of the path's sequence, the wall's offset block or
/// empty (the walls are not estimated). path holds the length and derivatives at `state`'s mean.
/// @param variance_m2 the range variance R (m^2).
MeasurementRow ImagePathRangeRow(const geometry::ImagePath& path, const std::optional<Block>& tx_agent,
                                 const std::optional<Block>& rx_agent, std::span<const std::optional<Block>> wall_blocks,
                                 double variance_m2);

}  // namespace mirage::estimation
