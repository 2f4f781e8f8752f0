// SPDX-License-Identifier: MIT
#include "mirage/core/rng.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace mirage::core {
namespace {

TEST(Rng, SameSeedAndStreamGiveTheSameSequence) {
  Rng a(42, 7), b(42, 7);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.NextU64(), b.NextU64());
}

TEST(Rng, DifferentStreamsGiveDifferentSequences) {
  Rng a(42, 0), b(42, 1);
  int equal = 0;
  for (int i = 0; i < 100; ++i) equal += a.NextU64() == b.NextU64() ? 1 : 0;
  EXPECT_EQ(equal, 0);
}

TEST(Rng, SubstreamsAreIndependentOfHowMuchTheParentWasUsed) {
  Rng a(5, 3), b(5, 3);
  for (int i = 0; i < 10; ++i) b.NextU64();
  Rng sa = a.Substream("noise"), sb = b.Substream("noise");
  EXPECT_EQ(sa.NextU64(), sb.NextU64());
  EXPECT_NE(a.Substream("noise").NextU64(), a.Substream("diffuse").NextU64());
}

TEST(Rng, UniformMomentsMatchTheDistribution) {
  Rng rng(1);
  const int n = 200000;
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double u = rng.Uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sum2 += u * u;
  }
  EXPECT_NEAR(sum / n, 0.5, 0.005);
  EXPECT_NEAR(sum2 / n - (sum / n) * (sum / n), 1.0 / 12.0, 0.002);
}

TEST(Rng, NormalHasUnitVarianceAndZeroMean) {
  Rng rng(2);
  const int n = 200000;
  double sum = 0.0, sum2 = 0.0, sum4 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = rng.Normal();
    sum += x;
    sum2 += x * x;
    sum4 += x * x * x * x;
  }
  EXPECT_NEAR(sum / n, 0.0, 0.01);
  EXPECT_NEAR(sum2 / n, 1.0, 0.01);
  EXPECT_NEAR(sum4 / n, 3.0, 0.06);  // Gaussian kurtosis
}

TEST(Rng, ComplexNormalSplitsTheVarianceBetweenRealAndImaginaryParts) {
  Rng rng(3);
  const int n = 200000;
  double re2 = 0.0, im2 = 0.0, cross = 0.0;
  for (int i = 0; i < n; ++i) {
    const Complex z = rng.ComplexNormal(4.0);
    re2 += z.real() * z.real();
    im2 += z.imag() * z.imag();
    cross += z.real() * z.imag();
  }
  EXPECT_NEAR(re2 / n, 2.0, 0.03);
  EXPECT_NEAR(im2 / n, 2.0, 0.03);
  EXPECT_NEAR(cross / n, 0.0, 0.03);
}

TEST(Rng, PoissonMeanAndVarianceEqualTheRate) {
  for (const double mean : {0.5, 3.0, 50.0}) {
    Rng rng(4);
    const int n = 100000;
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < n; ++i) {
      const double k = rng.Poisson(mean);
      sum += k;
      sum2 += k * k;
    }
    const double m = sum / n;
    EXPECT_NEAR(m, mean, 0.02 * mean + 0.01) << mean;
    EXPECT_NEAR(sum2 / n - m * m, mean, 0.05 * mean + 0.02) << mean;
  }
}

TEST(Rng, UniformIntCoversTheRangeEvenly) {
  Rng rng(9);
  std::vector<int> counts(7, 0);
  for (int i = 0; i < 70000; ++i) ++counts[rng.UniformInt(7)];
  for (const int c : counts) EXPECT_NEAR(c, 10000, 400);
}

}  // namespace
}  // namespace mirage::core
