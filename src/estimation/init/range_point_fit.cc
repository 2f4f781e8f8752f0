// SPDX-License-Identifier: MIT
#include "mirage/estimation/init/range_point_fit.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/LU>

namespace mirage::estimation {
namespace {

struct Normal {
  Eigen::Matrix2d JtJ = Eigen::Matrix2d::Zero();
  Eigen::Vector2d Jtr = Eigen::Vector2d::Zero();
  double cost_m2 = 0.0;
  int count = 0;
};

// Normal equations at q over the ranges with use[i]; J_i = (q - a_i)^T / |q - a_i| is the
// derivative of the predicted range |q - a_i| with respect to q.
Normal Accumulate(const Vec2& q, std::span<const Vec2> positions_m, std::span<const double> ranges_m,
                  const std::vector<bool>& use) {
  Normal n;
  for (std::size_t i = 0; i < positions_m.size(); ++i) {
    if (!use[i]) continue;
    const Vec2 d = q - positions_m[i];
    const double predicted_m = std::max(d.norm(), 1e-9);
    const Eigen::Vector2d J = d / predicted_m;
    const double residual_m = predicted_m - ranges_m[i];
    n.JtJ += J * J.transpose();
    n.Jtr += J * residual_m;
    n.cost_m2 += residual_m * residual_m;
    ++n.count;
  }
  return n;
}

// Damped Gauss-Newton (Levenberg) from q; returns the minimiser.
Vec2 Minimise(Vec2 q, std::span<const Vec2> positions_m, std::span<const double> ranges_m, const std::vector<bool>& use,
              int max_iterations) {
  double lambda = 1e-3;
  Normal n = Accumulate(q, positions_m, ranges_m, use);
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    Eigen::Matrix2d A = n.JtJ;
    A.diagonal().array() += lambda * (n.JtJ.trace() + 1e-9);
    const Vec2 next = q - A.ldlt().solve(n.Jtr);
    const Normal m = Accumulate(next, positions_m, ranges_m, use);
    if (m.cost_m2 < n.cost_m2) {
      const bool converged = (next - q).norm() < 1e-7;
      q = next;
      n = m;
      lambda = std::max(lambda * 0.3, 1e-9);
      if (converged) break;
    } else {
      lambda *= 10.0;
      if (lambda > 1e6) break;
    }
  }
  return q;
}

}  // namespace

std::optional<RangePointFit> FitPointToRanges(std::span<const Vec2> positions_m, std::span<const double> ranges_m,
                                              const Vec2& start_m, const RangePointFitOptions& options) {
  const std::size_t count = positions_m.size();
  if (count < 3 || ranges_m.size() != count || !start_m.allFinite()) return std::nullopt;
  for (std::size_t i = 0; i < count; ++i) {
    if (!positions_m[i].allFinite() || !std::isfinite(ranges_m[i])) return std::nullopt;
  }
  std::vector<bool> use(count, true);
  Vec2 q = Minimise(start_m, positions_m, ranges_m, use, options.max_iterations);
  // One round of outlier rejection: a candidate's ranges may include a few of another path. The
  // gate scales with the median absolute residual (times 1.4826, the std for Gaussian residuals),
  // which those ranges do not inflate as they do the RMS.
  std::vector<double> abs_residuals_m(count);
  for (std::size_t i = 0; i < count; ++i) abs_residuals_m[i] = std::abs((q - positions_m[i]).norm() - ranges_m[i]);
  std::vector<double> sorted_m = abs_residuals_m;
  const auto middle = sorted_m.begin() + static_cast<std::ptrdiff_t>(count / 2);
  std::nth_element(sorted_m.begin(), middle, sorted_m.end());
  constexpr double kMadToSigma = 1.4826;
  const double gate_m = std::max(options.gate_sigmas * kMadToSigma * *middle, options.min_gate_m);
  int kept = 0;
  for (std::size_t i = 0; i < count; ++i) {
    use[i] = abs_residuals_m[i] <= gate_m;
    if (use[i]) ++kept;
  }
  if (kept < 3) return std::nullopt;
  if (kept < static_cast<int>(count)) q = Minimise(q, positions_m, ranges_m, use, options.max_iterations);
  const Normal n = Accumulate(q, positions_m, ranges_m, use);
  const Eigen::FullPivLU<Eigen::Matrix2d> lu(n.JtJ);
  if (!lu.isInvertible() || n.JtJ.determinant() < 1e-12 * n.JtJ.trace() * n.JtJ.trace()) return std::nullopt;
  RangePointFit fit;
  fit.position_m = q;
  fit.rms_m = std::sqrt(n.cost_m2 / static_cast<double>(n.count));
  fit.inliers = n.count;
  const double sigma_m = std::max(fit.rms_m, options.range_sigma_floor_m);
  fit.covariance_m2 = sigma_m * sigma_m * n.JtJ.inverse();
  return fit;
}

}  // namespace mirage::estimation
