// SPDX-License-Identifier: MIT
// Range-level measurement simulator: the output of a channel estimator without the waveforms
// (digest slam_multipath_leitinger.md Sec. 6.2 item 7). Per visible specular path: a detection
// with probability P_d (never below a minimum SINR), a range with the CRLB noise of its true SINR
// (Lafer Eq. 3.28) and an amplitude |alpha + CN(0, |alpha|^2 / SINR)|, i.e. Rician with K = SINR,
// so that the moment-based SINR estimator sees what it would see on CIRs. Paths closer than the
// resolution come out as one range. Clutter: a Poisson number of ranges uniform over the
// observed range window, with Rayleigh amplitudes at the diffuse-multipath-plus-noise level of
// their delay. This is what `mirage simulate` writes as ranges.csv.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "mirage/channel/cir_synthesizer.h"
#include "mirage/channel/specular_path.h"
#include "mirage/core/records.h"
#include "mirage/core/options_descriptor.h"
#include "mirage/core/rng.h"

namespace mirage::channel {

/// Parameters of the range-level simulation.
struct RangeLevelOptions {
  /// Probability that a path above min_sinr_db is detected, in [0, 1]. 0.95: a
  /// simulation default (the MINT and SLAM papers give none), one missed path in twenty.
  double detection_probability = 0.95;
  /// Mean number of clutter ranges per anchor and step (Poisson), in [0, 1000].
  /// 1: a simulation default (the MINT and SLAM papers give none).
  double clutter_rate = 1.0;
  /// Paths below this true SINR are never detected (dB), in [-200, 200]. -10 dB: at lower SINR the
  /// matched-filter peak of a path is lost in the diffuse multipath.
  double min_sinr_db = -10.0;
  /// Detected paths closer than this merge into one range (m), in [0, 1e9]: half the pulse length
  /// c T_p / 2 = 7.5 cm at T_p = 0.5 ns, where two pulses are no longer separate peaks.
  double resolution_m = 0.075;
  /// Cap on the range standard deviation (m), in [1e-9, 1e9]: sigma_VA,max = 0.22 m of Lafer 2014.
  double max_range_sigma_m = 0.22;
};

/// The options' descriptor (keys, units, ranges, docs; core/options_descriptor.h).
const core::OptionsDescriptor<RangeLevelOptions>& RangeLevelOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const RangeLevelOptions& options);

/// Draws range measurements; immutable, one instance serves several threads.
class RangeLevelSimulator {
 public:
  /// synthesizer provides the SINR model (N0, the DM PDP, the pulse) and the CIR window; it must
  /// outlive this object.
  RangeLevelSimulator(const RangeLevelOptions& options, const CirSynthesizer& synthesizer);

  /// The unlabeled ranges of one anchor at one step (sorted by range; consumers must not rely on
  /// any order). truth, if given, is replaced by the paths inside the window with their true SINR
  /// (as CirSynthesizer::Synthesize returns them).
  core::RangeSet Simulate(int anchor_index, std::span<const SpecularPath> paths, double los_distance_m,
                              core::Rng& rng, std::vector<PathTruth>* truth = nullptr) const;

 private:
  RangeLevelOptions options_;
  const CirSynthesizer* synthesizer_;
};

}  // namespace mirage::channel
