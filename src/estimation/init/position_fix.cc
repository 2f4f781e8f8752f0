// SPDX-License-Identifier: MIT
#include "mirage/estimation/init/position_fix.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "mirage/estimation/gates/chi2.h"

namespace mirage::estimation {
namespace {

constexpr int kMaxIterations = 25;
constexpr double kStepTolerance_m = 1e-9;
/// Squared residuals below this chi-square quantile are consistent with the range noise: the
/// probability of a 3-sigma interval, as the filters' default gates.
constexpr double kConsistentProbability = 0.9973;

bool Finite(std::span<const Vec3> anchors_m, std::span<const double> ranges_m) {
  for (const auto& a : anchors_m) {
    if (!a.allFinite()) return false;
  }
  for (const double r : ranges_m) {
    if (!std::isfinite(r) || r < 0.0) return false;
  }
  return true;
}

// Gauss-Newton on sum (|p - a_i| - r_i)^2 over the free coordinates (the first `dims` of x, y,
// z; the rest stay fixed). Returns the final J^T J (dims x dims), or nothing if singular.
std::optional<Eigen::MatrixXd> GaussNewton(std::span<const Vec3> anchors_m, std::span<const double> ranges_m, int dims,
                                           Vec3& p_m) {
  const auto n = static_cast<Eigen::Index>(anchors_m.size());
  Eigen::MatrixXd J(n, dims);
  Eigen::VectorXd residual(n);
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const Vec3 d = p_m - anchors_m[static_cast<std::size_t>(i)];
      const double range_m = std::max(d.norm(), 1e-9);
      J.row(i) = (d / range_m).head(dims).transpose();
      residual(i) = ranges_m[static_cast<std::size_t>(i)] - range_m;
    }
    const Eigen::MatrixXd JtJ = J.transpose() * J;
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(JtJ);
    if (ldlt.info() != Eigen::Success || ldlt.rcond() < 1e-10) return std::nullopt;
    const Eigen::VectorXd step = ldlt.solve(J.transpose() * residual);
    p_m.head(dims) += step;
    if (step.norm() < kStepTolerance_m) break;
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    const Vec3 d = p_m - anchors_m[static_cast<std::size_t>(i)];
    J.row(i) = (d / std::max(d.norm(), 1e-9)).head(dims).transpose();
  }
  return Eigen::MatrixXd(J.transpose() * J);
}

}  // namespace

