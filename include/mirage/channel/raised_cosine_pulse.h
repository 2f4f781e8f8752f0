// SPDX-License-Identifier: MIT
// The raised-cosine (RC) transmit pulse of MINT, as its unit-energy complex-baseband equivalent
// (Lafer 2014 App. A.5, Eq. A.15-A.19). Centre f_c, roll-off beta_R, pulse duration T_p; the
// baseband spectrum occupies |f| <= (1 + beta_R) / (2 T_p).
#pragma once

#include <string>
#include <vector>

#include "mirage/core/options_descriptor.h"

namespace mirage::channel {

/// Parameters of the RC pulse.
struct PulseOptions {
  /// Carrier (centre) frequency f_c (Hz), in [1, 1e12]. 7 GHz as in Lafer 2014 Tab. 3.1.
  double carrier_hz = 7.0e9;
  /// Roll-off factor beta_R, in [0, 1]. 0.5 as in Lafer 2014 Tab. 3.1.
  double rolloff = 0.5;
  /// Pulse duration T_p (s), in [1e-12, 1e-3]; the bandwidth is (1 + beta_R) / T_p. 0.5 ns as in
  /// Tab. 3.1.
  double duration_s = 0.5e-9;
};

/// The options' descriptor (keys, units, ranges, docs; core/options_descriptor.h).
const core::OptionsDescriptor<PulseOptions>& PulseOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const PulseOptions& options);

/// The RC pulse's tails fall below 1e-6 of its peak within this many pulse durations; zero
/// padding of this length keeps circular (FFT) convolutions from wrapping.
inline constexpr double kPulseTailDurations = 32.0;

/// kPulseTailDurations pulse durations in samples of period sample_period_s (rounded up).
int PulseTailSamples(const PulseOptions& options, double sample_period_s);

/// Unit-energy baseband RC pulse p(t) with spectrum P(f), both real and even.
class RaisedCosinePulse {
 public:
  explicit RaisedCosinePulse(const PulseOptions& options);

  [[nodiscard]] const PulseOptions& options() const { return options_; }
  /// P(f) of the unit-energy pulse (sqrt(s)); zero beyond band_edge_hz().
  [[nodiscard]] double Spectrum(double f_hz) const;
  /// p(t) of the unit-energy pulse (1/sqrt(s)), Eq. (A.19) scaled to unit energy.
  [[nodiscard]] double Value(double t_s) const;
  /// Autocorrelation R(tau) = integral |P(f)|^2 e^{j 2 pi f tau} df, R(0) = 1 (table, linear
  /// interpolation; 0 beyond autocorrelation_support_s()).
  [[nodiscard]] double Autocorrelation(double tau_s) const;
  /// Largest |tau| at which Autocorrelation() is tabulated (s); beyond it |R| < 1e-4.
  [[nodiscard]] double autocorrelation_support_s() const { return support_s_; }
  /// One-sided band edge (1 + beta_R) / (2 T_p) (Hz).
  [[nodiscard]] double band_edge_hz() const;
  /// RMS (effective) bandwidth beta of the baseband spectrum, Eq. (3.29) (Hz). Baseband, not
  /// passband: with the carrier included beta would be about f_c and the CRLB absurdly small.
  [[nodiscard]] double rms_bandwidth_hz() const { return rms_bandwidth_hz_; }
  /// Effective pulse duration T_eff = integral |P(f)|^4 df (s): the factor that turns the diffuse
  /// power delay profile into interference energy in the SINR of Eq. (3.25).
  [[nodiscard]] double effective_duration_s() const { return effective_duration_s_; }
  /// Range standard deviation at SINR = 1 from the CRLB, c / (sqrt(8) pi beta) (m), Eq. (3.28).
  /// @param speed_mps the signal speed c of the medium (m/s), > 0: the pulse fixes the delay
  ///                  resolution, the medium turns it into a range.
  [[nodiscard]] double range_sigma_at_unit_sinr_m(double speed_mps) const;
  /// The spectrum of the discrete unit-energy pulse p[n] = sqrt(T_s) p(n T_s) on the bins of a
  /// length-fft_size DFT: P(f_k) / sqrt(T_s), real and even (bin k >= fft_size / 2 is negative).
  [[nodiscard]] std::vector<double> SampledSpectrum(std::size_t fft_size, double sample_period_s) const;

 private:
  PulseOptions options_;
  double rms_bandwidth_hz_ = 0.0;
  double effective_duration_s_ = 0.0;
  double support_s_ = 0.0;
  double table_step_s_ = 0.0;
  std::vector<double> autocorrelation_table_;  // R(i * table_step_s_), i >= 0
};

}  // namespace mirage::channel
