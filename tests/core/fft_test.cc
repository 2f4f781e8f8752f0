// SPDX-License-Identifier: MIT
#include "mirage/core/fft.h"

#include <cmath>
#include <cstddef>
#include <numbers>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/core/rng.h"
#include "rng_vectors.h"

namespace mirage::core {
namespace {

constexpr double kTol = 1e-12;

// e^{j 2 pi k n / N}
Complex Twiddle(std::size_t k, std::size_t n, std::size_t size) {
  const double angle = 2.0 * std::numbers::pi * static_cast<double>(k * n % size) / static_cast<double>(size);
  return {std::cos(angle), std::sin(angle)};
}

std::vector<Complex> RandomSignal(std::size_t size, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Complex> x(size);
  for (auto& v : x) {
    const Vec2 re_im = testing::NormalVec2(rng);
    v = Complex(re_im.x(), re_im.y());
  }
  return x;
}

// True when n has no prime factor other than 2, 3 and 5.
bool IsFiveSmooth(std::size_t n) {
  for (const std::size_t f : {2U, 3U, 5U}) {
    while (n % f == 0) n /= f;
  }
  return n == 1;
}

void ExpectComplexNear(Complex actual, Complex expected, double tol, const char* what, std::size_t index) {
  EXPECT_NEAR(actual.real(), expected.real(), tol) << what << "[" << index << "]";
  EXPECT_NEAR(actual.imag(), expected.imag(), tol) << what << "[" << index << "]";
}

// ---------------------------------------------------------------------------------------------
// Forward / Inverse
// ---------------------------------------------------------------------------------------------

TEST(Fft, ReportsItsLength) {
  const Fft fft(12);

  EXPECT_EQ(fft.size(), 12U);
}

TEST(Fft, ForwardOfAnImpulseAtZeroIsFlat) {
  // x = delta[n] -> X[k] = sum_n delta[n] e^{-j..} = 1 for every k.
  const std::size_t n = 8;
  const Fft fft(n);
  std::vector<Complex> x(n, Complex(0, 0)), spectrum(n);
  x[0] = 1.0;

  fft.Forward(x, spectrum);

  for (std::size_t k = 0; k < n; ++k) ExpectComplexNear(spectrum[k], Complex(1, 0), kTol, "X", k);
}

TEST(Fft, ForwardOfADelayedImpulseIsALinearPhase) {
  // x = delta[n - 3], N = 10 -> X[k] = e^{-j 2 pi 3 k / 10} (the forward sign is negative).
  const std::size_t n = 10, delay = 3;
  const Fft fft(n);
  std::vector<Complex> x(n, Complex(0, 0)), spectrum(n);
  x[delay] = 1.0;

  fft.Forward(x, spectrum);

  for (std::size_t k = 0; k < n; ++k) ExpectComplexNear(spectrum[k], std::conj(Twiddle(k, delay, n)), kTol, "X", k);
}

TEST(Fft, ForwardOfAComplexExponentialIsASingleBinOfHeightN) {
  // x[n] = 2 e^{+j 2 pi 5 n / 12} -> X[5] = 2 * 12 = 24, all other bins 0 (orthogonality).
  const std::size_t n = 12, bin = 5;
  const Fft fft(n);
  std::vector<Complex> x(n), spectrum(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = 2.0 * Twiddle(bin, i, n);

  fft.Forward(x, spectrum);

  for (std::size_t k = 0; k < n; ++k) {
    ExpectComplexNear(spectrum[k], k == bin ? Complex(24, 0) : Complex(0, 0), 1e-11, "X", k);
  }
}

TEST(Fft, ForwardPutsANegativeFrequencyInTheUpperHalf) {
  // x[n] = e^{-j 2 pi n / 16} = e^{+j 2 pi 15 n / 16} -> X[15] = 16.
  const std::size_t n = 16;
  const Fft fft(n);
  std::vector<Complex> x(n), spectrum(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = std::conj(Twiddle(1, i, n));

  fft.Forward(x, spectrum);

  for (std::size_t k = 0; k < n; ++k) {
    ExpectComplexNear(spectrum[k], k == n - 1 ? Complex(16, 0) : Complex(0, 0), 1e-11, "X", k);
  }
}

TEST(Fft, InverseOfASingleBinIsAComplexExponentialScaledByOneOverN) {
  // X[k] = N delta[k - 2] -> x[n] = (1/N) N e^{+j 2 pi 2 n / N}.
  const std::size_t n = 9, bin = 2;
  const Fft fft(n);
  std::vector<Complex> spectrum(n, Complex(0, 0)), x(n);
  spectrum[bin] = static_cast<double>(n);

  fft.Inverse(spectrum, x);

  for (std::size_t i = 0; i < n; ++i) ExpectComplexNear(x[i], Twiddle(bin, i, n), kTol, "x", i);
}

TEST(Fft, InverseUndoesForwardForPowerOfTwoSmoothAndPrimeLengths) {
  for (const std::size_t n : {std::size_t{1}, std::size_t{7}, std::size_t{30}, std::size_t{64}, std::size_t{1080},
                              std::size_t{1031}}) {
    const Fft fft(n);
    const std::vector<Complex> x = RandomSignal(n, 100 + n);
    std::vector<Complex> spectrum(n), back(n);

    fft.Forward(x, spectrum);
    fft.Inverse(spectrum, back);

    for (std::size_t i = 0; i < n; ++i) ExpectComplexNear(back[i], x[i], 1e-12, "x", i);
  }
}

TEST(Fft, ForwardSatisfiesParseval) {
  // sum |x|^2 = (1/N) sum |X|^2.
  const std::size_t n = 60;
  const Fft fft(n);
  const std::vector<Complex> x = RandomSignal(n, 7);
  std::vector<Complex> spectrum(n);

  fft.Forward(x, spectrum);

  double energy_time = 0.0, energy_freq = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    energy_time += std::norm(x[i]);
    energy_freq += std::norm(spectrum[i]);
  }
  EXPECT_NEAR(energy_freq / static_cast<double>(n), energy_time, 1e-10 * energy_time);
}

TEST(Fft, ForwardAndInverseWorkInPlaceOnAliasedSpans) {
  const std::size_t n = 24;
  const Fft fft(n);
  const std::vector<Complex> x = RandomSignal(n, 11);
  std::vector<Complex> expected(n);
  fft.Forward(x, expected);

  std::vector<Complex> buffer = x;
  fft.Forward(buffer, buffer);

  for (std::size_t k = 0; k < n; ++k) ExpectComplexNear(buffer[k], expected[k], kTol, "X", k);

  fft.Inverse(buffer, buffer);

  for (std::size_t i = 0; i < n; ++i) ExpectComplexNear(buffer[i], x[i], kTol, "x", i);
}

TEST(Fft, AMovedTransformKeepsWorkingAndTheSourceIsEmptied) {
  // Impulse at 1, N = 4: X[k] = e^{-j pi k / 2} = 1, -j, -1, j.
  Fft source(4);
  Fft moved(std::move(source));
  Fft assigned(2);
  assigned = std::move(moved);
  std::vector<Complex> x{0.0, 1.0, 0.0, 0.0}, spectrum(4);

  assigned.Forward(x, spectrum);

  EXPECT_EQ(assigned.size(), 4U);
  EXPECT_EQ(source.size(), 0U);  // NOLINT(bugprone-use-after-move): documented moved-from state
  EXPECT_EQ(moved.size(), 0U);   // NOLINT(bugprone-use-after-move)
  ExpectComplexNear(spectrum[0], Complex(1, 0), kTol, "X", 0);
  ExpectComplexNear(spectrum[1], Complex(0, -1), kTol, "X", 1);
  ExpectComplexNear(spectrum[2], Complex(-1, 0), kTol, "X", 2);
  ExpectComplexNear(spectrum[3], Complex(0, 1), kTol, "X", 3);
}

// ---------------------------------------------------------------------------------------------
// NextFastFftSize
// ---------------------------------------------------------------------------------------------

TEST(NextFastFftSize, ReturnsTheNextTwoThreeFiveSmoothLength) {
  EXPECT_EQ(NextFastFftSize(1), 1U);
  EXPECT_EQ(NextFastFftSize(7), 8U);
  EXPECT_EQ(NextFastFftSize(11), 12U);
  EXPECT_EQ(NextFastFftSize(13), 15U);
  EXPECT_EQ(NextFastFftSize(30), 30U);     // 2 * 3 * 5 is already fast
  EXPECT_EQ(NextFastFftSize(97), 100U);    // 2^2 5^2
  EXPECT_EQ(NextFastFftSize(1025), 1080U); // 2^3 3^3 5; 1026..1079 all have another prime factor
  EXPECT_EQ(NextFastFftSize(1153), 1200U); // 2^4 3 5^2; 1152 = 2^7 3^2 is just below
}

TEST(NextFastFftSize, TreatsZeroAsOne) {
  EXPECT_EQ(NextFastFftSize(0), 1U);
}

TEST(NextFastFftSize, IsTheSmallestSmoothLengthNotBelowTheInputUpTo3000) {
  for (std::size_t n = 1; n <= 3000; ++n) {
    const std::size_t fast = NextFastFftSize(n);

    ASSERT_GE(fast, n);
    ASSERT_TRUE(IsFiveSmooth(fast)) << n << " -> " << fast;
    for (std::size_t m = n; m < fast; ++m) ASSERT_FALSE(IsFiveSmooth(m)) << n << " skips " << m;
  }
}

}  // namespace
}  // namespace mirage::core
