// SPDX-License-Identifier: MIT
#include "mirage/eval/rigid_alignment.h"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>
#include <Eigen/SVD>

namespace mirage::eval {

double RigidTransform::AngleRad() const {
  // trace R = 1 + 2 cos(angle) for a rotation.
  return std::acos(std::clamp(0.5 * (rotation.trace() - 1.0), -1.0, 1.0));
}

std::optional<RigidTransform> AlignRigid(std::span<const Vec3> reference_m, std::span<const Vec3> estimate_m, bool planar) {
  const std::size_t n = reference_m.size();
  if (n != estimate_m.size() || n < (planar ? 2u : 3u)) return std::nullopt;
  RigidTransform out;
  for (std::size_t i = 0; i < n; ++i) {
    out.to_m += reference_m[i] / static_cast<double>(n);  // (3.49)
    out.from_m += estimate_m[i] / static_cast<double>(n);
  }
  const int d = planar ? 2 : 3;
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(d, d);  // (3.50)
  for (std::size_t i = 0; i < n; ++i) {
    W += (reference_m[i] - out.to_m).head(d) * (estimate_m[i] - out.from_m).head(d).transpose();
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(W, Eigen::ComputeFullU | Eigen::ComputeFullV);  // (3.51)
  Eigen::MatrixXd U = svd.matrixU();
  const Eigen::MatrixXd V = svd.matrixV();
  if ((U * V.transpose()).determinant() < 0.0) U.col(d - 1) *= -1.0;  // the reflection fix
  out.rotation.topLeftCorner(d, d) = U * V.transpose();                // (3.52)
  if (planar) {
    // Horizontal only: the heights stay where they are.
    out.to_m.z() = 0.0;
    out.from_m.z() = 0.0;
  }
  return out;
}

}  // namespace mirage::eval
