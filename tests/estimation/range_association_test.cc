// SPDX-License-Identifier: MIT
#include "mirage/estimation/range_association.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "mirage/core/rng.h"

namespace mirage::estimation {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

using Ranges = std::vector<double>;
using Assignment = std::vector<int>;

// The thesis's objective (Eq. 3.8 with the cut-off metric): an associated pair costs |d - z|, an
// expected range without a measurement costs d_c.
double CutoffCost(const Ranges& expected, const Ranges& measured, const Assignment& a, double cutoff) {
  double total = 0.0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    total += a[i] < 0 ? cutoff : std::abs(expected[i] - measured[static_cast<std::size_t>(a[i])]);
  }
  return total;
}

// Brute-force minimum of CutoffCost over all partial one-to-one associations whose pairs are
// closer than the cut-off.
double BruteForceCutoffMinimum(const Ranges& expected, const Ranges& measured, double cutoff) {
  std::vector<char> used(measured.size(), 0);
  double best = kInf;
  auto recurse = [&](auto&& self, std::size_t i, double sum) -> void {
    if (i == expected.size()) {
      best = std::min(best, sum);
      return;
    }
    self(self, i + 1, sum + cutoff);  // clutter / missed detection
    for (std::size_t j = 0; j < measured.size(); ++j) {
      const double d = std::abs(expected[i] - measured[j]);
      if (used[j] || d >= cutoff) continue;
      used[j] = 1;
      self(self, i + 1, sum + d);
      used[j] = 0;
    }
  };
  recurse(recurse, 0, 0.0);
  return best;
}

TEST(AssociateRanges, AssociatesEachExpectedRangeWithItsClosestMeasurement) {
  // d = {2, 5, 8}, z = {7.95, 2.04, 5.1}, d_c = 0.15: 0 -> 1, 1 -> 2, 2 -> 0.
  const Ranges expected{2.0, 5.0, 8.0}, measured{7.95, 2.04, 5.1};

  EXPECT_EQ(AssociateRanges(expected, measured, 0.15), (Assignment{1, 2, 0}));
}

TEST(AssociateRanges, RejectsAPairAtOrBeyondTheCutoff) {
  // Eq. (3.9): c_n = 0 when d^(d_c) >= d_c. |2 - 2.25| = 0.25 exactly (binary fractions), so it is
  // rejected at d_c = 0.25 and accepted at the next double above it; 0.3 is well beyond.
  const Ranges expected{2.0};

  EXPECT_EQ(AssociateRanges(expected, Ranges{2.25}, 0.25), (Assignment{-1}));
  EXPECT_EQ(AssociateRanges(expected, Ranges{2.25}, std::nextafter(0.25, 1.0)), (Assignment{0}));
  EXPECT_EQ(AssociateRanges(expected, Ranges{2.3}, 0.25), (Assignment{-1}));
  EXPECT_EQ(AssociateRanges(expected, Ranges{2.125}, 0.25), (Assignment{0}));
}

TEST(AssociateRanges, GlobalOptimumBeatsGreedyNearestNeighbour) {
  // d = {1.00, 1.10}, z = {1.08, 0.90}, d_c = 0.15.
  // Greedy in order: d0 takes its nearest z0 (0.08), d1 is left with z1 (0.20 >= d_c): one
  // association, cost 0.08 + 0.15 = 0.23.
  // Optimum: d0 -> z1 (0.10), d1 -> z0 (0.02): two associations, cost 0.12.
  const Ranges expected{1.00, 1.10}, measured{1.08, 0.90};

  const Assignment a = AssociateRanges(expected, measured, 0.15);

  EXPECT_EQ(a, (Assignment{1, 0}));
  EXPECT_NEAR(CutoffCost(expected, measured, a, 0.15), 0.12, 1e-12);
}

TEST(AssociateRanges, PrefersOneGoodPairOverTwoMediocreOnes) {
  // d = {3.00, 3.10}, z = {3.08, 3.20}, d_c = 0.15.
  // Two pairs d0 -> z0, d1 -> z1: 0.08 + 0.10 = 0.18. One pair d1 -> z0 (0.02) and d0 as clutter:
  // 0.02 + 0.15 = 0.17, which is the OSPA optimum.
  const Ranges expected{3.00, 3.10}, measured{3.08, 3.20};

  EXPECT_EQ(AssociateRanges(expected, measured, 0.15), (Assignment{-1, 0}));
}

