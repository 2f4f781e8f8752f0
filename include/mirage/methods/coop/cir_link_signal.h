// SPDX-License-Identifier: MIT
// The cooperative filter's view of one link's CIR (methods/coop/coop_tracker.h LinkSignal): MPC
// extraction with a per-call component count (Kulmer et al. Eq. 6-7) and the projection of the
// received signal onto the pulse at any delay (Sec. III-C), both from one matched filtering.
#pragma once

#include <vector>

#include "mirage/core/records.h"
#include "mirage/core/medium.h"
#include "mirage/core/types.h"
#include "mirage/dsp/mpc_extractor.h"
#include "mirage/methods/coop/coop_tracker.h"

namespace mirage::methods::coop {

/// A CIR seen through an MPC extractor; keeps references to both (they must outlive it).
class CirLinkSignal final : public LinkSignal {
 public:
  CirLinkSignal(const dsp::MpcExtractor& extractor, const core::Cir& cir);

  [[nodiscard]] std::vector<double> Ranges(int count) const override;
  [[nodiscard]] double AmplitudeAt(double range_m) const override;

 private:
  const dsp::MpcExtractor* extractor_;
  double start_s_ = 0.0;
  std::vector<Complex> matched_;  // the matched-filter output of the CIR
};

/// The filter's pulse facts of a transmit pulse sent through a medium.
PulseFacts PulseFactsOf(const channel::RaisedCosinePulse& pulse, const core::Medium& medium);

}  // namespace mirage::methods::coop
