// SPDX-License-Identifier: MIT
#include "mirage/estimation/hungarian.h"

#include <limits>

namespace mirage::estimation {
namespace {

// Rows <= columns. Shortest augmenting paths with row/column potentials u, v (1-based, index 0
// is the virtual source), the classic formulation of Kuhn-Munkres in O(n^2 m).
std::vector<int> SolveWide(const Eigen::MatrixXd& a) {
  const int n = static_cast<int>(a.rows());
  const int m = static_cast<int>(a.cols());
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(static_cast<std::size_t>(n + 1), 0.0), v(static_cast<std::size_t>(m + 1), 0.0);
  std::vector<int> p(static_cast<std::size_t>(m + 1), 0), way(static_cast<std::size_t>(m + 1), 0);
  for (int i = 1; i <= n; ++i) {
    p[0] = i;
    int j0 = 0;
    std::vector<double> minv(static_cast<std::size_t>(m + 1), inf);
    std::vector<char> used(static_cast<std::size_t>(m + 1), 0);
    do {
      used[static_cast<std::size_t>(j0)] = 1;
      const int i0 = p[static_cast<std::size_t>(j0)];
      double delta = inf;
      int j1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (used[static_cast<std::size_t>(j)]) continue;
        const double cur = a(i0 - 1, j - 1) - u[static_cast<std::size_t>(i0)] - v[static_cast<std::size_t>(j)];
        if (cur < minv[static_cast<std::size_t>(j)]) {
          minv[static_cast<std::size_t>(j)] = cur;
          way[static_cast<std::size_t>(j)] = j0;
        }
        if (minv[static_cast<std::size_t>(j)] < delta) {
          delta = minv[static_cast<std::size_t>(j)];
          j1 = j;
        }
      }
      for (int j = 0; j <= m; ++j) {
        if (used[static_cast<std::size_t>(j)]) {
          u[static_cast<std::size_t>(p[static_cast<std::size_t>(j)])] += delta;
          v[static_cast<std::size_t>(j)] -= delta;
        } else {
          minv[static_cast<std::size_t>(j)] -= delta;
        }
      }
      j0 = j1;
    } while (p[static_cast<std::size_t>(j0)] != 0);
    do {
      const int j1 = way[static_cast<std::size_t>(j0)];
      p[static_cast<std::size_t>(j0)] = p[static_cast<std::size_t>(j1)];
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<int> row_to_col(static_cast<std::size_t>(n), -1);
  for (int j = 1; j <= m; ++j) {
    if (p[static_cast<std::size_t>(j)] != 0) row_to_col[static_cast<std::size_t>(p[static_cast<std::size_t>(j)] - 1)] = j - 1;
  }
  return row_to_col;
}

}  // namespace

std::vector<int> SolveAssignment(const Eigen::MatrixXd& cost) {
  if (cost.rows() == 0 || cost.cols() == 0) return std::vector<int>(static_cast<std::size_t>(cost.rows()), -1);
  if (cost.rows() <= cost.cols()) return SolveWide(cost);
  const std::vector<int> col_to_row = SolveWide(cost.transpose());
  std::vector<int> row_to_col(static_cast<std::size_t>(cost.rows()), -1);
  for (std::size_t c = 0; c < col_to_row.size(); ++c) {
    if (col_to_row[c] >= 0) row_to_col[static_cast<std::size_t>(col_to_row[c])] = static_cast<int>(c);
  }
  return row_to_col;
}

}  // namespace mirage::estimation
