// SPDX-License-Identifier: MIT
// A position fix from one range to each of several known anchors (multilateration): linear least
// squares on differences of squared ranges for a start, then Gauss-Newton on the ranges
// themselves. Used to start an estimator without a given start point (self-initialisation).
//
// Anchors on one plane (the usual ceiling mount) leave the height ambiguous: the ranges fit the
// point and its mirror image about the anchors' plane equally well. The mirror on the side away
// from the floor (above ceiling anchors) is rejected: agents are below the anchors they see.
// Anchors near one plane (ceiling anchors at different heights) have two local solutions too;
// the upper one is taken only when the lower one's residuals are inconsistent with the noise.
#pragma once

#include <optional>
#include <span>

#include <Eigen/Core>

#include "mirage/core/types.h"

namespace mirage::estimation {

/// A fix and its uncertainty.
struct PositionFix {
  Vec3 position_m = Vec3::Zero();
  /// sigma^2 (J^T J)^-1 at the fix, sigma the range standard deviation given (m^2); for a planar
  /// fix the z row and column are zero.
  Eigen::Matrix3d covariance_m2 = Eigen::Matrix3d::Zero();
  double rms_m = 0.0;            ///< RMS range residual at the fix (m)
  /// The anchors were (nearly) coplanar and a solution above them, consistent with the noise too,
  /// was dropped.
  bool mirror_rejected = false;
};

/// The fix from ranges_m[i] to anchors_m[i]. With known_height_m the agent's z is given and
/// only x, y are solved (at least 3 anchors not on one vertical plane); without it all three
/// coordinates (at least 4 anchors not coplanar, or 3 coplanar ones with the mirror rule).
/// std::nullopt for too few anchors, degenerate geometry, non-finite input or no convergence.
/// @param range_sigma_m the ranges' standard deviation (m), > 0, for the covariance.
std::optional<PositionFix> FixPosition(std::span<const Vec3> anchors_m, std::span<const double> ranges_m,
                                       std::optional<double> known_height_m, double range_sigma_m);

}  // namespace mirage::estimation
