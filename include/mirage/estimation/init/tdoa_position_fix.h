// SPDX-License-Identifier: MIT
// A 3-D position from pairwise differences of arrival distances, tdoa_m = |p - a_j| - |p - a_i|
// (estimation/meas/tdoa.h), some of them gross outliers or biased: the start of a TDOA filter
// without a given start point. Any pairs, not one reference receiver: UWB TDOA systems report
// whichever pair a packet gave.
// Method: Gauss-Newton with Hampel weights (robust/hampel.h) on the residuals in units of sigma,
// a fixed clipping point a = 1 (the noise is known, so no MAD scale; b = 4 sigma rejects), from
// two points off the anchors' best-fit plane (below it, then above it, at the anchors' RMS
// spread: coplanar anchors leave the normal direction without gradient in the plane), from the
// anchors' centroid and from each anchor pulled halfway towards it: the TDOA cost is not convex,
// and a start near the right anchor finds the basin a centroid start can miss. The solution with
// the most rows within 3 sigma wins; of equal counts a later start wins only with a sum of
// squares lower by more than 1. Mirror rule: a solution above the anchors' best-fit plane is
// replaced by the solution from its mirror image when that one lies below and explains the rows
// as well (no fewer inliers, a sum of squares at most 1 higher): about coplanar anchors both are
// exact, and a ceiling-mounted system's tag is below (range_ekf's fix keeps the same side).
// It is accepted when those inliers number at least 5 (4 unknowns' worth of redundancy for 3
// coordinates plus one check), span at least 4 anchors, are at least half the rows, and the
// weighted normal matrix is well conditioned (the geometry determines p).
#pragma once

#include <optional>
#include <span>

#include "mirage/core/types.h"
#include "mirage/estimation/init/position_fix.h"

namespace mirage::estimation {

/// One difference with its anchors' positions.
struct TdoaRow {
  Vec3 anchor_i_m = Vec3::Zero();
  Vec3 anchor_j_m = Vec3::Zero();
  int index_i = 0;  ///< anchor ids, for counting the anchors the inliers span
  int index_j = 0;
  double tdoa_m = 0.0;  ///< |p - a_j| - |p - a_i| (m)
};

/// The robust fix and how many rows it explains.
struct TdoaPositionFix {
  PositionFix fix;  ///< covariance sigma^2 (J^T W J)^-1 over the inliers
  int inliers = 0;  ///< rows within 3 sigma of the fix
  int anchors = 0;  ///< distinct anchors among the inliers' pairs
};

/// The fix of `rows` (see the file comment); std::nullopt when no start converges to an
/// acceptable solution (too few rows or anchors, degenerate geometry, mostly outliers).
/// @param sigma_m the differences' standard deviation (m), > 0.
std::optional<TdoaPositionFix> FixPositionFromTdoas(std::span<const TdoaRow> rows, double sigma_m);

}  // namespace mirage::estimation
