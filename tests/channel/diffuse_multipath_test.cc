// SPDX-License-Identifier: MIT
#include "core/options_descriptor_expectations.h"
#include "mirage/channel/diffuse_multipath.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace mirage::channel {
namespace {

DiffuseOptions Options(double decay_s, double rise_s, double rise_weight) {
  DiffuseOptions options;
  options.decay_s = decay_s;
  options.rise_s = rise_s;
  options.rise_weight = rise_weight;
  return options;
}

// Composite Simpson rule for g over [0, b] with n (even) intervals.
template <typename G>
double Simpson(const G& g, double b, int n) {
  const double h = b / n;
  double sum = g(0.0) + g(b);
  for (int i = 1; i < n; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * g(i * h);
  return sum * h / 3.0;
}

TEST(DiffusePdpShape, IntegratesToOne) {
  // Integrate over [0, 25 gamma_1]: the tail beyond holds e^{-25} ~ 1e-11 of the area.
  for (const auto& options : {DiffuseOptions{}, Options(20e-9, 5e-9, 0.0), Options(20e-9, 5e-9, 1.0),
                              Options(8e-9, 2e-9, 0.5), Options(35e-9, 12e-9, 0.9)}) {
    const double area =
        Simpson([&](double t) { return DiffusePdpShape(options, t); }, 25.0 * options.decay_s, 50000);
    EXPECT_NEAR(area, 1.0, 1e-8) << "gamma_1 " << options.decay_s << " gamma_rise " << options.rise_s << " chi "
                                 << options.rise_weight;
  }
}

TEST(DiffusePdpShape, IsZeroBeforeTheLineOfSight) {
  const DiffuseOptions options;

  EXPECT_EQ(DiffusePdpShape(options, -1e-12), 0.0);
  EXPECT_EQ(DiffusePdpShape(options, -5e-9), 0.0);
  EXPECT_GT(DiffusePdpShape(options, 1e-12), 0.0);
}

TEST(DiffusePdpShape, StartsAtTheGoldenValueForEachRiseWeight) {
  // At t = 0: (1 - chi) / A, A = gamma_1 - chi gamma_1 gamma_rise / (gamma_1 + gamma_rise).
  //   chi = 0: 1 / gamma_1 = 5e7 /s;   chi = 1: 0;
  //   chi = 0.98 (defaults): 0.02 / (20 ns - 0.98 * 100 / 25 ns) = 0.02 / 16.08 ns = 1.2438e6 /s.
  EXPECT_NEAR(DiffusePdpShape(Options(20e-9, 5e-9, 0.0), 0.0), 5e7, 1e-3);
  EXPECT_EQ(DiffusePdpShape(Options(20e-9, 5e-9, 1.0), 0.0), 0.0);
  EXPECT_NEAR(DiffusePdpShape(DiffuseOptions{}, 0.0), 0.02 / 16.08e-9, 1e-6 * 0.02 / 16.08e-9);
}

TEST(DiffusePdpShape, DecaysWithTheDecayTimeConstantLongAfterTheRise) {
  // For t >> gamma_rise the shape is ~ e^{-t/gamma_1} / A: one gamma_1 later it is e^{-1} times
  // as large (the rise term is e^{-20} and e^{-24} there).
  const DiffuseOptions options;
  const double t = 100e-9;

  EXPECT_NEAR(DiffusePdpShape(options, t + 20e-9) / DiffusePdpShape(options, t), std::exp(-1.0), 1e-8);
}

TEST(DiffusePdpShape, PeaksAtTheAnalyticArgmax) {
  // d/dt [(1 - chi e^{-t/g_r}) e^{-t/g_1}] = 0 <=> chi e^{-t/g_r} (g_1 + g_r) / g_r = 1
  // <=> t* = g_r ln(chi (g_1 + g_r) / g_r) = 5 ns * ln(4.9) = 7.9462 ns for the defaults. There,
  // chi e^{-t*/g_r} = g_r / (g_1 + g_r) = 0.2, so the peak is 0.8 e^{-t*/g_1} / 16.08 ns.
  const DiffuseOptions options;
  const double t_star = 5e-9 * std::log(0.98 * 25.0 / 5.0);
  ASSERT_NEAR(t_star, 7.9462e-9, 1e-13);

  // Grid search with 1 ps steps over [0, 40 ns].
  double best_t = 0.0;
  double best = 0.0;
  for (int i = 0; i <= 40000; ++i) {
    const double t = i * 1e-12;
    const double v = DiffusePdpShape(options, t);
    if (v > best) {
      best = v;
      best_t = t;
    }
  }

  EXPECT_NEAR(best_t, t_star, 1e-12);
  const double peak = 0.8 * std::exp(-t_star / 20e-9) / 16.08e-9;
  EXPECT_NEAR(DiffusePdpShape(options, t_star), peak, 1e-9 * peak);
}

TEST(DiffusePdpShape, HasItsPeakAtTheLosWithoutARise) {
  // chi = 0: plain exponential, maximal at t = 0 and halving every gamma_1 ln 2.
  const DiffuseOptions options = Options(20e-9, 5e-9, 0.0);

  EXPECT_GT(DiffusePdpShape(options, 0.0), DiffusePdpShape(options, 1e-12));
  EXPECT_NEAR(DiffusePdpShape(options, 20e-9 * std::log(2.0)), 0.5 / 20e-9, 1e-3);
}

TEST(DiffuseOptions, ValidateAcceptsTheDefaultsAndRejectsBadOptions) {
  EXPECT_TRUE(Validate(DiffuseOptions{}).empty());
  EXPECT_TRUE(Validate(Options(20e-9, 5e-9, 0.0)).empty());
  EXPECT_TRUE(Validate(Options(20e-9, 5e-9, 1.0)).empty());

  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(Validate(Options(0.0, 5e-9, 0.5)).size(), 1u);
  EXPECT_EQ(Validate(Options(inf, 5e-9, 0.5)).size(), 1u);
  EXPECT_EQ(Validate(Options(20e-9, -1e-9, 0.5)).size(), 1u);
  EXPECT_EQ(Validate(Options(20e-9, nan, 0.5)).size(), 1u);
  EXPECT_EQ(Validate(Options(20e-9, 5e-9, 1.5)).size(), 1u);
  EXPECT_EQ(Validate(Options(20e-9, 5e-9, -0.1)).size(), 1u);
  EXPECT_EQ(Validate(Options(20e-9, 5e-9, nan)).size(), 1u);
  DiffuseOptions power;
  power.power_ratio_db = inf;
  EXPECT_EQ(Validate(power).size(), 1u);
  EXPECT_EQ(Validate(Options(-1.0, 0.0, 2.0)).size(), 3u);
}

TEST(DiffuseOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMember) {
  test::ExpectDescribesEveryMember(DiffuseOptionsDescriptor(),
                                   {"enabled", "power_ratio_db", "decay_s", "rise_s", "rise_weight"});
}

TEST(DiffuseOptions, ValidateNamesTheKeyTheValueAndTheRange) {
  DiffuseOptions options;
  options.decay_s = 0.0;
  EXPECT_EQ(Validate(options),
            std::vector<std::string>{"decay_s: 0 s is out of range, expected a number in [1e-12, 1] s"});
}

}  // namespace
}  // namespace mirage::channel
