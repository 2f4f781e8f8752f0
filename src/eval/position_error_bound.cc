// SPDX-License-Identifier: MIT
#include "mirage/eval/position_error_bound.h"

#include <cmath>

#include <Eigen/Core>
#include <Eigen/LU>

namespace mirage::eval {

std::optional<double> PositionErrorBound(const Vec2& agent_m, std::span<const RangeInformation> ranges,
                                         double range_sigma_at_unit_sinr_m) {
  Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
  const double inv_sigma2 = 1.0 / (range_sigma_at_unit_sinr_m * range_sigma_at_unit_sinr_m);
  for (const auto& r : ranges) {
    const Vec2 d = agent_m - r.va_m;
    const double norm = d.norm();
    if (norm <= 0.0) continue;
    const Vec2 u = d / norm;
    J += r.sinr * inv_sigma2 * u * u.transpose();
  }
  // Relative conditioning test: a near-singular J means a direction without information.
  const double det = J.determinant();
  if (!(det > 1e-12 * J.trace() * J.trace())) return std::nullopt;
  return std::sqrt(J.inverse().trace());
}

}  // namespace mirage::eval