std::optional<PositionFix> FixPosition(std::span<const Vec3> anchors_m, std::span<const double> ranges_m,
                                       std::optional<double> known_height_m, double range_sigma_m) {
  const auto n = static_cast<Eigen::Index>(anchors_m.size());
  if (anchors_m.size() != ranges_m.size() || !Finite(anchors_m, ranges_m) || !(range_sigma_m > 0.0)) return std::nullopt;
  const bool planar = known_height_m.has_value();
  if (n < 3) return std::nullopt;

  // Start: linear least squares on |p|^2 - 2 a_i.p + |a_i|^2 = r_i^2, differenced against the
  // anchors' mean (which removes |p|^2), in the coordinates that are free.
  PositionFix fix;
  Vec3 p_m = Vec3::Zero();
  const Vec3 centroid = [&] {
    Vec3 c = Vec3::Zero();
    for (const auto& a : anchors_m) c += a;
    return Vec3(c / static_cast<double>(n));
  }();
  Eigen::MatrixXd centred(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) centred.row(i) = (anchors_m[static_cast<std::size_t>(i)] - centroid).transpose();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(centred, Eigen::ComputeFullV);
  const Eigen::Vector3d singular = svd.singularValues();
  const double scale = std::max(singular(0), 1e-9);

  if (planar) {
    // Horizontal ranges from the known height; the anchors must not all lie on one vertical plane.
    const double z = *known_height_m;
    Eigen::MatrixXd A(n, 2);
    Eigen::VectorXd b(n);
    double mean_b = 0.0;
    Eigen::RowVector2d mean_a = Eigen::RowVector2d::Zero();
    std::vector<double> horizontal(static_cast<std::size_t>(n));
    for (Eigen::Index i = 0; i < n; ++i) {
      const Vec3& a = anchors_m[static_cast<std::size_t>(i)];
      const double dz = z - a.z();
      const double r = ranges_m[static_cast<std::size_t>(i)];
      horizontal[static_cast<std::size_t>(i)] = std::max(r * r - dz * dz, 0.0);
      A.row(i) = 2.0 * a.head<2>().transpose();
      b(i) = a.head<2>().squaredNorm() - horizontal[static_cast<std::size_t>(i)];
      mean_a += A.row(i);
      mean_b += b(i);
    }
    mean_a /= static_cast<double>(n);
    mean_b /= static_cast<double>(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      A.row(i) -= mean_a;
      b(i) -= mean_b;
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
    if (qr.rank() < 2) return std::nullopt;
    p_m.head<2>() = qr.solve(b);
    p_m.z() = z;
  } else {
    const bool coplanar = singular(2) < 1e-3 * scale;
    if (!coplanar && n < 4) return std::nullopt;
    if (singular(1) < 1e-3 * scale) return std::nullopt;  // all on one line
    // Solve in the anchors' own frame (u, v in their plane, w along its normal).
    const Eigen::Matrix3d V = svd.matrixV();
    Eigen::MatrixXd A(n, coplanar ? 2 : 3);
    Eigen::VectorXd b(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const Vec3 local = V.transpose() * (anchors_m[static_cast<std::size_t>(i)] - centroid);
      const double r = ranges_m[static_cast<std::size_t>(i)];
      A.row(i) = 2.0 * local.head(coplanar ? 2 : 3).transpose();
      b(i) = local.squaredNorm() - r * r;
    }
    // Differencing against the mean removes the unknown |p|^2 (and, coplanar, the w^2 term).
    const Eigen::RowVectorXd mean_a = A.colwise().mean();
    const double mean_b = b.mean();
    for (Eigen::Index i = 0; i < n; ++i) {
      A.row(i) -= mean_a;
      b(i) -= mean_b;
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
    Vec3 local = Vec3::Zero();
    local.head(coplanar ? 2 : 3) = qr.solve(b);
    if (coplanar) {
      // Anchors on a steep plane (one wall) leave no floor side to prefer: no fix.
      if (std::abs(V(2, 2)) < 0.5) return std::nullopt;
      // w^2 from the mean of r_i^2 - |in-plane distance|^2; the side away from the floor is the
      // mirror (the normal is oriented so that +w points up).
      double w2 = 0.0;
      for (Eigen::Index i = 0; i < n; ++i) {
        const Vec3 a = V.transpose() * (anchors_m[static_cast<std::size_t>(i)] - centroid);
        const double r = ranges_m[static_cast<std::size_t>(i)];
        w2 += r * r - (local.head<2>() - a.head<2>()).squaredNorm();
      }
      const double up = V(2, 2) >= 0.0 ? 1.0 : -1.0;  // sign that makes +w point to +z
      local.z() = -up * std::sqrt(std::max(w2 / static_cast<double>(n), 0.0));
      fix.mirror_rejected = true;
    }
    p_m = centroid + V * local;
    // A start exactly on the anchors' plane has a singular Jacobian in w: step below it.
    if (fix.mirror_rejected && std::abs(local.z()) < 1e-3) p_m.z() -= 1e-2;
  }
  if (!p_m.allFinite()) return std::nullopt;
  const int dims = planar ? 2 : 3;
  auto JtJ = GaussNewton(anchors_m, ranges_m, dims, p_m);
  if (!JtJ || !p_m.allFinite()) return std::nullopt;
  const auto squared_residuals = [&](const Vec3& p) {
    double sum = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double e = (p - anchors_m[static_cast<std::size_t>(i)]).norm() - ranges_m[static_cast<std::size_t>(i)];
      sum += e * e;
    }
    return sum;
  };
  double ssr = squared_residuals(p_m);
  // Anchors close to one plane (ceiling anchors at somewhat different heights) have a second
  // local solution near the mirror image about that plane, and with noisy ranges either may have
  // the lower squared residuals. The same rule as for coplanar anchors applies: agents are below
  // the anchors they see, so the floor-side solution is taken unless its residuals are
  // inconsistent with the noise (above the 99.73 % chi-square quantile, n - 3 degrees of
  // freedom) and the other one's are not.
  if (!planar && !fix.mirror_rejected && std::abs(svd.matrixV()(2, 2)) >= 0.5) {
    const Vec3 normal = svd.matrixV().col(2) * (svd.matrixV()(2, 2) >= 0.0 ? 1.0 : -1.0);  // points up
    Vec3 mirror_m = p_m - 2.0 * normal.dot(p_m - centroid) * normal;
    const auto mirror_JtJ = GaussNewton(anchors_m, ranges_m, dims, mirror_m);
    if (mirror_JtJ && mirror_m.allFinite() && (mirror_m - p_m).norm() > 1e-6) {
      const double mirror_ssr = squared_residuals(mirror_m);
      const double consistent_m2 =
          Chi2Quantile(kConsistentProbability, static_cast<int>(std::max<Eigen::Index>(n - 3, 1))) * range_sigma_m *
          range_sigma_m;
      const bool mirror_is_lower = normal.dot(mirror_m - p_m) < 0.0;
      const double lower_ssr = mirror_is_lower ? mirror_ssr : ssr;
      const double upper_ssr = mirror_is_lower ? ssr : mirror_ssr;
      const bool take_lower = lower_ssr <= consistent_m2 || lower_ssr <= upper_ssr;
      if (take_lower == mirror_is_lower) {
        p_m = mirror_m;
        JtJ = mirror_JtJ;
        ssr = mirror_ssr;
      }
      fix.mirror_rejected = take_lower && upper_ssr <= consistent_m2;
    }
  }
  fix.position_m = p_m;
  fix.covariance_m2.topLeftCorner(dims, dims) = range_sigma_m * range_sigma_m * JtJ->inverse();
  fix.rms_m = std::sqrt(ssr / static_cast<double>(n));
  return fix;
}

}  // namespace mirage::estimation
