// SPDX-License-Identifier: MIT
#include "mirage/channel/raised_cosine_pulse.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "core/options_descriptor_expectations.h"
#include "mirage/core/constants.h"

namespace mirage::channel {
namespace {

using core::kPi;

PulseOptions Options(double duration_s, double rolloff = 0.5) {
  PulseOptions options;
  options.duration_s = duration_s;
  options.rolloff = rolloff;
  return options;
}

// Composite Simpson rule for g over [a, b] with n (even) intervals.
template <typename G>
double Simpson(const G& g, double a, double b, int n) {
  const double h = (b - a) / n;
  double sum = g(a) + g(b);
  for (int i = 1; i < n; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * g(a + i * h);
  return sum * h / 3.0;
}

// Closed-form RMS bandwidth of the unit-energy RC spectrum (derivation in the test below).
double ClosedFormRmsBandwidth(double duration_s, double beta) {
  const double a = (1.0 - beta) / 2.0;
  const double b = (1.0 + beta) / 2.0;
  const double numerator =
      2.0 * a * a * a / 3.0 +
      2.0 * ((b * b * b - a * a * a) / 8.0 - beta * beta / (kPi * kPi) + beta * beta * beta / (16.0 * kPi * kPi));
  return std::sqrt(numerator / (1.0 - beta / 4.0)) / duration_s;
}

// Direct integral R(tau) = 2 int_0^edge |P(f)|^2 cos(2 pi f tau) df.
double DirectAutocorrelation(const RaisedCosinePulse& pulse, double tau_s) {
  return 2.0 * Simpson(
                   [&](double f) {
                     const double p = pulse.Spectrum(f);
                     return p * p * std::cos(2.0 * kPi * f * tau_s);
                   },
                   0.0, pulse.band_edge_hz(), 20000);
}

TEST(RaisedCosinePulse, ValueHasUnitEnergy) {
  // int p(t)^2 dt over +-64 T_p; the tails decay as 1/t^3, so the energy beyond is ~1e-11.
  // p is band-limited to 1.5 GHz, so Simpson with step T_p/64 (128 GHz) is essentially exact.
  for (const double duration_s : {0.5e-9, 1e-9}) {
    const RaisedCosinePulse pulse(Options(duration_s));
    const double energy = Simpson(
        [&](double t) {
          const double p = pulse.Value(t);
          return p * p;
        },
        -64.0 * duration_s, 64.0 * duration_s, 8192);
    EXPECT_NEAR(energy, 1.0, 1e-6) << "T_p = " << duration_s;
  }
}

TEST(RaisedCosinePulse, SpectrumHasUnitEnergyAndVanishesBeyondTheBandEdge) {
  const RaisedCosinePulse pulse(Options(0.5e-9));
  const double edge = pulse.band_edge_hz();  // (1 + 0.5) / (2 * 0.5 ns) = 1.5 GHz
  ASSERT_DOUBLE_EQ(edge, 1.5e9);

  const double energy = Simpson(
      [&](double f) {
        const double p = pulse.Spectrum(f);
        return p * p;
      },
      -edge, edge, 40000);

  EXPECT_NEAR(energy, 1.0, 1e-9);
  EXPECT_EQ(pulse.Spectrum(1.5001e9), 0.0);
  EXPECT_EQ(pulse.Spectrum(-2e9), 0.0);
  // Flat part: P(0) = T / sqrt(T (1 - beta/4)) = sqrt(0.5 ns / 0.875).
  EXPECT_NEAR(pulse.Spectrum(0.0), std::sqrt(0.5e-9 / 0.875), 1e-12 * std::sqrt(0.5e-9));
  // Roll-off middle at f = 1/(2T) = 1 GHz: half the flat value.
  EXPECT_NEAR(pulse.Spectrum(1e9), 0.5 * pulse.Spectrum(0.0), 1e-9 * pulse.Spectrum(0.0));
}

TEST(RaisedCosinePulse, ValueIsTheInverseFourierTransformOfTheSpectrum) {
  // p(t) = 2 int_0^edge P(f) cos(2 pi f t) df (P real and even). t = T/(2 beta) = 1.2 T_p is the
  // removable singularity of Eq. (A.19) for beta = 5/12.
  for (const double beta : {0.5, 5.0 / 12.0}) {
    const RaisedCosinePulse pulse(Options(0.5e-9, beta));
    for (const double u : {0.0, 0.3, 1.0, 1.2, 1.7, 3.4}) {
      const double t = u * 0.5e-9;
      const double direct =
          2.0 * Simpson([&](double f) { return pulse.Spectrum(f) * std::cos(2.0 * kPi * f * t); }, 0.0,
                        pulse.band_edge_hz(), 20000);
      EXPECT_NEAR(pulse.Value(t), direct, 1e-6 * pulse.Value(0.0)) << "beta " << beta << " t/T " << u;
    }
  }
}

TEST(RaisedCosinePulse, ValuePeaksAtOneOverSqrtEnergyAndCrossesZeroAtMultiplesOfTp) {
  // p(0) = 1 / sqrt(T (1 - beta/4)); sinc zeros at t = k T (k != 0), and at t = T the cos/denominator
  // factor is the removable singularity for beta = 0.5.
  const RaisedCosinePulse pulse(Options(0.5e-9));
  const double peak = 1.0 / std::sqrt(0.5e-9 * 0.875);

  EXPECT_NEAR(pulse.Value(0.0), peak, 1e-12 * peak);
  EXPECT_NEAR(pulse.Value(0.5e-9), 0.0, 1e-9 * peak);
  EXPECT_NEAR(pulse.Value(-1.0e-9), 0.0, 1e-9 * peak);
  EXPECT_NEAR(pulse.Value(1.5e-9), 0.0, 1e-9 * peak);
  EXPECT_EQ(pulse.Value(0.37e-9), pulse.Value(-0.37e-9));
}

TEST(RaisedCosinePulse, RmsBandwidthMatchesTheClosedFormAndTheDigest) {
  // With nu = f T, a = (1 - beta)/2, b = (1 + beta)/2, the unit-height RC spectrum is 1 on
  // |nu| <= a and cos^2(pi x / (2 beta)), x = |nu| - a, on the roll-off. Using
  // cos^4 = 3/8 + cos(2th)/2 + cos(4th)/8 and int_0^beta (a + x)^2 cos(k pi x / beta) dx
  // = -2 beta^2 / (k pi)^2 (a - (a + beta)(-1)^k):
  //   int nu^2 X^2 = 2a^3/3 + 2 [(b^3 - a^3)/8 - beta^2/pi^2 + beta^3/(16 pi^2)],
  //   int X^2 = 1 - beta/4,   beta_rms = sqrt(ratio) / T.
  // beta_R = 0.5: ratio = 0.0718884 -> 0.268120 / T: 0.5362 GHz at 0.5 ns, 0.2681 GHz at 1 ns
  // (digest Sec. 2.9: ~0.536 and ~0.268 GHz).
  const RaisedCosinePulse half(Options(0.5e-9));
  const RaisedCosinePulse one(Options(1e-9));

  EXPECT_NEAR(half.rms_bandwidth_hz(), ClosedFormRmsBandwidth(0.5e-9, 0.5), 1e-6 * half.rms_bandwidth_hz());
  EXPECT_NEAR(half.rms_bandwidth_hz(), 0.536e9, 0.001e9);
  EXPECT_NEAR(one.rms_bandwidth_hz(), 0.268e9, 0.001e9);
  // Scaling 1/T_p.
  EXPECT_NEAR(half.rms_bandwidth_hz() / one.rms_bandwidth_hz(), 2.0, 1e-9);
}

TEST(RaisedCosinePulse, RmsBandwidthMatchesTheClosedFormAtBothRollOffExtremes) {
  // beta = 0: flat spectrum of width 1/T -> 1/(T sqrt 12).
  // beta = 1: (1/4 - 15/(8 pi^2)) / (3/4) = 1/3 - 5/(2 pi^2) -> sqrt(that) / T.
  const RaisedCosinePulse flat(Options(0.5e-9, 0.0));
  const RaisedCosinePulse full(Options(0.5e-9, 1.0));

  EXPECT_NEAR(flat.rms_bandwidth_hz(), 1.0 / (0.5e-9 * std::sqrt(12.0)), 1e-6 * flat.rms_bandwidth_hz());
  EXPECT_NEAR(full.rms_bandwidth_hz(), std::sqrt(1.0 / 3.0 - 2.5 / (kPi * kPi)) / 0.5e-9,
              1e-6 * full.rms_bandwidth_hz());
  EXPECT_NEAR(full.rms_bandwidth_hz(), ClosedFormRmsBandwidth(0.5e-9, 1.0), 1e-6 * full.rms_bandwidth_hz());
}

TEST(RaisedCosinePulse, RangeSigmaAtUnitSinrIsAbout6Point3Centimetres) {
  // c / (sqrt(8) pi beta_rms) = 299792458 / (2.8284 * 3.1416 * 0.53624e9) = 0.06292 m (digest 2.9).
  const RaisedCosinePulse half(Options(0.5e-9));
  const RaisedCosinePulse one(Options(1e-9));

  EXPECT_NEAR(half.range_sigma_at_unit_sinr_m(core::kSpeedOfLight_mps), 0.06292, 0.00005);
  EXPECT_NEAR(one.range_sigma_at_unit_sinr_m(core::kSpeedOfLight_mps), 0.12583, 0.0001);
}

TEST(RaisedCosinePulse, RangeSigmaAtUnitSinrScalesWithTheSpeedOfTheMedium) {
  // The pulse fixes the delay resolution; the medium turns it into metres: sound at 343 m/s
  // resolves 343 / 299792458 as finely as radio with the same pulse.
  const RaisedCosinePulse pulse(Options(0.5e-9));

  const double radio_m = pulse.range_sigma_at_unit_sinr_m(core::kSpeedOfLight_mps);
  const double sound_m = pulse.range_sigma_at_unit_sinr_m(343.0);

  EXPECT_NEAR(sound_m / radio_m, 343.0 / core::kSpeedOfLight_mps, 1e-15);
  EXPECT_DOUBLE_EQ(sound_m, 343.0 / (std::sqrt(8.0) * core::kPi * pulse.rms_bandwidth_hz()));
}

TEST(RaisedCosinePulse, EffectiveDurationMatchesTheIntegralOfPToTheFourth) {
  // Closed form: int X^4 = T^3 [(1 - beta) + 2 * 35 beta / 128] (int_0^{pi/2} cos^8 = 35 pi / 256),
  // (int X^2)^2 = T^2 (1 - beta/4)^2, so T_eff = T (1 - 29 beta / 64) / (1 - beta/4)^2:
  // beta = 0.5 -> 0.7734375 / 0.765625 T = 1.010204 T = 0.505102 ns.
  const RaisedCosinePulse pulse(Options(0.5e-9));
  const double direct = Simpson(
      [&](double f) {
        const double p = pulse.Spectrum(f);
        return p * p * p * p;
      },
      -pulse.band_edge_hz(), pulse.band_edge_hz(), 40000);

  EXPECT_NEAR(pulse.effective_duration_s(), direct, 1e-6 * direct);
  EXPECT_NEAR(pulse.effective_duration_s(), 0.5e-9 * (1.0 - 29.0 * 0.5 / 64.0) / (0.875 * 0.875), 1e-6 * direct);
  // beta = 0: T_eff = T; beta = 1: 35/36 T.
  EXPECT_NEAR(RaisedCosinePulse(Options(1e-9, 0.0)).effective_duration_s(), 1e-9, 1e-15);
  EXPECT_NEAR(RaisedCosinePulse(Options(1e-9, 1.0)).effective_duration_s(), 35.0 / 36.0 * 1e-9, 1e-15);
}

TEST(RaisedCosinePulse, AutocorrelationIsOneAtZeroAndSymmetric) {
  const RaisedCosinePulse pulse(Options(0.5e-9));

  EXPECT_DOUBLE_EQ(pulse.Autocorrelation(0.0), 1.0);
  for (const double tau : {0.013e-9, 0.21e-9, 0.77e-9, 2.3e-9}) {
    EXPECT_EQ(pulse.Autocorrelation(tau), pulse.Autocorrelation(-tau)) << tau;
    EXPECT_LT(pulse.Autocorrelation(tau), 1.0) << tau;
  }
}

TEST(RaisedCosinePulse, AutocorrelationMatchesADirectIntegralOfTheSpectrum) {
  // The table has step T/64 with linear interpolation: error <= h^2/8 |R''| = (7.8 ps)^2 / 8 *
  // (2 pi 0.536 GHz)^2 ~ 9e-5.
  const RaisedCosinePulse pulse(Options(0.5e-9));

  for (const double tau : {0.013e-9, 0.1e-9, 0.37e-9, 0.5e-9, 0.61e-9, 1.0e-9, 2.3e-9, 4.1e-9}) {
    EXPECT_NEAR(pulse.Autocorrelation(tau), DirectAutocorrelation(pulse, tau), 1.5e-4) << "tau " << tau;
  }
}

TEST(RaisedCosinePulse, AutocorrelationVanishesBeyondItsSupportWhereItIsNegligible) {
  const RaisedCosinePulse pulse(Options(0.5e-9));
  const double support = pulse.autocorrelation_support_s();

  // The support covers at least the main lobe and at most the 32 T_p the table spans.
  EXPECT_GT(support, 2.0 * 0.5e-9);
  EXPECT_LE(support, 32.0 * 0.5e-9);
  EXPECT_EQ(pulse.Autocorrelation(support * 1.01), 0.0);
  EXPECT_EQ(pulse.Autocorrelation(-support * 1.5), 0.0);
  for (const double factor : {1.0, 1.13, 1.5, 2.0}) {
    EXPECT_LT(std::abs(DirectAutocorrelation(pulse, factor * support)), 1e-4) << "factor " << factor;
  }
}

TEST(RaisedCosinePulse, ValidateAcceptsTheDefaultsAndRejectsBadOptions) {
  EXPECT_TRUE(Validate(PulseOptions{}).empty());
  EXPECT_TRUE(Validate(Options(1e-9, 0.0)).empty());
  EXPECT_TRUE(Validate(Options(1e-9, 1.0)).empty());

  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const double rolloff : {-0.1, 1.1, nan}) EXPECT_EQ(Validate(Options(0.5e-9, rolloff)).size(), 1u) << rolloff;
  for (const double duration : {0.0, -1e-9, inf, nan}) EXPECT_EQ(Validate(Options(duration)).size(), 1u) << duration;
  PulseOptions no_carrier;
  no_carrier.carrier_hz = 0.0;
  EXPECT_EQ(Validate(no_carrier).size(), 1u);
  PulseOptions all_bad;
  all_bad.carrier_hz = -1.0;
  all_bad.rolloff = 2.0;
  all_bad.duration_s = 0.0;
  EXPECT_EQ(Validate(all_bad).size(), 3u);
}

TEST(PulseOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMember) {
  test::ExpectDescribesEveryMember(PulseOptionsDescriptor(), {"carrier_hz", "rolloff", "duration_s"});
}

TEST(PulseOptions, ValidateNamesTheKeyTheValueAndTheRange) {
  EXPECT_EQ(Validate(Options(0.5e-9, 1.5)),
            std::vector<std::string>{"rolloff: 1.5 is out of range, expected a number in [0, 1]"});
  EXPECT_EQ(Validate(Options(0.0)).size(), 1u);
}

}  // namespace
}  // namespace mirage::channel
