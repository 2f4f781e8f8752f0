// SPDX-License-Identifier: MIT
#include "mirage/channel/raised_cosine_pulse.h"

#include <cassert>
#include <cmath>

#include "mirage/core/constants.h"
#include "mirage/core/fft.h"
#include "mirage/core/types.h"

namespace mirage::channel {
namespace {

using core::kPi;

// Unnormalised RC spectrum X(f): T on the flat part, raised cosine on the roll-off, 0 beyond.
double RcSpectrum(double f_hz, double duration_s, double rolloff) {
  const double f = std::abs(f_hz);
  const double flat_edge = (1.0 - rolloff) / (2.0 * duration_s);
  const double band_edge = (1.0 + rolloff) / (2.0 * duration_s);
  if (f <= flat_edge) return duration_s;
  if (f > band_edge) return 0.0;
  return 0.5 * duration_s * (1.0 + std::cos(kPi * duration_s / rolloff * (f - flat_edge)));
}

// Composite Simpson integral of g over [0, b] with n (even) intervals.
template <typename G>
double Simpson(const G& g, double b, int n) {
  const double h = b / n;
  double sum = g(0.0) + g(b);
  for (int i = 1; i < n; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * g(i * h);
  return sum * h / 3.0;
}

}  // namespace

const core::OptionsDescriptor<PulseOptions>& PulseOptionsDescriptor() {
  using core::ValueRange;
  using O = PulseOptions;
  static const auto descriptor = [] {
    core::OptionsDescriptor<O> d("channel::PulseOptions");
    d.Number(&O::carrier_hz, {.key = "carrier_hz",
                              .unit = "Hz",
                              .range = ValueRange::Closed(1.0, 1e12),
                              .doc = "Carrier (centre) frequency f_c of the raised-cosine pulse. 7 GHz as in Lafer "
                                     "Tab. 3.1."});
    d.Number(&O::rolloff, {.key = "rolloff",
                           .range = ValueRange::Closed(0.0, 1.0),
                           .doc = "Roll-off factor beta_R of the raised-cosine pulse. 0.5 as in Lafer Tab. 3.1."});
    d.Number(&O::duration_s, {.key = "duration_s",
                              .unit = "s",
                              .range = ValueRange::Closed(1e-12, 1e-3),
                              .doc = "Pulse duration T_p; the bandwidth is (1 + beta_R) / T_p. 0.5 ns as in Lafer "
                                     "Tab. 3.1."});
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const PulseOptions& options) { return PulseOptionsDescriptor().Validate(options); }

int PulseTailSamples(const PulseOptions& options, double sample_period_s) {
  return static_cast<int>(std::ceil(kPulseTailDurations * options.duration_s / sample_period_s));
}

std::vector<double> RaisedCosinePulse::SampledSpectrum(std::size_t fft_size, double sample_period_s) const {
  const double df_hz = 1.0 / (static_cast<double>(fft_size) * sample_period_s);
  const double scale = 1.0 / std::sqrt(sample_period_s);
  std::vector<double> spectrum(fft_size);
  for (std::size_t k = 0; k < fft_size; ++k) {
    const double index = k <= fft_size / 2 ? static_cast<double>(k) : static_cast<double>(k) - static_cast<double>(fft_size);
    spectrum[k] = Spectrum(index * df_hz) * scale;
  }
  return spectrum;
}

RaisedCosinePulse::RaisedCosinePulse(const PulseOptions& options) : options_(options) {
  const double t = options_.duration_s;
  const double edge = band_edge_hz();
  constexpr int kIntervals = 4096;
  // All integrals are over the even spectrum, so twice the integral over [0, edge]; the factor
  // cancels in ratios. Energy of X: T (1 - beta / 4).
  const auto p2 = [&](double f) {
    const double x = Spectrum(f);
    return x * x;
  };
  const double energy = 2.0 * Simpson(p2, edge, kIntervals);
  const double second_moment = 2.0 * Simpson([&](double f) { return f * f * p2(f); }, edge, kIntervals);
  rms_bandwidth_hz_ = std::sqrt(second_moment / energy);
  effective_duration_s_ = 2.0 * Simpson([&](double f) { return p2(f) * p2(f); }, edge, kIntervals);

  // Tabulate R(tau) by an inverse FFT of |P(f)|^2 on a fine grid (step T/64, period 128 T, so
  // the periodic copies of R are far below the 1e-4 support threshold), normalised to R(0) = 1.
  constexpr std::size_t kSize = 8192;
  table_step_s_ = t / 64.0;
  const double df_hz = 1.0 / (static_cast<double>(kSize) * table_step_s_);
  std::vector<Complex> spectrum(kSize);
  for (std::size_t k = 0; k < kSize; ++k) {
    const double f = (k < kSize / 2 ? static_cast<double>(k) : static_cast<double>(k) - static_cast<double>(kSize)) * df_hz;
    spectrum[k] = p2(f);
  }
  const core::Fft fft(kSize);
  fft.Inverse(spectrum, spectrum);
  const double r0 = spectrum[0].real();
  const std::size_t max_index = kSize / 4;  // 32 T
  std::size_t last_significant = 0;
  for (std::size_t i = 0; i < max_index; ++i) {
    if (std::abs(spectrum[i].real() / r0) >= 1e-4) last_significant = i;
  }
  autocorrelation_table_.resize(last_significant + 2);
  for (std::size_t i = 0; i < autocorrelation_table_.size(); ++i) autocorrelation_table_[i] = spectrum[i].real() / r0;
  support_s_ = static_cast<double>(last_significant + 1) * table_step_s_;
}

double RaisedCosinePulse::band_edge_hz() const {
  return (1.0 + options_.rolloff) / (2.0 * options_.duration_s);
}

double RaisedCosinePulse::Spectrum(double f_hz) const {
  const double t = options_.duration_s;
  const double norm = std::sqrt(t * (1.0 - options_.rolloff / 4.0));
  return RcSpectrum(f_hz, t, options_.rolloff) / norm;
}

double RaisedCosinePulse::Value(double t_s) const {
  const double t = options_.duration_s;
  const double beta = options_.rolloff;
  const double norm = std::sqrt(t * (1.0 - beta / 4.0));
  const double u = t_s / t;
  const double sinc = std::abs(u) < 1e-12 ? 1.0 : std::sin(kPi * u) / (kPi * u);
  const double denom = 1.0 - 4.0 * beta * beta * u * u;
  double shape = 0.0;
  if (std::abs(denom) < 1e-10) {
    // Removable singularity at |t| = T / (2 beta): limit (pi / 4) sinc(1 / (2 beta)).
    const double v = 1.0 / (2.0 * beta);
    shape = kPi / 4.0 * std::sin(kPi * v) / (kPi * v);
  } else {
    shape = sinc * std::cos(kPi * beta * u) / denom;
  }
  return shape / norm;
}

double RaisedCosinePulse::Autocorrelation(double tau_s) const {
  const double x = std::abs(tau_s) / table_step_s_;
  const auto i = static_cast<std::size_t>(x);
  if (i + 1 >= autocorrelation_table_.size()) return 0.0;
  const double frac = x - static_cast<double>(i);
  return (1.0 - frac) * autocorrelation_table_[i] + frac * autocorrelation_table_[i + 1];
}

double RaisedCosinePulse::range_sigma_at_unit_sinr_m(double speed_mps) const {
  assert(speed_mps > 0.0);
  return speed_mps / (std::sqrt(8.0) * core::kPi * rms_bandwidth_hz_);
}

}  // namespace mirage::channel
