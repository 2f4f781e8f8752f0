// SPDX-License-Identifier: MIT
// The Rician CDF against the empirical CDF of 200,000 seeded draws of |a + n| (both branches:
// the Poisson mixture and the Gaussian approximation), its limits, and the moment fit recovering
// the law that generated a sample.
#include "mirage/estimation/gates/rician_gate.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/core/rng.h"

namespace mirage::estimation {
namespace {

std::vector<double> Draw(const RicianLaw& law, int n, std::uint64_t seed) {
  core::Rng rng(seed, 0);
  std::vector<double> r;
  for (int i = 0; i < n; ++i) r.push_back(std::abs(law.nu + rng.ComplexNormal(law.scatter_power)));
  std::sort(r.begin(), r.end());
  return r;
}

class RicianCdfTest : public ::testing::TestWithParam<double> {};

TEST_P(RicianCdfTest, MatchesTheEmpiricalCdf) {
  const double k = GetParam();
  const RicianLaw law{std::sqrt(k * 0.01), 0.01};
  const int n = 200000;
  const auto r = Draw(law, n, 7);
  for (const double q : {0.001, 0.01, 0.1, 0.5, 0.9, 0.99}) {
    const double x = r[static_cast<std::size_t>(q * n)];
    // Binomial standard error of the empirical CDF, 5 sigma (plus a little for the discrete step).
    const double tolerance = 5.0 * std::sqrt(q * (1.0 - q) / n) + 1e-5;
    EXPECT_NEAR(RicianCdf(x, law), q, tolerance) << "K = " << k << ", quantile " << q;
  }
}

INSTANTIATE_TEST_SUITE_P(RicianGate, RicianCdfTest, ::testing::Values(0.0, 0.5, 3.0, 30.0, 150.0, 500.0, 900.0, 2000.0, 5000.0));

TEST(RicianGate, Limits) {
  const RicianLaw law{0.2, 0.004};
  EXPECT_EQ(RicianCdf(0.0, law), 0.0);
  EXPECT_EQ(RicianCdf(-1.0, law), 0.0);
  EXPECT_NEAR(RicianCdf(10.0, law), 1.0, 1e-12);
  // Rayleigh: 1 - exp(-r^2 / s^2).
  EXPECT_NEAR(RicianCdf(0.1, {0.0, 0.02}), 1.0 - std::exp(-0.01 / 0.02), 1e-12);
  // Continuous across the switch of branches at K = 600.
  for (const double x : {0.19, 0.2, 0.21}) {
    EXPECT_NEAR(RicianCdf(x, {0.2, 0.04 / 599.0}), RicianCdf(x, {0.2, 0.04 / 601.0}), 2e-3);
  }
  // Monotone in r.
  double previous = 0.0;
  for (double x = 0.0; x < 0.5; x += 0.005) {
    const double c = RicianCdf(x, {0.2, 0.2 * 0.2 / 599.0});
    EXPECT_GE(c, previous - 1e-12);
    previous = c;
  }
}

TEST(RicianGate, MomentFitRecoversTheLaw) {
  const RicianLaw truth{0.3, 0.01};  // K = 9
  const auto r = Draw(truth, 100000, 11);
  double m1 = 0.0, m2 = 0.0;
  for (const double x : r) m1 += x * x;
  m1 /= static_cast<double>(r.size());
  for (const double x : r) m2 += (x * x - m1) * (x * x - m1);
  m2 /= static_cast<double>(r.size() - 1);
  const auto law = RicianFromMoments(m1, m2);
  ASSERT_TRUE(law.has_value());
  EXPECT_NEAR(law->nu, 0.3, 0.005);
  EXPECT_NEAR(law->scatter_power, 0.01, 0.001);
  EXPECT_FALSE(RicianFromMoments(0.0, 1.0).has_value());
  EXPECT_EQ(RicianFromMoments(1.0, 2.0)->nu, 0.0);  // more spread than Rayleigh: nu = 0
}

}  // namespace
}  // namespace mirage::estimation
