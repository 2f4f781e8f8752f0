// SPDX-License-Identifier: MIT
// UWB channel impulse response synthesis (Lafer 2014 Eq. 2.6):
//   r(t) = sum_k alpha_k s(t - tau_k) + (s * nu)(t) + w(t)
// in complex baseband, sampled at T_s. Specular paths sit at their exact fractional delays
// (synthesised in the frequency domain, where a delay is a phase ramp), diffuse multipath nu is
// white in delay with the double-exponential PDP from the LOS delay on, and w is white noise of
// PSD N0. Samples are scaled so that the projection of r onto the unit-energy pulse at tau_k is
// alpha_k plus noise of variance N0 + T_eff S_nu(tau_k), the SINR denominator of Eq. (3.25).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "mirage/channel/diffuse_multipath.h"
#include "mirage/channel/raised_cosine_pulse.h"
#include "mirage/channel/specular_path.h"
#include "mirage/core/fft.h"
#include "mirage/core/records.h"
#include "mirage/core/medium.h"
#include "mirage/core/options_descriptor.h"
#include "mirage/core/rng.h"

namespace mirage::channel {

/// Parameters of the simulated channel and receiver.
struct ChannelOptions {
  /// What carries the signal: its speed turns path lengths into delays (m/s). Radio (the speed
  /// of light) until the scenario schema can name another medium.
  core::Medium medium = core::Medium::Radio();
  /// Transmit pulse.
  PulseOptions pulse;
  /// Diffuse multipath.
  DiffuseOptions diffuse;
  /// Sample period T_s (s), in [1e-15, 1e-3], below the Nyquist limit 1 / (2 band edge) and at
  /// least window_length_s / 1e6 and pulse.duration_s / 1000. 0.125 ns, close to the thesis's
  /// 0.133 ns synthetic grid.
  double sample_period_s = 0.125e-9;
  /// Delay of the first sample (s), in [0, 1]. Anchors and agent are synchronised (ToA), so 0.
  double window_start_s = 0.0;
  /// Length of the CIR window (s), in [1e-12, 1] and at least 8 pulse durations. 128 ns covers
  /// second-order paths in a 9 m room.
  double window_length_s = 128e-9;
  /// SNR of an unobstructed LOS at 1 m: LOS energy over N0 (dB), in [-100, 200]. 35 dB gives a LOS
  /// SNR of about 25 dB at 3 m, typical of the thesis's measured seminar-room channels.
  double snr_at_1m_db = 35.0;
};

/// The options' descriptor (keys, units, ranges, docs, the samples-per-CIR check;
/// core/options_descriptor.h). `medium` is no key: the scenario schema cannot name a medium yet.
/// The checks that involve the pulse duration are not in it, as a cooperative scenario sets the
/// duration per variant after reading the section: see Validate().
const core::OptionsDescriptor<ChannelOptions>& ChannelOptionsDescriptor();

/// Problems with the options, empty if valid: the descriptor's ("key: message"), then the medium's
/// speed and, with everything else valid, the checks against the pulse ("key must ..."): the
/// Nyquist limit of sample_period_s, at most 1000 samples per pulse duration and a window of at
/// least 8 pulse durations.
std::vector<std::string> Validate(const ChannelOptions& options);

/// Ground truth of one specular path in a synthesised CIR.
struct PathTruth {
  int va_id = 0;          ///< VA id
  int order = 0;          ///< reflection order
  double delay_s = 0.0;   ///< true delay (s)
  Complex amplitude;      ///< true complex amplitude
  double sinr = 0.0;      ///< true SINR |alpha|^2 / (N0 + T_eff S_nu(tau)) (linear), Eq. (3.25)
};

/// A synthesised CIR with its ground truth.
struct SynthesizedCir {
  core::Cir cir;                  ///< the received samples
  std::vector<PathTruth> paths;   ///< the specular paths inside the window
};

/// Synthesises CIRs for one set of channel options; immutable after construction, so one
/// instance can serve several threads.
class CirSynthesizer {
 public:
  explicit CirSynthesizer(const ChannelOptions& options);

  [[nodiscard]] const ChannelOptions& options() const { return options_; }
  [[nodiscard]] const RaisedCosinePulse& pulse() const { return pulse_; }
  /// Number of samples per CIR.
  [[nodiscard]] int sample_count() const { return sample_count_; }
  /// White-noise PSD N0 in the CIR's energy unit (the 1 m LOS energy is 1).
  [[nodiscard]] double noise_psd() const { return noise_psd_; }
  /// DM power delay profile S_nu at delay tau for a LOS distance d_LOS (energy per second).
  [[nodiscard]] double DiffusePdp(double delay_s, double los_distance_m) const;
  /// True SINR of a path of given amplitude and delay, Eq. (3.25).
  [[nodiscard]] double TrueSinr(const Complex& amplitude, double delay_s, double los_distance_m) const;

  /// One CIR. los_distance_m is the agent-anchor distance (the DM starts at its delay even when
  /// the LOS itself is blocked). diffuse_rng and noise_rng are separate streams so that switching
  /// DM off leaves the noise unchanged.
  SynthesizedCir Synthesize(std::span<const SpecularPath> paths, double los_distance_m, core::Rng& diffuse_rng,
                            core::Rng& noise_rng) const;

 private:
  ChannelOptions options_;
  RaisedCosinePulse pulse_;
  int sample_count_ = 0;
  int guard_samples_ = 0;
  double noise_psd_ = 0.0;
  core::Fft fft_;
  std::vector<double> bin_spectrum_;      // P(f_k) / sqrt(T_s) of each bin
};

}  // namespace mirage::channel
