// SPDX-License-Identifier: MIT
#include "mirage/estimation/solvers/linear_toa.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "mirage/estimation/solvers/toa_nlls.h"

namespace mirage::estimation {
namespace {

// Smallest LDLT pivot of the column-normalised normal matrix (a correlation matrix, largest
// eigenvalue <= p) below which two unknowns are not separable.
constexpr double kMinNormalEigen = 1e-10;

using Normal = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 5, 5>;
using Column = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 5, 1>;

bool Valid(std::span<const Vec3> receivers_m, std::span<const double> values_m, std::span<const double> sigmas_m,
           std::optional<double> known_height_m) {
  if (values_m.size() != receivers_m.size()) return false;
  if (!sigmas_m.empty() && sigmas_m.size() != receivers_m.size()) return false;
  if (known_height_m && !std::isfinite(*known_height_m)) return false;
  for (std::size_t i = 0; i < receivers_m.size(); ++i) {
    if (!receivers_m[i].allFinite() || !std::isfinite(values_m[i])) return false;
    if (!sigmas_m.empty() && !(sigmas_m[i] > 0.0 && std::isfinite(sigmas_m[i]))) return false;
  }
  return true;
}

// Solves the squared rows; with_offset: pseudo-ranges (b unknown), else ranges.
SolverFix Solve(std::span<const Vec3> receivers_m, std::span<const double> values_m, std::span<const double> sigmas_m,
                std::optional<double> known_height_m, bool with_offset) {
  SolverFix fix;
  if (!Valid(receivers_m, values_m, sigmas_m, known_height_m)) {
    fix.status = SolverStatus::kInvalidInput;
    return fix;
  }
  const std::size_t n = receivers_m.size();
  const int position_columns = known_height_m ? 2 : 3;
  const int p = position_columns + (with_offset ? 1 : 0) + 1;  // + lambda
  if (static_cast<int>(n) < p) {
    fix.status = SolverStatus::kTooFewRows;
    return fix;
  }
  const auto weight = [&](std::size_t i) { return sigmas_m.empty() ? 1.0 : 1.0 / (sigmas_m[i] * sigmas_m[i]); };
  // Weighted centroid of the receivers and weighted mean of the values (conditioning only).
  Vec3 centre = Vec3::Zero();
  double mean_value = 0.0;
  double weight_sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    centre += weight(i) * receivers_m[i];
    mean_value += weight(i) * values_m[i];
    weight_sum += weight(i);
  }
  centre /= weight_sum;
  mean_value = with_offset ? mean_value / weight_sum : 0.0;  // ranges keep b = 0
  const double z_centred = known_height_m ? *known_height_m - centre.z() : 0.0;

  Normal A = Normal::Zero(p, p);
  Column y = Column::Zero(p);
  Column row(p);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 m = receivers_m[i] - centre;
    const double v = values_m[i] - mean_value;
    double rhs = m.squaredNorm() - v * v;
    int c = 0;
    row(c++) = 2.0 * m.x();
    row(c++) = 2.0 * m.y();
    if (known_height_m) {
      rhs -= 2.0 * m.z() * z_centred;
    } else {
      row(c++) = 2.0 * m.z();
    }
    if (with_offset) row(c++) = -2.0 * v;
    row(c) = 1.0;  // lambda
    A.noalias() += weight(i) * row * row.transpose();
    y.noalias() += weight(i) * rhs * row;
  }
  // Singular when some unknown is (nearly) a combination of the others, e.g. the z column of
  // coplanar receivers against lambda's.
  const Column d = A.diagonal();
  // The position and offset columns share a unit (m): one of them at rounding-noise level
  // (coplanar receivers stored at "equal" heights, pseudo-ranges equal up to rounding) would
  // look regular after normalisation.
  const int metric_columns = p - 1;  // all but lambda's
  double max_metric = 0.0;
  for (int k = 0; k < metric_columns; ++k) max_metric = std::max(max_metric, d(k));
  bool tiny_column = false;
  for (int k = 0; k < metric_columns; ++k) tiny_column = tiny_column || !(d(k) > kMinNormalEigen * max_metric);
  if (!(d.minCoeff() > 0.0) || tiny_column) {
    fix.status = SolverStatus::kDegenerateGeometry;
    return fix;
  }
  const Column scale = d.cwiseSqrt().cwiseInverse();
  const Normal correlation = scale.asDiagonal() * A * scale.asDiagonal();
  // LDLT with diagonal pivoting: its smallest pivot bounds the smallest eigenvalue from above
  // (up to a small factor for p <= 5), so a tiny pivot flags inseparable unknowns.
  const Eigen::LDLT<Normal> ldlt(correlation);
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > kMinNormalEigen)) {
    fix.status = SolverStatus::kDegenerateGeometry;
    return fix;
  }
  const Column scaled_solution = ldlt.solve(Column(scale.asDiagonal() * y));
  const Column solution = scale.asDiagonal() * scaled_solution;
  Vec3 position = centre;
  position.x() += solution(0);
  position.y() += solution(1);
  position.z() = known_height_m ? *known_height_m : centre.z() + solution(2);
  const double offset = with_offset ? mean_value + solution(position_columns) : 0.0;

  NllsProblem problem;
  problem.model = with_offset ? RowModel::kToa : RowModel::kRange;
  problem.receivers_m = receivers_m;
  problem.values_m = values_m;
  problem.sigmas_m = sigmas_m;
  SolverFix fix_out = AssessFix(problem, position, offset, known_height_m);
  fix_out.converged = true;  // the linear fix exists even where AssessFix finds no covariance
  return fix_out;
}

}  // namespace

SolverFix SolveLinearToa(std::span<const Vec3> receivers_m, std::span<const double> pseudo_ranges_m,
                         std::span<const double> sigmas_m, std::optional<double> known_height_m) {
  return Solve(receivers_m, pseudo_ranges_m, sigmas_m, known_height_m, true);
}

SolverFix SolveLinearRanges(std::span<const Vec3> receivers_m, std::span<const double> ranges_m,
                            std::span<const double> sigmas_m, std::optional<double> known_height_m) {
  return Solve(receivers_m, ranges_m, sigmas_m, known_height_m, false);
}

}  // namespace mirage::estimation
