// SPDX-License-Identifier: MIT
#include "mirage/eval/ospa.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "mirage/estimation/hungarian.h"

namespace mirage::eval {

OspaResult Ospa(std::span<const Vec2> estimated, std::span<const Vec2> truth, double cutoff_m, double order_p) {
  OspaResult result;
  result.assignment.assign(estimated.size(), -1);
  const std::size_t m = estimated.size();
  const std::size_t k = truth.size();
  const std::size_t n = std::max(m, k);
  if (n == 0) return result;
  const double c_p = std::pow(cutoff_m, order_p);
  double assigned_sum = 0.0;
  if (m > 0 && k > 0) {
    // Costs min(c, d)^p; the assignment over the smaller set is complete.
    Eigen::MatrixXd cost(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(k));
    for (std::size_t i = 0; i < m; ++i) {
      for (std::size_t j = 0; j < k; ++j) {
        cost(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
            std::pow(std::min(cutoff_m, (estimated[i] - truth[j]).norm()), order_p);
      }
    }
    const std::vector<int> assignment = estimation::SolveAssignment(cost);
    for (std::size_t i = 0; i < m; ++i) {
      if (assignment[i] < 0) continue;
      const auto j = static_cast<std::size_t>(assignment[i]);
      assigned_sum += cost(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
      if ((estimated[i] - truth[j]).norm() < cutoff_m) result.assignment[i] = assignment[i];
    }
  }
  const double unassigned = static_cast<double>(n - std::min(m, k));
  const double nn = static_cast<double>(n);
  result.distance_m = std::pow((assigned_sum + c_p * unassigned) / nn, 1.0 / order_p);
  result.localization_m = std::pow(assigned_sum / nn, 1.0 / order_p);
  result.cardinality_m = std::pow(c_p * unassigned / nn, 1.0 / order_p);
  return result;
}

}  // namespace mirage::eval
