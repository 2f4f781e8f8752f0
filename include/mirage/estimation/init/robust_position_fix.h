// SPDX-License-Identifier: MIT
// A position fix that survives wrong ranges: each anchor offers several unlabeled ranges (the line
// of sight, a false peak, a reflection), or its line of sight is missed and only a wrong range is
// left. Least squares over all anchors spreads one wrong range over every residual and can still
// pass an RMS test, or even every single residual's gate: near-coplanar anchors absorb it by
// moving the height metres off. So each anchor's range is tested against the fix of the OTHER
// anchors (its deletion residual, normalised by that prediction's variance), the worst one
// failing the gate is left out and the test repeated; then every anchor is re-admitted with its
// range closest to the fix's prediction if that range passes the gate.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "mirage/core/types.h"
#include "mirage/estimation/init/position_fix.h"

namespace mirage::estimation {

/// The unlabeled ranges measured to one anchor (m).
struct AnchorCandidates {
  Vec3 anchor_m = Vec3::Zero();
  std::vector<double> ranges_m;
};

/// A fix whose every residual passed the gate.
struct RobustPositionFix {
  PositionFix fix;
  /// For each anchor of the input, the index of the range the fix used, or -1 if none passed.
  std::vector<int> range_index;
  int anchors_used = 0;
  /// More anchors than unknowns were used (at least 4 in 3-D, 3 with a known height), so the
  /// residuals could have revealed a wrong range; a fix with exactly as many is unverified.
  bool redundant = false;
};

/// The fix of the candidates. Starts from the earliest range of every anchor (the line of sight
/// when it is not blocked). While some residual r_i fails r_i^2 <= gate_chi2 sigma^2 or some
/// deletion residual e_i (range i against the fix of the other anchors, covariance P_-i) fails
/// e_i^2 <= gate_chi2 (sigma^2 + d_i^T P_-i d_i), the anchor with the largest deletion residual is
/// left out (at most two, and more anchors than unknowns must remain). Then each anchor is
/// re-admitted with its range nearest the fix's predicted range when that one passes the gate,
/// and the fix is redone.
/// std::nullopt when no fix passes (too few anchors, degenerate geometry, no consensus).
/// @param range_sigma_m the ranges' standard deviation (m), > 0
/// @param gate_chi2 the gate on one range's normalised squared residual, > 0 (9: 3 sigma)
std::optional<RobustPositionFix> FixPositionRobust(std::span<const AnchorCandidates> candidates,
                                                   std::optional<double> known_height_m, double range_sigma_m,
                                                   double gate_chi2);

}  // namespace mirage::estimation
