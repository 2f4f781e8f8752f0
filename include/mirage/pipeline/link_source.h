// SPDX-License-Identifier: MIT
// Simulated epochs of a group of agents walking together, for methods that consume the CIRs of
// named links (cooperative tracking, Kulmer et al. Sec. IV-D): per step and link the specular
// paths of the true floor plan between the link's antennas by image sources, the antenna
// coupling of an agent's own channel, diffuse multipath and noise. The agents stand at their
// known start at t = 0 and the links are measured from the first step on. Run i draws from
// Rng(seed, i) sub-streams named after the link, so a link sees the same draws in every grid
// variant that has it (common random numbers).
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "mirage/channel/cir_synthesizer.h"
#include "mirage/channel/link.h"
#include "mirage/core/rng.h"
#include "mirage/pipeline/epoch_source.h"
#include "mirage/pipeline/experiment.h"

namespace mirage::pipeline {

/// The agents' true positions of a joint run, per agent and step (step 0 the start), the same in
/// every run: each walks its trajectory and stays at its end once there.
struct JointTruth {
  std::vector<std::vector<Vec3>> positions_m;  ///< [agent][step]
  std::vector<double> t_s;                      ///< [step]
  std::vector<std::string> names;               ///< the agents' trajectory names
};

/// The joint truth of an experiment: its first `agents` trajectories (all when 0) for `steps`
/// steps (until the longest has ended when 0); their step times must be equal.
JointTruth SampleJointTruth(const Experiment& experiment);

/// What every run of an experiment shares; immutable after construction.
struct LinkContext {
  LinkContext(const Experiment& experiment, std::vector<channel::LinkSpec> links);
  const Experiment* experiment = nullptr;
  std::vector<channel::LinkSpec> links;
  JointTruth truth;
  std::unique_ptr<channel::CirSynthesizer> synthesizer;
};

/// The epochs of one joint run: steps 1 .. N, one CIR per link.
class LinkSource final : public EpochSource {
 public:
  LinkSource(const LinkContext& context, int run);

  std::optional<SourceStep> Next() override;
  [[nodiscard]] std::optional<std::vector<Vec3>> TrueStart() const override;
  [[nodiscard]] double start_s() const override { return context_.truth.t_s.front(); }

 private:
  const LinkContext& context_;
  std::vector<core::Rng> diffuse_rng_, noise_rng_;  // one stream per link
  std::size_t next_ = 1;
};

}  // namespace mirage::pipeline
