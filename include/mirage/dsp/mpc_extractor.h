// SPDX-License-Identifier: MIT
// Multipath-component (MPC) extraction by search-subtract-readjust (Lafer 2014 Sec. 3.3,
// Eq. 3.1-3.3; the cancellation algorithm of its ref. [28]).
//
// Choice (documented in docs/methods/mint.md): the search runs on the matched-filter output
// y(tau) = <r, s(. - tau)> rather than on |r| itself. For one path in white noise, argmax |y| is
// the ML delay and y(tau_hat) is exactly the projection of Eq. (3.1); subtracting
// alpha_hat s(t - tau_hat) from r (Eq. 3.2) is subtracting alpha_hat R_ss(tau - tau_hat) from y.
// Delays are refined below the sample grid by a parabola through |y|^2 at the peak; after each new
// component, the earlier components that overlap it and then the new one are re-estimated one at
// a time with the others removed ("readjust"), which undoes the bias a strong neighbour leaves.
#pragma once

#include <string>
#include <vector>

#include "mirage/channel/raised_cosine_pulse.h"
#include "mirage/core/fft.h"
#include "mirage/core/records.h"
#include "mirage/core/medium.h"
#include "mirage/core/options_descriptor.h"
#include "mirage/core/types.h"

namespace mirage::dsp {

/// Parameters of the extraction.
struct MpcExtractorOptions {
  /// Maximum number of components K, in [1, 1000]. 20 as in Lafer 2014 Tab. 3.1.
  int max_components = 20;
  /// Stop when a component's energy falls this far below the strongest one (dB), in [-300, -1e-9].
  /// The thesis only says the threshold is relative [GAP]. -30 dB is below the noise floor of a
  /// 20-35 dB LOS, so with the defaults the extraction usually runs to max_components and its last
  /// components are diffuse-multipath and noise peaks: clutter the association has to reject, as
  /// with the thesis's measured data (Sec. 3.3: "Z typically also contains spurious ranges").
  double relative_threshold_db = -30.0;
  /// Re-estimate overlapping earlier components after each new one.
  bool readjust = true;
};

/// The options' descriptor (keys, units, ranges, docs; core/options_descriptor.h).
const core::OptionsDescriptor<MpcExtractorOptions>& MpcExtractorOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const MpcExtractorOptions& options);

/// One extracted component.
struct Mpc {
  double delay_s = 0.0;  ///< estimated delay tau_hat (s)
  double range_m = 0.0;  ///< c * tau_hat, c the medium's signal speed (m)
  Complex amplitude;     ///< estimated complex amplitude alpha_hat (the CIR's unit)
};

/// Extracts MPCs from CIRs of a fixed length and sample period; immutable, thread-safe.
class MpcExtractor {
 public:
  /// @param pulse           the template s(t), the transmit pulse.
  /// @param sample_count    samples per CIR.
  /// @param sample_period_s T_s (s).
  /// @param medium          carries the signal: range = delay * medium.speed_mps.
  MpcExtractor(const MpcExtractorOptions& options, const channel::RaisedCosinePulse& pulse, int sample_count,
               double sample_period_s, const core::Medium& medium);

  /// The medium whose speed turns delays into ranges.
  [[nodiscard]] const core::Medium& medium() const { return medium_; }

  /// Components sorted by increasing delay. The CIR must have the constructor's length and
  /// sample period.
  [[nodiscard]] std::vector<Mpc> Extract(const core::Cir& cir) const;
  /// The same with a per-call component count (Kulmer et al. extract 1.5 |K| components, |K| the
  /// number of paths the filter expects on the link, Sec. IV-B); the relative threshold still
  /// applies.
  [[nodiscard]] std::vector<Mpc> Extract(const core::Cir& cir, int max_components) const;
  /// The same on a matched-filter output computed before (MatchedFilter(cir)), so that a caller
  /// who also projects onto the pulse (ProjectAt) filters the CIR once.
  [[nodiscard]] std::vector<Mpc> ExtractFromMatchedFilter(std::vector<Complex> matched_filter_output, double start_s,
                                                          int max_components) const;
  /// The projection <r, s(. - delay)> of the CIR onto the pulse at an arbitrary delay (Kulmer et
  /// al. Eq. 6, the amplitude a(tau)), interpolated quadratically from the matched-filter output
  /// y = MatchedFilter(cir) of a CIR starting at start_s; 0 outside the window.
  [[nodiscard]] Complex ProjectAt(const std::vector<Complex>& matched_filter_output, double start_s,
                                  double delay_s) const;

  /// The matched-filter output y[n] = <r, s(. - n T_s)> of a CIR (exposed for tests and plots).
  [[nodiscard]] std::vector<Complex> MatchedFilter(const core::Cir& cir) const;

 private:
  struct Component {
    double offset_samples = 0.0;  // delay from the window start (samples)
    Complex amplitude;
  };
  // The residual matched-filter output with its energies |y|^2 and per-block maxima, so that
  // the strongest peak is found without scanning the whole window each time.
  struct Residual {
    std::vector<Complex> y;
    std::vector<double> energy;
    std::vector<int> block_argmax;
  };
  // Peak search around sample index n in y, sub-sample parabola; returns the component.
  [[nodiscard]] Component Refine(const std::vector<Complex>& y, int n) const;
  // y += sign * alpha * R((n - offset_samples) T_s) over the component's support; updates the energies.
  void AddScaled(Residual& residual, const Component& c, double sign) const;
  void UpdateBlocks(Residual& residual, int lo, int hi) const;
  // Re-estimates one component with everything else removed (the "readjust" step).
  void Readjust(Residual& residual, Component& c) const;
  [[nodiscard]] int ArgMax(const Residual& residual) const;

  MpcExtractorOptions options_;
  channel::RaisedCosinePulse pulse_;
  int sample_count_ = 0;
  double sample_period_s_ = 0.0;
  core::Medium medium_;
  double threshold_ratio_ = 0.0;
  int support_samples_ = 0;                // |R| < 1e-3 beyond this many samples
  std::vector<double> autocorrelation_;    // R(i T_s / kTableOversampling), i >= 0
  core::Fft fft_;
  std::vector<double> template_spectrum_;  // P(f_k) / sqrt(T_s), real and even
};

}  // namespace mirage::dsp
