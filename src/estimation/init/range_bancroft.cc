// SPDX-License-Identifier: MIT
#include "mirage/estimation/init/range_bancroft.h"

#include <cmath>

#include <Eigen/Dense>

namespace mirage::estimation {

namespace {

// s_2 / s_1 of the differenced system above which the path has turned enough for a unique point.
constexpr double kTurnRatio = 0.3;

double SquaredResidual(const Vec2& q, std::span<const Vec2> positions_m, std::span<const double> ranges_m) {
  double sum = 0.0;
  for (std::size_t i = 0; i < positions_m.size(); ++i) {
    const double r = (q - positions_m[i]).norm() - ranges_m[i];
    sum += r * r;
  }
  return sum;
}

// A few Gauss-Newton steps on sum_i (|q - a_i| - r_i)^2 from the closed form (which minimises the
// squared-range residuals instead); a step that does not lower the cost is not taken.
Vec2 Refine(Vec2 q, std::span<const Vec2> positions_m, std::span<const double> ranges_m) {
  double cost = SquaredResidual(q, positions_m, ranges_m);
  for (int iteration = 0; iteration < 5; ++iteration) {
    Eigen::Matrix2d JtJ = Eigen::Matrix2d::Zero();
    Eigen::Vector2d Jtr = Eigen::Vector2d::Zero();
    for (std::size_t i = 0; i < positions_m.size(); ++i) {
      const Vec2 d = q - positions_m[i];
      const double range_m = d.norm();
      if (range_m < 1e-9) return q;
      const Eigen::Vector2d J = d / range_m;
      JtJ += J * J.transpose();
      Jtr += J * (range_m - ranges_m[i]);
    }
    // Levenberg damping keeps the weakly observed direction across a straight path in place.
    JtJ.diagonal().array() += 1e-6 + 1e-3 * JtJ.trace();
    const Vec2 next = q - JtJ.ldlt().solve(Jtr);
    const double next_cost = SquaredResidual(next, positions_m, ranges_m);
    if (!(next_cost < cost)) break;
    q = next;
    cost = next_cost;
  }
  return q;
}

}  // namespace

std::optional<BancroftPair> RangeBancroft(std::span<const Vec2> positions_m, std::span<const double> ranges_m) {
  const std::size_t n = positions_m.size();
  if (n < 3 || ranges_m.size() != n) return std::nullopt;
  for (std::size_t i = 0; i < n; ++i) {
    if (!positions_m[i].allFinite() || !std::isfinite(ranges_m[i]) || ranges_m[i] < 0.0) return std::nullopt;
  }
  // Differenced form: |q - a_i|^2 - |q - a_0|^2 = r_i^2 - r_0^2 is linear in q,
  //   2 (a_i - a_0)^T q = |a_i|^2 - |a_0|^2 - r_i^2 + r_0^2.
  // Work relative to the centroid c (q = c + x) for conditioning; the differenced equations have
  // no lambda = |q|^2 term, so the digest's rank problem for a path through the origin cannot
  // occur. Along the null direction of the system (collinear positions) x is fixed by the
  // remaining quadratic |x - b_0|^2 = r_0^2, which gives the mirror pair.
  Vec2 c = Vec2::Zero();
  for (const auto& a : positions_m) c += a;
  c /= static_cast<double>(n);
  Eigen::MatrixXd A(static_cast<Eigen::Index>(n - 1), 2);
  Eigen::VectorXd y(static_cast<Eigen::Index>(n - 1));
  const Vec2 b0 = positions_m[0] - c;
  for (std::size_t i = 1; i < n; ++i) {
    const Vec2 bi = positions_m[i] - c;
    const auto row = static_cast<Eigen::Index>(i - 1);
    A.row(row) = 2.0 * (bi - b0).transpose();
    y(row) = bi.squaredNorm() - b0.squaredNorm() - ranges_m[i] * ranges_m[i] + ranges_m[0] * ranges_m[0];
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV | Eigen::ComputeThinU);
  const Eigen::Vector2d s = svd.singularValues();
  if (!(s(0) > 0.0)) return std::nullopt;  // all positions identical
  const Eigen::Matrix2d V = svd.matrixV();
  const Eigen::VectorXd uy = svd.matrixU().transpose() * y;
  BancroftPair pair;
  // A clear turn in the path (both directions spanned): the linear LS point is unique.
  if (s(1) > kTurnRatio * s(0)) {
    const Vec2 x = V.col(0) * (uy(0) / s(0)) + V.col(1) * (uy(1) / s(1));
    const Vec2 q = Refine(c + x, positions_m, ranges_m);
    pair.positions_m = {q, q};
    pair.solutions = 1;
    return pair;
  }
  // A nearly straight path: the linear system fixes only the coordinate t along the path; the
  // coordinate u across it follows from the circles, sum_i |t along + u normal - b_i|^2 =
  // sum_i r_i^2, a quadratic whose two roots are the mirror pair.
  const Vec2 along = V.col(0);
  const Vec2 normal = V.col(1);
  const double t = uy(0) / s(0);
  double qb = 0.0, qc = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 w = t * along - (positions_m[i] - c);
    qb += 2.0 * w.dot(normal);
    qc += w.squaredNorm() - ranges_m[i] * ranges_m[i];
  }
  const double qa = static_cast<double>(n);
  const double disc = qb * qb - 4.0 * qa * qc;
  if (disc <= 0.0) {
    // Complex roots (noise): the real part, a point on the path line.
    const Vec2 q = Refine(c + t * along + (-qb / (2.0 * qa)) * normal, positions_m, ranges_m);
    pair.positions_m = {q, q};
    pair.solutions = 1;
    return pair;
  }
  const double root = std::sqrt(disc);
  pair.positions_m = {Refine(c + t * along + ((-qb + root) / (2.0 * qa)) * normal, positions_m, ranges_m),
                      Refine(c + t * along + ((-qb - root) / (2.0 * qa)) * normal, positions_m, ranges_m)};
  pair.solutions = 2;
  return pair;
}

}  // namespace mirage::estimation
