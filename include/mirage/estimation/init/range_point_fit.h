// SPDX-License-Identifier: MIT
// Batch least-squares fit of a point q to ranges r_i measured from known positions a_i,
// min sum_i (|q - a_i| - r_i)^2, by Gauss-Newton from a start point, with one round of outlier
// rejection (a median-based gate). Used to verify a VA candidate over all of its ranges before it
// enters the SLAM state: once the positions span two dimensions (the agent turned) the fit from
// the wrong mirror hypothesis leaves large residuals, which the RLS-tracked pair cannot show
// reliably (mirage choice; the thesis resolves the pair by its RLS association alone, Lafer Sec.
// 4.2.2).
#pragma once

#include <optional>
#include <span>

#include <Eigen/Core>

#include "mirage/core/types.h"

namespace mirage::estimation {

/// Result of the fit.
struct RangePointFit {
  Vec2 position_m = Vec2::Zero();
  /// sigma^2 (J^T J)^-1 over the inliers with sigma = max(rms, range_sigma_floor_m) (m^2).
  Eigen::Matrix2d covariance_m2 = Eigen::Matrix2d::Identity();
  double rms_m = 0.0;              ///< RMS residual over the inliers (m)
  int inliers = 0;                 ///< ranges within the outlier gate of the first fit (the final fit's)
};

/// Options of the fit.
struct RangePointFitOptions {
  int max_iterations = 10;
  /// Ranges with |residual| above max(gate_sigmas * s, min_gate_m) after the first fit are left
  /// out of the second (m), s = 1.4826 * median |residual|, the MAD estimate of the residual std.
  /// Why not the RMS: the ranges to reject inflate it. A weak VA's candidate in the seminar room
  /// had caught another path's or clutter ranges 10-23 cm short of the true range at one step in
  /// seven: a core within +-4 cm but a 6 cm RMS, so a 3 x RMS gate kept them all; the median
  /// barely moves.
  /// (docs/methods/slam.md, "Promotion by a batch check".)
  double gate_sigmas = 3.0;
  double min_gate_m = 0.05;
  /// Floor of the residual std used for the covariance (m): a lucky small rms must not make the
  /// point overconfident.
  double range_sigma_floor_m = 0.02;
};

/// Fits q from `start_m`. Returns std::nullopt for fewer than 3 ranges, non-finite input, or a
/// singular geometry (J^T J not invertible: all positions on a line through q).
std::optional<RangePointFit> FitPointToRanges(std::span<const Vec2> positions_m, std::span<const double> ranges_m,
                                              const Vec2& start_m, const RangePointFitOptions& options = {});

}  // namespace mirage::estimation