TEST(AssociateRanges, HandlesFewerMeasurementsThanExpectedRanges) {
  const Ranges expected{2.0, 4.0, 6.0};

  EXPECT_EQ(AssociateRanges(expected, Ranges{4.05}, 0.2), (Assignment{-1, 0, -1}));
  EXPECT_EQ(AssociateRanges(expected, Ranges{5.9, 4.05}, 0.2), (Assignment{-1, 1, 0}));
  EXPECT_EQ(AssociateRanges(expected, Ranges{}, 0.2), (Assignment{-1, -1, -1}));
}

TEST(AssociateRanges, IgnoresClutterWhenThereAreMoreMeasurementsThanExpectedRanges) {
  const Ranges expected{3.0};

  EXPECT_EQ(AssociateRanges(expected, Ranges{1.0, 3.02, 7.0, 2.9}, 0.15), (Assignment{1}));
  EXPECT_TRUE(AssociateRanges(Ranges{}, Ranges{1.0, 2.0}, 0.15).empty());
}

TEST(AssociateRanges, UsesAMeasurementForAtMostOneExpectedRange) {
  // Two VAs predicted 1 cm apart and a single measurement between them.
  const Assignment a = AssociateRanges(Ranges{5.0, 5.01}, Ranges{5.004}, 0.15);

  EXPECT_EQ(a, (Assignment{0, -1}));  // 0.004 < 0.006
}

TEST(AssociateRanges, MatchesTheBruteForceCutoffOptimumOnSeededRandomCases) {
  // Ranges clustered in [3, 4] m so that cut-offs of 0.05-0.3 m create real conflicts.
  core::Rng rng(326);
  for (int trial = 0; trial < 300; ++trial) {
    const auto n = static_cast<std::size_t>(rng.UniformInt(6));
    const auto m = static_cast<std::size_t>(rng.UniformInt(6));
    const double cutoff = rng.Uniform(0.05, 0.3);
    Ranges expected(n), measured(m);
    for (auto& d : expected) d = rng.Uniform(3.0, 4.0);
    for (auto& z : measured) z = rng.Uniform(3.0, 4.0);

    const Assignment a = AssociateRanges(expected, measured, cutoff);

    ASSERT_EQ(a.size(), n);
    std::vector<int> uses(m, 0);
    for (std::size_t i = 0; i < n; ++i) {
      if (a[i] < 0) continue;
      ASSERT_LT(static_cast<std::size_t>(a[i]), m);
      EXPECT_EQ(++uses[static_cast<std::size_t>(a[i])], 1);
      EXPECT_LT(std::abs(expected[i] - measured[static_cast<std::size_t>(a[i])]), cutoff);
    }
    EXPECT_NEAR(CutoffCost(expected, measured, a, cutoff), BruteForceCutoffMinimum(expected, measured, cutoff), 1e-12)
        << "trial " << trial;
  }
}

TEST(AssociateWithCutoff, NeverAssociatesInfiniteDistances) {
  // Pairs ruled out beforehand (+inf) stay unassociated even when nothing else is available.
  Eigen::Matrix2d distance;
  distance << kInf, 0.05,  //
      0.01, kInf;
  Eigen::Matrix2d row_ruled_out;
  row_ruled_out << kInf, kInf,  //
      0.01, 0.02;

  EXPECT_EQ(AssociateWithCutoff(distance, 0.2), (Assignment{1, 0}));
  EXPECT_EQ(AssociateWithCutoff(row_ruled_out, 0.2), (Assignment{-1, 0}));
  EXPECT_EQ(AssociateWithCutoff(Eigen::MatrixXd::Constant(1, 1, kInf), 0.2), (Assignment{-1}));
  EXPECT_EQ(AssociateWithCutoff(Eigen::MatrixXd::Constant(3, 2, kInf), 0.2), (Assignment{-1, -1, -1}));
}

TEST(AssociateWithCutoff, RejectsEntriesAtTheCutoffAndKeepsThoseBelow) {
  // Row 0 only has 0.2 (= d_c, rejected); row 1 has 0.1999 (kept).
  Eigen::MatrixXd distance(2, 2);
  distance << 0.2, kInf,  //
      kInf, 0.1999;

  EXPECT_EQ(AssociateWithCutoff(distance, 0.2), (Assignment{-1, 1}));
}

}  // namespace
}  // namespace mirage::estimation
