// SPDX-License-Identifier: MIT
// Optimal assignment (Hungarian / Kuhn-Munkres with potentials, O(n^2 m)) on a rectangular cost
// matrix: every row gets a distinct column when rows <= columns, and vice versa.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace mirage::estimation {

/// For each row, the assigned column, or -1 when there are more rows than columns and the row is
/// left out. Minimises the total cost of the assigned pairs. Costs must be finite.
std::vector<int> SolveAssignment(const Eigen::MatrixXd& cost);

}  // namespace mirage::estimation
