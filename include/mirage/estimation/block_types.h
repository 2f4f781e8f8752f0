// SPDX-License-Identifier: MIT
// The built-in state block types (all Euclidean). Methods add their own BlockType constants
// (ids >= 100) next to their code; block_type.h says how.
#pragma once

#include "mirage/estimation/block_type.h"

namespace mirage::estimation::blocks {

/// Agent position in the plane [x, y] (m).
inline constexpr BlockType kPosition{1, "position", 2, 2};
/// Agent velocity in the plane [vx, vy] (m/s).
inline constexpr BlockType kVelocity{2, "velocity", 2, 2};
/// Agent position in 3-D [x, y, z] (m).
inline constexpr BlockType kPosition3{3, "position3", 3, 3};
/// Agent velocity in 3-D [vx, vy, vz] (m/s).
inline constexpr BlockType kVelocity3{4, "velocity3", 3, 3};
/// Virtual anchor position in the plane [x, y] (m).
inline constexpr BlockType kVirtualAnchor{5, "virtual_anchor", 2, 2};
/// Offset of a wall along its normal (m).
inline constexpr BlockType kWallOffset{6, "wall_offset", 1, 1};

}  // namespace mirage::estimation::blocks
