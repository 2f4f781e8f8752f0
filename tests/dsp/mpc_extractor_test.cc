// SPDX-License-Identifier: MIT
#include "mirage/dsp/mpc_extractor.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "core/options_descriptor_expectations.h"
#include "mirage/channel/cir_synthesizer.h"
#include "mirage/core/constants.h"
#include "mirage/core/rng.h"
#include "rng_vectors.h"

namespace mirage::dsp {
namespace {

using core::kSpeedOfLight_mps;

// Defaults (T_s = 0.125 ns, T_p = 0.5 ns, 128 ns window), no diffuse multipath.
channel::ChannelOptions Options(double snr_at_1m_db, double window_start_s = 0.0) {
  channel::ChannelOptions options;
  options.diffuse.enabled = false;
  options.snr_at_1m_db = snr_at_1m_db;
  options.window_start_s = window_start_s;
  return options;
}

channel::SpecularPath Path(double delay_s, Complex amplitude, int va_id = 0) {
  channel::SpecularPath path;
  path.va_id = va_id;
  path.delay_s = delay_s;
  path.amplitude = amplitude;
  return path;
}

MpcExtractorOptions Extraction(bool readjust = true, int max_components = 20, double threshold_db = -30.0) {
  MpcExtractorOptions options;
  options.readjust = readjust;
  options.max_components = max_components;
  options.relative_threshold_db = threshold_db;
  return options;
}

// A CIR at 200 dB SNR (noise 1e-10 per sample): noiseless for every assertion here.
core::Cir Noiseless(const channel::CirSynthesizer& synth, const std::vector<channel::SpecularPath>& paths) {
  core::Rng diffuse_rng(1), noise_rng(2);
  return synth.Synthesize(paths, 3.0, diffuse_rng, noise_rng).cir;
}

MpcExtractor ExtractorFor(const channel::CirSynthesizer& synth, const MpcExtractorOptions& options) {
  return MpcExtractor(options, synth.pulse(), synth.sample_count(), synth.options().sample_period_s,
                      synth.options().medium);
}

// The component nearest in delay to delay_s.
const Mpc& Nearest(const std::vector<Mpc>& mpcs, double delay_s) {
  return *std::min_element(mpcs.begin(), mpcs.end(), [&](const Mpc& a, const Mpc& b) {
    return std::abs(a.delay_s - delay_s) < std::abs(b.delay_s - delay_s);
  });
}

TEST(MpcExtractor, MatchedFilterOutputEqualsThePathAmplitudeAtItsOnGridDelay) {
  // y[n] = <r, s(. - n T_s)>: at the path's sample (20 ns = sample 160) the projection is alpha;
  // one pulse duration (4 samples) away it is alpha R(T_p), and R(T_p) is small for an RC pulse.
  const channel::CirSynthesizer synth(Options(200.0));
  const Complex alpha = std::polar(0.3, 0.7);
  const auto cir = Noiseless(synth, {Path(20e-9, alpha)});
  const MpcExtractor extractor = ExtractorFor(synth, Extraction());

  const auto y = extractor.MatchedFilter(cir);

  ASSERT_EQ(y.size(), 1024u);
  EXPECT_LT(std::abs(y[160] - alpha) / std::abs(alpha), 1e-3);
  EXPECT_LT(std::abs(y[164] - alpha * synth.pulse().Autocorrelation(0.5e-9)), 1e-3 * std::abs(alpha));
  const auto peak = std::max_element(y.begin(), y.end(), [](Complex a, Complex b) { return std::abs(a) < std::abs(b); });
  EXPECT_EQ(peak - y.begin(), 160);
}

TEST(MpcExtractor, PerCallCountAndProjectionAtAnArbitraryDelay) {
  // Three paths: asking for 2 components returns the 2 strongest; the projection at a path's
  // exact (fractional) delay is its amplitude (Kulmer Eq. 6), and 0 outside the window.
  const channel::CirSynthesizer synth(Options(200.0));
  const MpcExtractor extractor = ExtractorFor(synth, Extraction(true, 20, -60.0));
  const std::vector<channel::SpecularPath> paths{Path(10.03e-9, Complex(0.5, 0.2)), Path(30.41e-9, Complex(-0.3, 0.1)),
                                                 Path(50.77e-9, Complex(0.05, 0.0))};
  const core::Cir cir = Noiseless(synth, paths);
  const auto two = extractor.Extract(cir, 2);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_NEAR(two[0].delay_s, 10.03e-9, 2e-12);
  EXPECT_NEAR(two[1].delay_s, 30.41e-9, 2e-12);
  const auto matched = extractor.MatchedFilter(cir);
  for (const auto& p : paths) {
    const Complex a = extractor.ProjectAt(matched, cir.start_s, p.delay_s);
    EXPECT_NEAR(std::abs(a - p.amplitude), 0.0, 2e-3 * std::abs(p.amplitude) + 1e-4);
  }
  EXPECT_EQ(extractor.ProjectAt(matched, cir.start_s, -1e-9), Complex(0.0, 0.0));
  EXPECT_EQ(extractor.ProjectAt(matched, cir.start_s, 1e-6), Complex(0.0, 0.0));
}

TEST(MpcExtractor, RecoversASingleNoiselessPathAtRandomFractionalDelays) {
  // 30 seeded delays in [10, 100] ns with random amplitudes and phases. Parabolic refinement on a
  // 0.125 ns (3.7 cm) grid: |range error| < 2 mm and |amplitude error| < 2 %.
  const channel::CirSynthesizer synth(Options(200.0));
  const MpcExtractor extractor = ExtractorFor(synth, Extraction());
  core::Rng rng(2024);

  for (int trial = 0; trial < 30; ++trial) {
    const double delay_s = rng.Uniform(10e-9, 100e-9);
    const Vec2 magnitude_phase = testing::UniformVec2(rng, Vec2(0.05, -core::kPi), Vec2(1.0, core::kPi));
    const Complex alpha = std::polar(magnitude_phase.x(), magnitude_phase.y());

    const auto mpcs = extractor.Extract(Noiseless(synth, {Path(delay_s, alpha)}));

    ASSERT_EQ(mpcs.size(), 1u) << "delay " << delay_s;
    EXPECT_LT(std::abs(mpcs[0].range_m - delay_s * kSpeedOfLight_mps), 2e-3) << "delay " << delay_s;
    EXPECT_LT(std::abs(mpcs[0].amplitude - alpha) / std::abs(alpha), 0.02) << "delay " << delay_s;
    EXPECT_DOUBLE_EQ(mpcs[0].range_m, mpcs[0].delay_s * kSpeedOfLight_mps);
  }
}

TEST(MpcExtractor, TurnsDelaysIntoRangesWithTheSpeedOfItsMedium) {
  // The same CIR read as sound at 343 m/s: same delays, ranges delay * 343 m/s.
  const channel::CirSynthesizer synth(Options(200.0));
  const core::Medium air{core::MediumKind::kSound, 343.0};
  const MpcExtractor extractor(Extraction(), synth.pulse(), synth.sample_count(), synth.options().sample_period_s, air);

  const auto mpcs = extractor.Extract(Noiseless(synth, {Path(20.3e-9, Complex(0.4, 0.1))}));

  ASSERT_EQ(mpcs.size(), 1u);
  EXPECT_NEAR(mpcs[0].delay_s, 20.3e-9, 2e-12);
  EXPECT_DOUBLE_EQ(mpcs[0].range_m, mpcs[0].delay_s * 343.0);
  EXPECT_EQ(extractor.medium().speed_mps, 343.0);
}

TEST(MpcExtractor, RecoversTwoPathsThreeNanosecondsApart) {
  // 3 ns = 6 pulse durations: the paths barely interact.
  const channel::CirSynthesizer synth(Options(200.0));
  const MpcExtractor extractor = ExtractorFor(synth, Extraction());
  const Complex a1 = std::polar(0.3, 0.4), a2 = std::polar(0.2, -1.9);
  const double d1 = 30.0123e-9, d2 = 33.0123e-9;

  const auto mpcs = extractor.Extract(Noiseless(synth, {Path(d1, a1), Path(d2, a2, 1)}));

  ASSERT_EQ(mpcs.size(), 2u);
  EXPECT_LT(std::abs(mpcs[0].delay_s - d1) * kSpeedOfLight_mps, 2e-3);
  EXPECT_LT(std::abs(mpcs[1].delay_s - d2) * kSpeedOfLight_mps, 2e-3);
  EXPECT_LT(std::abs(mpcs[0].amplitude - a1) / std::abs(a1), 0.02);
  EXPECT_LT(std::abs(mpcs[1].amplitude - a2) / std::abs(a2), 0.02);
}

TEST(MpcExtractor, ReadjustImprovesTwoOverlappingPathsOfUnequalAmplitude) {
  // Two paths 0.6 ns apart (1.2 T_p, inside each other's main lobe), amplitudes 1 and 0.5 with
  // seeded random phases, 20 trials. Without readjust the strong path keeps the bias the weak one
  // left on it (about 13 mm RMS); re-estimating it after the weak one is subtracted removes most
  // of that (about 3 mm). Matching: the two strongest components, in delay order.
  const channel::CirSynthesizer synth(Options(200.0));
  const MpcExtractor with = ExtractorFor(synth, Extraction(true));
  const MpcExtractor without = ExtractorFor(synth, Extraction(false));
  double strong_sq[2] = {0.0, 0.0};
  double total_sq[2] = {0.0, 0.0};
  core::Rng rng(5);

  for (int trial = 0; trial < 20; ++trial) {
    const double d1 = rng.Uniform(20e-9, 21e-9);
    const double d2 = d1 + 0.6e-9;
    const Complex a1 = std::polar(1.0, rng.Uniform(-core::kPi, core::kPi));
    const Complex a2 = std::polar(0.5, rng.Uniform(-core::kPi, core::kPi));
    const auto cir = Noiseless(synth, {Path(d1, a1), Path(d2, a2, 1)});
    for (int mode = 0; mode < 2; ++mode) {
      auto mpcs = (mode == 0 ? with : without).Extract(cir);
      ASSERT_GE(mpcs.size(), 2u);
      std::sort(mpcs.begin(), mpcs.end(), [](const Mpc& a, const Mpc& b) { return std::abs(a.amplitude) > std::abs(b.amplitude); });
      mpcs.resize(2);
      std::sort(mpcs.begin(), mpcs.end(), [](const Mpc& a, const Mpc& b) { return a.delay_s < b.delay_s; });
      const double e1 = (mpcs[0].delay_s - d1) * kSpeedOfLight_mps;
      const double e2 = (mpcs[1].delay_s - d2) * kSpeedOfLight_mps;
      strong_sq[mode] += e1 * e1;
      total_sq[mode] += e1 * e1 + e2 * e2;
    }
  }

  const double strong_rms_with = std::sqrt(strong_sq[0] / 20), strong_rms_without = std::sqrt(strong_sq[1] / 20);
  const double total_rms_with = std::sqrt(total_sq[0] / 40), total_rms_without = std::sqrt(total_sq[1] / 40);
  EXPECT_LT(strong_rms_with, 0.5 * strong_rms_without) << strong_rms_with << " vs " << strong_rms_without;
  EXPECT_LT(total_rms_with, 0.7 * total_rms_without) << total_rms_with << " vs " << total_rms_without;
  // Both are still centimetre-accurate for paths 18 cm apart.
  EXPECT_LT(strong_rms_with, 0.01);
}

TEST(MpcExtractor, StopsAtTheRelativeThresholdWhenOnlyNoiseRemains) {
  // One path of amplitude 1 at 35 dB SNR (N0 = 3.2e-4). The largest noise peak of the matched
  // filter output is about ln(1024/4) N0 ~ 5.5 N0, i.e. -27.6 dB: a -10 dB threshold stops after
  // the path, a -40 dB threshold lets the noise run up to max_components.
  const channel::CirSynthesizer synth(Options(35.0));
  const MpcExtractor strict = ExtractorFor(synth, Extraction(true, 20, -10.0));
  const MpcExtractor lax = ExtractorFor(synth, Extraction(true, 20, -40.0));
  const std::vector<channel::SpecularPath> paths{Path(25.3e-9, std::polar(1.0, 0.4))};

  for (std::uint64_t seed = 0; seed < 5; ++seed) {
    core::Rng diffuse_rng(1), noise_rng(seed);
    const auto cir = synth.Synthesize(paths, 3.0, diffuse_rng, noise_rng).cir;

    const auto strict_mpcs = strict.Extract(cir);
    const auto lax_mpcs = lax.Extract(cir);

    ASSERT_EQ(strict_mpcs.size(), 1u) << "seed " << seed;
    EXPECT_LT(std::abs(strict_mpcs[0].delay_s - 25.3e-9) * kSpeedOfLight_mps, 0.01);
    EXPECT_EQ(lax_mpcs.size(), 20u) << "seed " << seed;
  }
}

TEST(MpcExtractor, SortsTheComponentsByDelay) {
  // Five paths whose amplitudes are not in delay order; all found, in increasing delay.
  const channel::CirSynthesizer synth(Options(200.0));
  const MpcExtractor extractor = ExtractorFor(synth, Extraction());
  const std::vector<double> delays{15.1e-9, 31.7e-9, 48.2e-9, 70.9e-9, 99.4e-9};
  const std::vector<double> magnitudes{0.1, 0.5, 0.2, 0.8, 0.3};
  std::vector<channel::SpecularPath> paths;
  for (std::size_t i = 0; i < delays.size(); ++i) {
    paths.push_back(Path(delays[i], std::polar(magnitudes[i], 0.7 * static_cast<double>(i)), static_cast<int>(i)));
  }

  const auto mpcs = extractor.Extract(Noiseless(synth, paths));

  ASSERT_EQ(mpcs.size(), 5u);
  for (std::size_t i = 0; i < delays.size(); ++i) {
    EXPECT_LT(std::abs(mpcs[i].delay_s - delays[i]) * kSpeedOfLight_mps, 2e-3) << i;
    EXPECT_NEAR(std::abs(mpcs[i].amplitude), magnitudes[i], 0.02 * magnitudes[i]) << i;
  }
}

TEST(MpcExtractor, KeepsOnlyTheStrongestMaxComponents) {
  // max_components 3 of the five paths above: the strongest are 0.8 at 70.9 ns, 0.5 at 31.7 ns
  // and 0.3 at 99.4 ns, returned in delay order.
  const channel::CirSynthesizer synth(Options(200.0));
  const MpcExtractor extractor = ExtractorFor(synth, Extraction(true, 3));
  const std::vector<channel::SpecularPath> paths{Path(15.1e-9, 0.1), Path(31.7e-9, 0.5), Path(48.2e-9, 0.2),
                                                 Path(70.9e-9, 0.8), Path(99.4e-9, 0.3)};

  const auto mpcs = extractor.Extract(Noiseless(synth, paths));

  ASSERT_EQ(mpcs.size(), 3u);
  EXPECT_LT(std::abs(mpcs[0].delay_s - 31.7e-9) * kSpeedOfLight_mps, 2e-3);
  EXPECT_LT(std::abs(mpcs[1].delay_s - 70.9e-9) * kSpeedOfLight_mps, 2e-3);
  EXPECT_LT(std::abs(mpcs[2].delay_s - 99.4e-9) * kSpeedOfLight_mps, 2e-3);
  EXPECT_EQ(ExtractorFor(synth, Extraction(true, 1)).Extract(Noiseless(synth, paths)).size(), 1u);
}

TEST(MpcExtractor, ReportsDelaysRelativeToTheTransmitTimeForAShiftedWindow) {
  // Window starting at 5 ns: a path at 20.3 ns sits 15.3 ns into the window; the reported delay
  // and range include the 5 ns start.
  const channel::CirSynthesizer synth(Options(200.0, 5e-9));
  const MpcExtractor extractor = ExtractorFor(synth, Extraction());

  const auto mpcs = extractor.Extract(Noiseless(synth, {Path(20.3e-9, 0.4)}));

  ASSERT_EQ(mpcs.size(), 1u);
  EXPECT_LT(std::abs(mpcs[0].range_m - 20.3e-9 * kSpeedOfLight_mps), 2e-3);
  EXPECT_LT(std::abs(Nearest(mpcs, 20.3e-9).amplitude - 0.4), 0.008);
}

TEST(MpcExtractor, ValidateAcceptsTheDefaultsAndRejectsBadOptions) {
  EXPECT_TRUE(Validate(MpcExtractorOptions{}).empty());
  EXPECT_TRUE(Validate(Extraction(true, 1, -0.1)).empty());
  EXPECT_TRUE(Validate(Extraction(true, 1000, -30.0)).empty());

  EXPECT_EQ(Validate(Extraction(true, 0)).size(), 1u);
  EXPECT_EQ(Validate(Extraction(true, 1001)).size(), 1u);
  EXPECT_EQ(Validate(Extraction(true, 20, 0.0)).size(), 1u);
  EXPECT_EQ(Validate(Extraction(true, 20, 3.0)).size(), 1u);
  EXPECT_EQ(Validate(Extraction(true, 20, std::numeric_limits<double>::quiet_NaN())).size(), 1u);
  EXPECT_EQ(Validate(Extraction(true, 20, -std::numeric_limits<double>::infinity())).size(), 1u);
  EXPECT_EQ(Validate(Extraction(true, -5, 1.0)).size(), 2u);
}

TEST(MpcExtractorOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMember) {
  test::ExpectDescribesEveryMember(MpcExtractorOptionsDescriptor(),
                                   {"max_components", "relative_threshold_db", "readjust"});
}

}  // namespace
}  // namespace mirage::dsp
