// SPDX-License-Identifier: MIT
#include "mirage/estimation/hungarian.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "mirage/core/rng.h"

namespace mirage::estimation {
namespace {

// Minimum total cost over all injective maps of the smaller side into the larger one, by
// depth-first enumeration (at most 8!/2! = 20160 leaves for 6x8 or 8x6).
double BruteForceMinimum(const Eigen::MatrixXd& cost) {
  const bool wide = cost.rows() <= cost.cols();
  const Eigen::MatrixXd c = wide ? cost : Eigen::MatrixXd(cost.transpose());
  const int n = static_cast<int>(c.rows()), m = static_cast<int>(c.cols());
  std::vector<char> used(static_cast<std::size_t>(m), 0);
  double best = std::numeric_limits<double>::infinity();
  auto recurse = [&](auto&& self, int row, double sum) -> void {
    if (row == n) {
      best = std::min(best, sum);
      return;
    }
    for (int j = 0; j < m; ++j) {
      if (used[static_cast<std::size_t>(j)]) continue;
      used[static_cast<std::size_t>(j)] = 1;
      self(self, row + 1, sum + c(row, j));
      used[static_cast<std::size_t>(j)] = 0;
    }
  };
  recurse(recurse, 0, 0.0);
  return best;
}

// Checks that `assignment` is a valid rectangular assignment for `cost` and returns its total.
double CheckedTotal(const Eigen::MatrixXd& cost, const std::vector<int>& assignment) {
  const int rows = static_cast<int>(cost.rows()), cols = static_cast<int>(cost.cols());
  EXPECT_EQ(static_cast<int>(assignment.size()), rows);
  std::vector<int> column_uses(static_cast<std::size_t>(cols), 0);
  int assigned = 0;
  double total = 0.0;
  for (int i = 0; i < static_cast<int>(assignment.size()); ++i) {
    const int j = assignment[static_cast<std::size_t>(i)];
    if (j == -1) continue;
    EXPECT_GE(j, 0);
    EXPECT_LT(j, cols);
    if (j < 0 || j >= cols) continue;
    ++column_uses[static_cast<std::size_t>(j)];
    ++assigned;
    total += cost(i, j);
  }
  for (int j = 0; j < cols; ++j) EXPECT_LE(column_uses[static_cast<std::size_t>(j)], 1) << "column " << j;
  // Every row is assigned when rows <= cols; otherwise exactly rows - cols rows are left out.
  EXPECT_EQ(assigned, std::min(rows, cols));
  EXPECT_EQ(static_cast<int>(std::count(assignment.begin(), assignment.end(), -1)), rows - std::min(rows, cols));
  return total;
}

Eigen::MatrixXd RandomCost(int rows, int cols, core::Rng& rng, bool integer) {
  Eigen::MatrixXd c(rows, cols);
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      c(i, j) = integer ? static_cast<double>(rng.UniformInt(4)) : rng.Uniform(-5.0, 5.0);
    }
  }
  return c;
}

TEST(SolveAssignment, FindsTheUniqueOptimumOfASmallSquareProblem) {
  // Rows 0/1/2 -> columns 1/0/2 cost 1 + 2 + 2 = 5; the other five permutations cost 6, 6, 7, 9, 11.
  Eigen::Matrix3d cost;
  cost << 4, 1, 3,  //
      2, 0, 5,      //
      3, 2, 2;

  const std::vector<int> assignment = SolveAssignment(cost);

  EXPECT_EQ(assignment, (std::vector<int>{1, 0, 2}));
}

TEST(SolveAssignment, BeatsGreedyRowByRowChoice) {
  // Greedy gives row 0 its cheapest column 0 (1) and row 1 column 1 (100): 101.
  // The optimum is 0 -> 1, 1 -> 0: 2 + 2 = 4.
  Eigen::Matrix2d cost;
  cost << 1, 2,  //
      2, 100;

  EXPECT_EQ(SolveAssignment(cost), (std::vector<int>{1, 0}));
}

TEST(SolveAssignment, LeavesOutTheRowsThatCostMostWhenThereAreMoreRowsThanColumns) {
  // One column, three rows: the cheapest row (1, cost 0.5) gets it.
  Eigen::MatrixXd cost(3, 1);
  cost << 2.0, 0.5, 1.0;

  EXPECT_EQ(SolveAssignment(cost), (std::vector<int>{-1, 0, -1}));
}

TEST(SolveAssignment, PicksTheCheapestColumnsWhenThereAreMoreColumnsThanRows) {
  // Row 0 prefers column 2 (0), row 1 also prefers column 2 (0.5) but column 0 (1) is cheaper
  // for it than column 1 (9) is for row 0: 0 + 1 = 1 beats 0.5 + 3 = 3.5.
  Eigen::MatrixXd cost(2, 3);
  cost << 3, 9, 0,  //
      1, 8, 0.5;

  EXPECT_EQ(SolveAssignment(cost), (std::vector<int>{2, 0}));
}

TEST(SolveAssignment, HandlesEmptyMatrices) {
  EXPECT_TRUE(SolveAssignment(Eigen::MatrixXd(0, 3)).empty());
  EXPECT_EQ(SolveAssignment(Eigen::MatrixXd(3, 0)), (std::vector<int>{-1, -1, -1}));
  EXPECT_TRUE(SolveAssignment(Eigen::MatrixXd(0, 0)).empty());
}

TEST(SolveAssignment, MatchesBruteForceOnSeededRandomRectangularMatrices) {
  // All sizes from 1x1 to 6x8 and 8x6 (7x7 and larger skipped for speed), three real-valued
  // matrices (negative costs included) and three with many ties (integers 0..3) per size.
  core::Rng rng(1955);  // Kuhn's year
  for (int rows = 1; rows <= 8; ++rows) {
    for (int cols = 1; cols <= 8; ++cols) {
      if (rows > 6 && cols > 6) continue;
      for (int trial = 0; trial < 6; ++trial) {
        const Eigen::MatrixXd cost = RandomCost(rows, cols, rng, trial >= 3);

        const std::vector<int> assignment = SolveAssignment(cost);

        const double total = CheckedTotal(cost, assignment);
        EXPECT_NEAR(total, BruteForceMinimum(cost), 1e-9) << rows << "x" << cols << " trial " << trial << "\n" << cost;
      }
    }
  }
}

TEST(SolveAssignment, IsInvariantToAddingAConstantToARow) {
  // Adding 10 to every entry of row 1 adds 10 to every full assignment, so the optimum is the same.
  core::Rng rng(3);
  const Eigen::MatrixXd cost = RandomCost(4, 4, rng, false);
  Eigen::MatrixXd shifted = cost;
  shifted.row(1).array() += 10.0;

  EXPECT_EQ(SolveAssignment(cost), SolveAssignment(shifted));
}

}  // namespace
}  // namespace mirage::estimation
