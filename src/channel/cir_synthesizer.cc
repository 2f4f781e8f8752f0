// SPDX-License-Identifier: MIT
#include "mirage/channel/cir_synthesizer.h"

#include <cmath>

#include <fmt/format.h>

#include "mirage/core/constants.h"
#include "mirage/core/units.h"

namespace mirage::channel {
namespace {

int SampleCount(const ChannelOptions& options) {
  return static_cast<int>(std::lround(options.window_length_s / options.sample_period_s));
}

// Guard band beyond the window (samples): tails that wrap around the circular FFT grid are
// negligible after kPulseTailDurations.
int GuardSamples(const ChannelOptions& options) { return PulseTailSamples(options.pulse, options.sample_period_s); }

std::size_t FftSize(const ChannelOptions& options) {
  return core::NextFastFftSize(static_cast<std::size_t>(SampleCount(options) + 2 * GuardSamples(options)));
}

// Bounds that keep the sampled quantities (window, guard, FFT, tables) of a sane size.
constexpr double kMaxWindowSamples = 1e6;
constexpr double kMaxPulseSamples = 1000.0;  // T_p / T_s
constexpr double kMinWindowPulses = 8.0;     // window_length_s / T_p

}  // namespace

const core::OptionsDescriptor<ChannelOptions>& ChannelOptionsDescriptor() {
  using core::ValueRange;
  using O = ChannelOptions;
  static const auto descriptor = [] {
    const ValueRange sample_period_range = ValueRange::Closed(1e-15, 1e-3);
    const ValueRange window_length_range = ValueRange::Closed(1e-12, 1.0);
    core::OptionsDescriptor<O> d("channel::ChannelOptions");
    d.Section(&O::pulse, {.key = "pulse", .doc = "The raised-cosine transmit pulse (Lafer App. A.5)."},
              PulseOptionsDescriptor());
    d.Section(&O::diffuse, {.key = "diffuse", .doc = "Diffuse multipath (Lafer Eq. 2.5)."}, DiffuseOptionsDescriptor());
    d.Number(&O::sample_period_s,
             {.key = "sample_period_s",
              .unit = "s",
              .range = sample_period_range,
              .doc = "Sample period T_s; it must also lie below the pulse's Nyquist limit 1 / (2 band edge). 0.125 ns, "
                     "close to the thesis's 0.133 ns synthetic grid."});
    d.Number(&O::window_start_s, {.key = "window_start_s",
                                  .unit = "s",
                                  .range = ValueRange::Closed(0.0, 1.0),
                                  .doc = "Delay of the first sample. 0: anchors and agent are synchronised (ToA)."});
    d.Number(&O::window_length_s,
             {.key = "window_length_s",
              .unit = "s",
              .range = window_length_range,
              .doc = "Length of the CIR window, at least 8 pulse durations. 128 ns covers second-order paths in a "
                     "9 m room."});
    d.Number(&O::snr_at_1m_db,
             {.key = "snr_at_1m_db",
              .unit = "dB",
              .range = ValueRange::Closed(-100.0, 200.0),
              .doc = "SNR of an unobstructed LOS at 1 m: LOS energy over N0. 35 dB gives a LOS SNR of about 25 dB at "
                     "3 m, typical of the thesis's measured seminar-room channels."});
    d.Check("sample_period_s >= window_length_s / 1e6 (at most 1e6 samples per CIR)",
            [=](const O& o) -> std::vector<std::string> {
              if (!sample_period_range.Contains(o.sample_period_s) ||
                  !window_length_range.Contains(o.window_length_s) ||
                  o.window_length_s / o.sample_period_s <= kMaxWindowSamples) {
                return {};
              }
              return {
                  fmt::format("sample_period_s: {} s must be at least window_length_s / {:g} ({:.6g} s): the CIR "
                              "window would span {:.6g} samples",
                              core::FormatNumber(o.sample_period_s), kMaxWindowSamples,
                              o.window_length_s / kMaxWindowSamples, o.window_length_s / o.sample_period_s)};
            });
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const ChannelOptions& options) {
  std::vector<std::string> problems = ChannelOptionsDescriptor().Validate(options);
  if (!(options.medium.speed_mps > 0.0) || !std::isfinite(options.medium.speed_mps)) {
    problems.push_back("medium.speed_mps must be > 0 m/s");
  }
  // The checks against the pulse need every value in range (finite, positive).
  if (!problems.empty()) return problems;
  const double nyquist_s = 1.0 / (2.0 * RaisedCosinePulse(options.pulse).band_edge_hz());
  if (options.sample_period_s > nyquist_s) {
    problems.push_back(
        fmt::format("sample_period_s must be at most {:.6g} s (Nyquist for the pulse bandwidth)", nyquist_s));
  }
  if (options.pulse.duration_s / options.sample_period_s > kMaxPulseSamples) {
    problems.push_back(fmt::format("sample_period_s must be at least pulse.duration_s / {:g} = {:.6g} s",
                                   kMaxPulseSamples, options.pulse.duration_s / kMaxPulseSamples));
  }
  if (options.window_length_s < kMinWindowPulses * options.pulse.duration_s) {
    problems.push_back(fmt::format("window_length_s must be at least {:g} pulse durations ({:.6g} s)", kMinWindowPulses,
                                   kMinWindowPulses * options.pulse.duration_s));
  }
  return problems;
}

CirSynthesizer::CirSynthesizer(const ChannelOptions& options)
    : options_(options),
      pulse_(options.pulse),
      sample_count_(SampleCount(options)),
      guard_samples_(GuardSamples(options)),
      noise_psd_(core::DbToPowerRatio(-options.snr_at_1m_db)),
      fft_(FftSize(options)) {
  bin_spectrum_ = pulse_.SampledSpectrum(fft_.size(), options_.sample_period_s);
}

double CirSynthesizer::DiffusePdp(double delay_s, double los_distance_m) const {
  if (!options_.diffuse.enabled) return 0.0;
  const double los_delay_s = los_distance_m / options_.medium.speed_mps;
  // Total DM energy Omega_1 scales with the free-space LOS energy (1 m / d_LOS)^2.
  const double omega = core::DbToPowerRatio(options_.diffuse.power_ratio_db) / (los_distance_m * los_distance_m);
  return omega * DiffusePdpShape(options_.diffuse, delay_s - los_delay_s);
}

double CirSynthesizer::TrueSinr(const Complex& amplitude, double delay_s, double los_distance_m) const {
  const double interference = noise_psd_ + pulse_.effective_duration_s() * DiffusePdp(delay_s, los_distance_m);
  return std::norm(amplitude) / interference;
}

SynthesizedCir CirSynthesizer::Synthesize(std::span<const SpecularPath> paths, double los_distance_m,
                                          core::Rng& diffuse_rng, core::Rng& noise_rng) const {
  const std::size_t m = fft_.size();
  const double ts = options_.sample_period_s;
  const double start_s = options_.window_start_s;
  const double df_hz = 1.0 / (static_cast<double>(m) * ts);
  const double band_edge_hz = pulse_.band_edge_hz();
  const auto positive_bins = static_cast<std::size_t>(std::floor(band_edge_hz / df_hz));

  SynthesizedCir out;
  std::vector<Complex> spectrum(m, Complex(0.0, 0.0));

  // Specular paths: sum_k alpha_k e^{-j 2 pi f (tau_k - start)} on the in-band bins. Paths whose
  // pulse would wrap around the FFT grid into the window are outside every physical window.
  const double earliest_s = start_s - guard_samples_ * ts;
  const double latest_s = start_s + static_cast<double>(m - static_cast<std::size_t>(guard_samples_)) * ts;
  for (const auto& path : paths) {
    if (path.delay_s < earliest_s || path.delay_s >= latest_s) continue;
    const double rel_s = path.delay_s - start_s;
    const Complex step = std::polar(1.0, -2.0 * core::kPi * df_hz * rel_s);
    Complex positive = path.amplitude;
    Complex negative = path.amplitude;
    spectrum[0] += positive;
    for (std::size_t k = 1; k <= positive_bins && k < m / 2; ++k) {
      positive *= step;
      negative *= std::conj(step);
      spectrum[k] += positive;
      spectrum[m - k] += negative;
    }
    if (path.delay_s >= start_s && path.delay_s < start_s + sample_count_ * ts) {
      out.paths.push_back({path.va_id, path.order, path.delay_s, path.amplitude,
                           TrueSinr(path.amplitude, path.delay_s, los_distance_m)});
    }
  }

  // Diffuse multipath: nu[j] ~ CN(0, S_nu(t_j) T_s) on the window and the guard after it. Every
  // sample takes a draw, zero-weighted before the LOS, so the stream's use does not depend on
  // the geometry.
  if (options_.diffuse.enabled) {
    std::vector<Complex> nu(m, Complex(0.0, 0.0));
    const std::size_t last = static_cast<std::size_t>(sample_count_ + guard_samples_);
    const double los_delay_s = los_distance_m / options_.medium.speed_mps;
    const double omega_ts = core::DbToPowerRatio(options_.diffuse.power_ratio_db) / (los_distance_m * los_distance_m) * ts;
    for (std::size_t j = 0; j < last; ++j) {
      const double excess_s = start_s + static_cast<double>(j) * ts - los_delay_s;
      const Complex draw = diffuse_rng.ComplexNormal(1.0);
      if (excess_s >= 0.0) nu[j] = draw * std::sqrt(omega_ts * DiffusePdpShape(options_.diffuse, excess_s));
    }
    std::vector<Complex> nu_spectrum(m);
    fft_.Forward(nu, nu_spectrum);
    for (std::size_t k = 0; k < m; ++k) spectrum[k] += nu_spectrum[k];
  }

  for (std::size_t k = 0; k < m; ++k) spectrum[k] *= bin_spectrum_[k];
  std::vector<Complex> samples(m);
  fft_.Inverse(spectrum, samples);

  out.cir.start_s = start_s;
  out.cir.sample_period_s = ts;
  out.cir.samples.assign(samples.begin(), samples.begin() + sample_count_);
  for (auto& sample : out.cir.samples) sample += noise_rng.ComplexNormal(noise_psd_);
  return out;
}

}  // namespace mirage::channel
