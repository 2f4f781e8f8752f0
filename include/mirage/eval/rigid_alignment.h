// SPDX-License-Identifier: MIT
// Rigid alignment of an estimated track to a reference track (Bordoy 2020, PhD thesis Univ.
// Freiburg, Sec. 3.3, Eq. 3.49-3.52, after Arun et al. 1987): for recorded data whose reference
// (a motion-capture system) has its own frame. With the means mu_g of the reference points g_i
// and mu_h of the estimates h_i (3.49), the cross-covariance W = sum (g_i - mu_g)(h_i - mu_h)^T
// (3.50) and its SVD W = U D V^T (3.51), the aligned estimate is U V^T (h_i - mu_h) + mu_g
// (3.52). Rotation and translation only, no scale (digest Sec. 2.3 [INF]). Choices:
//  - The reflection fix (digest [SUG]): when det(U V^T) = -1 the last column of U is negated, so
//    that the result is a rotation (the nearest one), never a mirror image.
//  - planar: the rotation is about the vertical axis only and the translation horizontal (a
//    method that estimates x, y at a known height, whose heights are not estimates): a 2-D SVD of
//    the horizontal coordinates, so that a planar track is never tilted.
#pragma once

#include <optional>
#include <span>

#include <Eigen/Core>

#include "mirage/core/types.h"

namespace mirage::eval {

/// x -> rotation (x - from_m) + to_m.
struct RigidTransform {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Vec3 from_m = Vec3::Zero();  ///< mu_h, the estimates' mean (m)
  Vec3 to_m = Vec3::Zero();    ///< mu_g, the reference's mean (m)
  [[nodiscard]] Vec3 Apply(const Vec3& x_m) const { return rotation * (x_m - from_m) + to_m; }
  /// The rotation's angle (rad), in [0, pi].
  [[nodiscard]] double AngleRad() const;
  /// The displacement of the estimates' mean (m): to_m - from_m (the t of x' = R x + t is
  /// to_m - R from_m; the two agree for a small rotation).
  [[nodiscard]] Vec3 TranslationM() const { return to_m - from_m; }
};

/// The rigid transform that best maps estimate_m onto reference_m in the least-squares sense
/// (Eq. 3.49-3.52); pairs by index. Empty with fewer than 2 pairs (planar) or 3 (3-D), or sizes
/// that differ.
std::optional<RigidTransform> AlignRigid(std::span<const Vec3> reference_m, std::span<const Vec3> estimate_m, bool planar);

}  // namespace mirage::eval
