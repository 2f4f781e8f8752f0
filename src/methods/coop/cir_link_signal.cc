// SPDX-License-Identifier: MIT
#include "mirage/methods/coop/cir_link_signal.h"

#include <cmath>


namespace mirage::methods::coop {

CirLinkSignal::CirLinkSignal(const dsp::MpcExtractor& extractor, const core::Cir& cir)
    : extractor_(&extractor), start_s_(cir.start_s), matched_(extractor.MatchedFilter(cir)) {}

std::vector<double> CirLinkSignal::Ranges(int count) const {
  std::vector<double> ranges;
  for (const auto& mpc : extractor_->ExtractFromMatchedFilter(matched_, start_s_, count)) ranges.push_back(mpc.range_m);
  return ranges;
}

double CirLinkSignal::AmplitudeAt(double range_m) const {
  return std::abs(extractor_->ProjectAt(matched_, start_s_, range_m / extractor_->medium().speed_mps));
}

PulseFacts PulseFactsOf(const channel::RaisedCosinePulse& pulse, const core::Medium& medium) {
  return {pulse.options().duration_s, pulse.range_sigma_at_unit_sinr_m(medium.speed_mps), medium};
}

}  // namespace mirage::methods::coop
