// SPDX-License-Identifier: MIT
#include "mirage/estimation/range_association.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "mirage/estimation/hungarian.h"

namespace mirage::estimation {

std::vector<int> AssociateRanges(std::span<const double> expected_m, std::span<const double> measured_m,
                                 double cutoff_m) {
  const auto n = static_cast<Eigen::Index>(expected_m.size());
  const auto m = static_cast<Eigen::Index>(measured_m.size());
  Eigen::MatrixXd distance(n, m);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < m; ++j) {
      distance(i, j) = std::abs(expected_m[static_cast<std::size_t>(i)] - measured_m[static_cast<std::size_t>(j)]);
    }
  }
  return AssociateWithCutoff(distance, cutoff_m);
}

std::vector<int> AssociateWithCutoff(const Eigen::MatrixXd& distance_m, double cutoff_m) {
  const Eigen::Index n = distance_m.rows();
  // Eq. (3.8) with the cut-off metric; when there are fewer measurements than expected ranges
  // the rectangular assignment plays the role of the thesis's clutter padding.
  const Eigen::MatrixXd cost = distance_m.cwiseMin(cutoff_m);
  std::vector<int> assignment = SolveAssignment(cost);
  // Eq. (3.9): pairs assigned at the cut-off are clutter.
  for (Eigen::Index i = 0; i < n; ++i) {
    int& j = assignment[static_cast<std::size_t>(i)];
    if (j >= 0 && cost(i, j) >= cutoff_m) j = -1;
  }
  return assignment;
}

}  // namespace mirage::estimation
