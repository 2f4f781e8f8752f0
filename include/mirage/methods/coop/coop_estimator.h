// SPDX-License-Identifier: MIT
// Anchorless cooperative tracking behind the Estimator interface (Kulmer et al.): all of the
// world's agents in one filter, fed with the CIR of every link each epoch (its own channel, the
// channel to every other agent and, with CoopOptions::anchor_links, the channel from the first
// anchor), with the given floor plan's walls in the state.
#pragma once

#include <memory>
#include <vector>

#include "mirage/channel/link.h"
#include "mirage/dsp/mpc_extractor.h"
#include "mirage/methods/coop/coop_tracker.h"
#include "mirage/methods/estimator.h"
#include "mirage/methods/world.h"

namespace mirage::methods::coop {

/// The links the method measures, in the filter's stacking order (Eq. 12), as the simulator
/// needs them: self links, relative links (1,2), (1,3), ..., then the anchor links.
std::vector<channel::LinkSpec> CoopLinks(const CoopOptions& options, const World& world);

class CoopEstimator final : public Estimator {
 public:
  CoopEstimator(const CoopOptions& options, const World& world);

  void Initialize(const Prior& prior) override;
  /// Expects one CIR per link (CoopLinks order, by link_index).
  StepOutput Process(const core::Epoch& epoch) override;
  [[nodiscard]] std::vector<WallEstimate> Walls() const override;
  /// The filter's covariance recursion on the true trajectory and the true walls with every
  /// visible, unambiguous path of its model measured at the CRLB variance of its true SINR (no
  /// misses, no wrong associations).
  [[nodiscard]] std::vector<std::vector<double>> PosteriorBound(const BoundInput& truth) const override;

 private:
  CoopOptions options_;
  World world_;
  std::vector<Link> links_;
  std::unique_ptr<channel::CirSynthesizer> synthesizer_;  // the pulse, sampling and true SINR
  std::unique_ptr<dsp::MpcExtractor> extractor_;
  CoopTracker tracker_;
};

}  // namespace mirage::methods::coop
