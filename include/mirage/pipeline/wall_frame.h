// SPDX-License-Identifier: MIT
// The floor plan's frame of an estimated plan (Kulmer et al. Sec. IV-E): an anchorless estimate
// is defined only up to a common translation of agents and walls, so its errors are read after
// removing the translation that best explains the walls' estimated offsets. With wall offsets
// e_s (estimated minus true, along the normals n_s) of standard deviation sigma_s, the
// translation is t = (sum n_s n_s^T / sigma_s^2)^-1 sum n_s e_s / sigma_s^2 (weighted least
// squares, the analogue of the paper's centre of gravity for normal offsets).
#pragma once

#include <span>
#include <vector>

#include "mirage/core/types.h"
#include "mirage/geometry/floor_plan.h"
#include "mirage/methods/estimator.h"

namespace mirage::pipeline {

/// The frame of one epoch.
struct WallFrame {
  Vec2 translation_m = Vec2::Zero();
  /// Per given wall: estimated minus true offset along its normal, translation removed (m).
  std::vector<double> wall_error_m;
};

/// The frame of `walls` (the estimator's offsets of the given plan's walls) against their true
/// offsets. Walls with zero standard deviation are fixed (not estimated) and do not define the
/// translation; with none estimated, the plan itself is the frame (translation 0).
WallFrame ComputeWallFrame(const geometry::FloorPlan& given, std::span<const methods::WallEstimate> walls,
                           std::span<const double> true_offset_m);

}  // namespace mirage::pipeline
