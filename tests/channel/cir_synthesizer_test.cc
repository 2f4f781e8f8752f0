// SPDX-License-Identifier: MIT
#include "mirage/channel/cir_synthesizer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "core/options_descriptor_expectations.h"
#include "mirage/core/constants.h"
#include "mirage/core/rng.h"

namespace mirage::channel {
namespace {

using core::kSpeedOfLight_mps;

// Defaults (T_s = 0.125 ns, T_p = 0.5 ns, 128 ns window) with the given diffuse switch and SNR.
ChannelOptions Options(bool diffuse, double snr_at_1m_db) {
  ChannelOptions options;
  options.diffuse.enabled = diffuse;
  options.snr_at_1m_db = snr_at_1m_db;
  return options;
}

SpecularPath Path(double delay_s, Complex amplitude, int va_id = 0) {
  SpecularPath path;
  path.va_id = va_id;
  path.order = va_id == 0 ? 0 : 1;
  path.delay_s = delay_s;
  path.amplitude = amplitude;
  return path;
}

// Projection of the CIR onto the unit-energy pulse at delay tau: sum_n r[n] p(t_n - tau) sqrt(T_s)
// over the samples within +-half_width of tau (all samples for half_width < 0).
Complex Project(const core::Cir& cir, const RaisedCosinePulse& pulse, double tau_s, int half_width = -1) {
  const double ts = cir.sample_period_s;
  const int count = static_cast<int>(cir.samples.size());
  int lo = 0;
  int hi = count - 1;
  if (half_width >= 0) {
    const int center = static_cast<int>(std::lround((tau_s - cir.start_s) / ts));
    lo = std::max(0, center - half_width);
    hi = std::min(count - 1, center + half_width);
  }
  Complex sum(0.0, 0.0);
  for (int n = lo; n <= hi; ++n) {
    sum += cir.samples[static_cast<std::size_t>(n)] * pulse.Value(cir.start_s + n * ts - tau_s);
  }
  return sum * std::sqrt(ts);
}

// S_nu(tau) written out from Lafer 2014 Eq. (2.5) and the header's shape, independently of the
// library: (1/d^2) (1 - chi e^{-t/g_r}) e^{-t/g_1} / A, t = tau - d/c, for the default options.
double HandDiffusePdp(double delay_s, double los_distance_m) {
  const double t = delay_s - los_distance_m / kSpeedOfLight_mps;
  if (t < 0.0) return 0.0;
  const double area = 20e-9 - 0.98 * 20e-9 * 5e-9 / 25e-9;  // 16.08 ns
  return (1.0 - 0.98 * std::exp(-t / 5e-9)) * std::exp(-t / 20e-9) / area / (los_distance_m * los_distance_m);
}

// T_eff of the default pulse in closed form, T (1 - 29 beta/64) / (1 - beta/4)^2 (see
// raised_cosine_pulse_test.cc).
constexpr double kEffectiveDuration_s = 0.5e-9 * (1.0 - 29.0 * 0.5 / 64.0) / (0.875 * 0.875);

TEST(CirSynthesizer, HasTheWindowLengthOverTheSamplePeriodAndTheNoisePsdOfTheSnr) {
  const CirSynthesizer synth(Options(true, 35.0));

  EXPECT_EQ(synth.sample_count(), 1024);                       // 128 ns / 0.125 ns
  EXPECT_NEAR(synth.noise_psd(), 3.16227766e-4, 1e-12);         // 10^(-35/10)
}

TEST(CirSynthesizer, ProjectsOntoThePathAmplitudeAtAnOnGridDelay) {
  // 20 ns = sample 160. Noise at 200 dB SNR is 1e-10 per sample, so the projection must equal
  // alpha to the accuracy of the synthesis.
  const CirSynthesizer synth(Options(false, 200.0));
  const Complex alpha = std::polar(0.3, 0.7);
  const std::vector<SpecularPath> paths{Path(20e-9, alpha)};
  core::Rng diffuse_rng(1), noise_rng(2);

  const auto out = synth.Synthesize(paths, 3.0, diffuse_rng, noise_rng);

  ASSERT_EQ(out.cir.samples.size(), 1024u);
  EXPECT_LT(std::abs(Project(out.cir, synth.pulse(), 20e-9) - alpha) / std::abs(alpha), 1e-3);
  // The sample at the delay is alpha p(0) sqrt(T_s) = alpha sqrt(0.125 / (0.5 * 0.875)) = 0.53452 alpha.
  EXPECT_LT(std::abs(out.cir.samples[160] - 0.534522 * alpha) / std::abs(alpha), 1e-4);
  // And so is the sample one pulse duration (4 samples) later: the sinc zero.
  EXPECT_LT(std::abs(out.cir.samples[164]) / std::abs(alpha), 1e-4);
}

TEST(CirSynthesizer, ProjectsOntoThePathAmplitudeAtAnOffGridDelay) {
  // 20.0437 ns is 0.3496 samples past sample 160.
  const CirSynthesizer synth(Options(false, 200.0));
  const Complex alpha = std::polar(0.05, -2.1);
  const std::vector<SpecularPath> paths{Path(20.0437e-9, alpha)};
  core::Rng diffuse_rng(1), noise_rng(2);

  const auto out = synth.Synthesize(paths, 3.0, diffuse_rng, noise_rng);

  EXPECT_LT(std::abs(Project(out.cir, synth.pulse(), 20.0437e-9) - alpha) / std::abs(alpha), 1e-3);
  // Projecting at the nearest grid delay instead loses energy: R(0.0437 ns) < 1 by ~1 %.
  EXPECT_GT(std::abs(Project(out.cir, synth.pulse(), 20e-9) - alpha) / std::abs(alpha), 3e-3);
}

TEST(CirSynthesizer, SuperposesSeveralPaths) {
  const CirSynthesizer synth(Options(false, 200.0));
  const Complex a1 = std::polar(0.4, 0.3), a2 = std::polar(0.1, 2.0);
  const std::vector<SpecularPath> paths{Path(12.31e-9, a1, 0), Path(47.77e-9, a2, 1)};
  core::Rng diffuse_rng(1), noise_rng(2);

  const auto out = synth.Synthesize(paths, 3.0, diffuse_rng, noise_rng);

  // 35 ns apart, the cross-term a1 R(35 ns) is far below 1e-3 |a2|.
  EXPECT_LT(std::abs(Project(out.cir, synth.pulse(), 12.31e-9) - a1) / std::abs(a1), 1e-3);
  EXPECT_LT(std::abs(Project(out.cir, synth.pulse(), 47.77e-9) - a2) / std::abs(a2), 1e-3);
}

TEST(CirSynthesizer, AddsWhiteNoiseOfVarianceN0PerSample) {
  // N0 = 10^(-3.5) = 3.162e-4. |r|^2 of CN(0, N0) is exponential with mean and std N0, so the
  // mean over 20 x 1024 = 20480 samples has a relative std of 1/sqrt(20480) = 0.7 %: 3 % is 4.3
  // sigma. Each quadrature has variance N0/2, estimated with relative std sqrt(2/20480) = 1 %.
  const CirSynthesizer synth(Options(false, 35.0));
  const double n0 = std::pow(10.0, -3.5);
  core::Rng noise_rng(7);
  double sum2 = 0.0, sum_re2 = 0.0, sum_im2 = 0.0;
  Complex sum(0.0, 0.0);
  int count = 0;

  for (int run = 0; run < 20; ++run) {
    core::Rng diffuse_rng(run);
    const auto out = synth.Synthesize({}, 3.0, diffuse_rng, noise_rng);
    for (const auto& r : out.cir.samples) {
      sum += r;
      sum2 += std::norm(r);
      sum_re2 += r.real() * r.real();
      sum_im2 += r.imag() * r.imag();
      ++count;
    }
  }

  EXPECT_NEAR(sum2 / count, n0, 0.03 * n0);
  EXPECT_NEAR(sum_re2 / count, n0 / 2.0, 0.04 * n0 / 2.0);
  EXPECT_NEAR(sum_im2 / count, n0 / 2.0, 0.04 * n0 / 2.0);
  // Mean: std sqrt(N0/20480) = 1.2e-4 sqrt(N0) per quadrature.
  EXPECT_LT(std::abs(sum / static_cast<double>(count)), 5.0 * std::sqrt(n0 / count));
}

TEST(CirSynthesizer, MatchedFilterVarianceUnderDiffuseMultipathIsTeffTimesThePdpPlusN0) {
  // No specular paths, DM on (0 dB at the 3 m LOS), SNR 35 dB. The projection y(tau) =
  // sum_j nu_j R(t_j - tau) has variance sum_j S_nu(t_j) T_s R^2 ~= S_nu(tau) int R^2 = T_eff
  // S_nu(tau), plus N0. Expected (hand): 15 ns 2.054e-3, 30 ns 1.578e-3, 45 ns 9.22e-4,
  // 60 ns 6.03e-4 (DM 5.5, 4.0, 1.9 and 0.9 times N0). |y|^2 is exponential, so the mean of 1500
  // realisations has a relative std of 2.6 %; 10 % is 3.9 sigma.
  const CirSynthesizer synth(Options(true, 35.0));
  const double n0 = std::pow(10.0, -3.5);
  const std::vector<double> delays{15e-9, 30e-9, 45e-9, 60e-9};
  std::vector<double> sum(delays.size(), 0.0);
  constexpr int kRuns = 1500;
  core::Rng diffuse_rng(11), noise_rng(12);

  for (int run = 0; run < kRuns; ++run) {
    const auto out = synth.Synthesize({}, 3.0, diffuse_rng, noise_rng);
    for (std::size_t i = 0; i < delays.size(); ++i) {
      sum[i] += std::norm(Project(out.cir, synth.pulse(), delays[i], 64));
    }
  }

  for (std::size_t i = 0; i < delays.size(); ++i) {
    const double expected = kEffectiveDuration_s * HandDiffusePdp(delays[i], 3.0) + n0;
    EXPECT_NEAR(sum[i] / kRuns, expected, 0.1 * expected) << "tau " << delays[i];
  }
}

TEST(CirSynthesizer, DiffusePdpScalesTheShapeByTheInverseSquareLosDistance) {
  // Omega = 10^(0/10) / d^2. At 30 ns and d = 3 m: excess 19.993 ns, shape 2.2475e7 /s,
  // S_nu = 2.4972e6 /s. Halving d quadruples Omega (and moves the LOS).
  const CirSynthesizer synth(Options(true, 35.0));

  EXPECT_NEAR(synth.DiffusePdp(30e-9, 3.0), HandDiffusePdp(30e-9, 3.0), 1e-9 * HandDiffusePdp(30e-9, 3.0));
  EXPECT_NEAR(synth.DiffusePdp(30e-9, 3.0), 2.4972e6, 0.0001e6);
  EXPECT_NEAR(synth.DiffusePdp(30e-9, 1.5), HandDiffusePdp(30e-9, 1.5), 1e-9 * HandDiffusePdp(30e-9, 1.5));
  EXPECT_EQ(synth.DiffusePdp(9e-9, 3.0), 0.0);  // before the 10.007 ns LOS delay
  EXPECT_EQ(CirSynthesizer(Options(false, 35.0)).DiffusePdp(30e-9, 3.0), 0.0);

  ChannelOptions stronger = Options(true, 35.0);
  stronger.diffuse.power_ratio_db = 10.0;
  EXPECT_NEAR(CirSynthesizer(stronger).DiffusePdp(30e-9, 3.0), 10.0 * HandDiffusePdp(30e-9, 3.0),
              1e-8 * HandDiffusePdp(30e-9, 3.0));
}

TEST(CirSynthesizer, DiffuseMultipathStartsAtTheLosDelayOfTheMedium) {
  // In air (343 m/s) a 3.43 m LOS arrives after 10 ms: no DM 1 ns before, DM 1 ns after.
  ChannelOptions options;
  options.medium = core::Medium{core::MediumKind::kSound, 343.0};
  const CirSynthesizer synth(options);

  EXPECT_EQ(synth.DiffusePdp(3.43 / 343.0 - 1e-9, 3.43), 0.0);
  EXPECT_GT(synth.DiffusePdp(3.43 / 343.0 + 1e-9, 3.43), 0.0);
}

TEST(CirSynthesizer, TrueSinrIsAmplitudeSquaredOverNoisePlusTeffTimesThePdp) {
  // |a|^2 = 0.04; N0 = 3.1623e-4; T_eff S_nu(30 ns) = 0.50510 ns * 2.4972e6 /s = 1.2613e-3:
  // SINR = 0.04 / 1.5776e-3 = 25.356.
  const CirSynthesizer synth(Options(true, 35.0));
  const Complex a = std::polar(0.2, 1.0);

  EXPECT_NEAR(synth.TrueSinr(a, 30e-9, 3.0), 25.356, 0.001);
  // Without DM, and before the LOS delay, only the noise remains: 0.04 / 3.1623e-4 = 126.49.
  EXPECT_NEAR(CirSynthesizer(Options(false, 35.0)).TrueSinr(a, 30e-9, 3.0), 126.49, 0.01);
  EXPECT_NEAR(synth.TrueSinr(a, 5e-9, 3.0), 126.49, 0.01);
}

TEST(CirSynthesizer, ReportsTheTruthOfThePathsInsideTheWindowOnly) {
  // Window [0, 128 ns). -1 ns and 130 ns are synthesised (inside the guard band) but outside the
  // window; 200 ns is beyond the FFT grid and dropped.
  const CirSynthesizer synth(Options(true, 35.0));
  const std::vector<SpecularPath> paths{Path(-1e-9, 0.5, 0), Path(10.0069e-9, 0.33, 1), Path(64.3e-9, 0.1, 2),
                                        Path(127.9e-9, 0.05, 3), Path(130e-9, 0.05, 4), Path(200e-9, 0.05, 5)};
  core::Rng diffuse_rng(3), noise_rng(4);

  const auto out = synth.Synthesize(paths, 3.0, diffuse_rng, noise_rng);

  ASSERT_EQ(out.paths.size(), 3u);
  EXPECT_EQ(out.paths[0].va_id, 1);
  EXPECT_EQ(out.paths[1].va_id, 2);
  EXPECT_EQ(out.paths[2].va_id, 3);
  EXPECT_EQ(out.paths[1].delay_s, 64.3e-9);
  EXPECT_EQ(out.paths[1].amplitude, Complex(0.1, 0.0));
  EXPECT_EQ(out.paths[1].order, 1);
  EXPECT_DOUBLE_EQ(out.paths[1].sinr, synth.TrueSinr(0.1, 64.3e-9, 3.0));
  EXPECT_EQ(out.cir.start_s, 0.0);
  EXPECT_EQ(out.cir.sample_period_s, 0.125e-9);
}

TEST(CirSynthesizer, DropsAPathBeyondTheFftGridWithoutAWrapAroundTrace) {
  // A 200 ns path at 200 dB SNR: if it wrapped around the circular grid it would show up in the
  // window at about 200 - 160 = 40 ns; the CIR must hold only the 1e-10 noise.
  const CirSynthesizer synth(Options(false, 200.0));
  const std::vector<SpecularPath> paths{Path(200e-9, 1.0)};
  core::Rng diffuse_rng(1), noise_rng(2);

  const auto out = synth.Synthesize(paths, 3.0, diffuse_rng, noise_rng);

  double peak = 0.0;
  for (const auto& r : out.cir.samples) peak = std::max(peak, std::abs(r));
  EXPECT_LT(peak, 1e-8);
  EXPECT_TRUE(out.paths.empty());
}

TEST(CirSynthesizer, GivesIdenticalSamplesForTheSameSeeds) {
  const CirSynthesizer synth(Options(true, 35.0));
  const std::vector<SpecularPath> paths{Path(15.5e-9, std::polar(0.3, 0.2))};
  core::Rng d1(5), n1(6), d2(5), n2(6), d3(5), n3(7);

  const auto a = synth.Synthesize(paths, 3.0, d1, n1);
  const auto b = synth.Synthesize(paths, 3.0, d2, n2);
  const auto c = synth.Synthesize(paths, 3.0, d3, n3);

  ASSERT_EQ(a.cir.samples.size(), b.cir.samples.size());
  for (std::size_t n = 0; n < a.cir.samples.size(); ++n) EXPECT_EQ(a.cir.samples[n], b.cir.samples[n]) << n;
  int differing = 0;
  for (std::size_t n = 0; n < a.cir.samples.size(); ++n) differing += a.cir.samples[n] != c.cir.samples[n] ? 1 : 0;
  EXPECT_EQ(differing, 1024);
}

TEST(CirSynthesizer, LeavesTheNoiseUnchangedWhenDiffuseMultipathIsSwitchedOff) {
  // r_on - r_off is the DM part alone; it must not depend on the noise seed.
  const CirSynthesizer on(Options(true, 35.0));
  const CirSynthesizer off(Options(false, 35.0));
  const std::vector<SpecularPath> paths{Path(15.5e-9, std::polar(0.3, 0.2))};
  std::vector<std::vector<Complex>> dm;

  for (const std::uint64_t noise_seed : {21u, 22u}) {
    core::Rng d_on(9), n_on(noise_seed), d_off(9), n_off(noise_seed);
    const auto with = on.Synthesize(paths, 3.0, d_on, n_on);
    const auto without = off.Synthesize(paths, 3.0, d_off, n_off);
    std::vector<Complex> diff(with.cir.samples.size());
    for (std::size_t n = 0; n < diff.size(); ++n) diff[n] = with.cir.samples[n] - without.cir.samples[n];
    dm.push_back(diff);
  }

  double dm_energy = 0.0;
  for (std::size_t n = 0; n < dm[0].size(); ++n) {
    EXPECT_NEAR(std::abs(dm[0][n] - dm[1][n]), 0.0, 1e-15) << n;
    dm_energy += std::norm(dm[0][n]);
  }
  EXPECT_GT(dm_energy, 0.0);
}

TEST(CirSynthesizer, ValidateRejectsASamplePeriodAboveNyquist) {
  // Band edge 1.5 GHz -> Nyquist T_s = 1 / 3 GHz = 0.3333 ns.
  ChannelOptions options;
  EXPECT_TRUE(Validate(options).empty());
  options.sample_period_s = 0.33e-9;
  EXPECT_TRUE(Validate(options).empty());
  options.sample_period_s = 0.34e-9;
  ASSERT_EQ(Validate(options).size(), 1u);
  EXPECT_NE(Validate(options)[0].find("Nyquist"), std::string::npos);
  // A 1 ns pulse (band edge 0.75 GHz) allows T_s up to 0.667 ns.
  options.pulse.duration_s = 1e-9;
  options.sample_period_s = 0.6e-9;
  EXPECT_TRUE(Validate(options).empty());
}

TEST(CirSynthesizer, ValidateRejectsBadWindowSnrAndSubOptions) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ChannelOptions options;
  options.sample_period_s = 0.0;
  EXPECT_EQ(Validate(options).size(), 1u);
  options = ChannelOptions{};
  options.window_start_s = -1e-9;
  EXPECT_EQ(Validate(options).size(), 1u);
  options = ChannelOptions{};
  options.window_length_s = 0.0;
  EXPECT_EQ(Validate(options).size(), 1u);
  options = ChannelOptions{};
  options.window_length_s = 1e-3;  // 8e6 samples
  EXPECT_EQ(Validate(options).size(), 1u);
  options = ChannelOptions{};
  options.snr_at_1m_db = nan;
  EXPECT_EQ(Validate(options).size(), 1u);
  options = ChannelOptions{};
  options.medium.speed_mps = 0.0;
  EXPECT_EQ(Validate(options).size(), 1u);
  options.medium.speed_mps = nan;
  EXPECT_EQ(Validate(options).size(), 1u);
  options = ChannelOptions{};
  options.pulse.rolloff = 2.0;
  options.diffuse.decay_s = 0.0;
  const auto problems = Validate(options);
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_EQ(problems[0].rfind("pulse.", 0), 0u);
  EXPECT_EQ(problems[1].rfind("diffuse.", 0), 0u);
}

TEST(ChannelOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMemberButTheMedium) {
  test::ExpectDescribesEveryMember(ChannelOptionsDescriptor(), {"pulse", "diffuse", "sample_period_s", "window_start_s",
                                                                "window_length_s", "snr_at_1m_db"});
  EXPECT_EQ(ChannelOptionsDescriptor().Find("medium"), nullptr);
}

TEST(ChannelOptionsDescriptor, LeavesTheChecksAgainstThePulseToValidate) {
  // A cooperative scenario sets the pulse duration per variant after reading the section.
  ChannelOptions options;
  options.sample_period_s = 0.34e-9;  // above the 0.333 ns Nyquist limit of the 0.5 ns pulse
  EXPECT_TRUE(ChannelOptionsDescriptor().Validate(options).empty());
  ASSERT_EQ(Validate(options).size(), 1u);
  EXPECT_EQ(Validate(options)[0].rfind("sample_period_s must be at most", 0), 0u);
  options = ChannelOptions{};
  options.window_length_s = 2e-9;  // 4 pulse durations
  EXPECT_TRUE(ChannelOptionsDescriptor().Validate(options).empty());
  EXPECT_EQ(Validate(options).size(), 1u);
}

TEST(ChannelOptionsDescriptor, BlamesTheSamplePeriodForTooManySamplesPerCir) {
  ChannelOptions options;
  options.sample_period_s = 1e-15;

  const auto problems = ChannelOptionsDescriptor().Validate(options);

  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].rfind("sample_period_s: 1e-15 s must be at least window_length_s / 1e+06", 0), 0u)
      << problems[0];
}

}  // namespace
}  // namespace mirage::channel
