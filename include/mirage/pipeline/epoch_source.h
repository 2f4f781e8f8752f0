// SPDX-License-Identifier: MIT
// Where a run's epochs come from: a simulation of the scenario, a recording, or (later) a live
// stream. The runner drives every estimator through this one interface; a source also hands out
// the truth it knows (simulations and recordings with truth.csv), which the estimator never sees.
#pragma once

#include <optional>
#include <vector>

#include "mirage/channel/cir_synthesizer.h"
#include "mirage/core/epoch.h"
#include "mirage/core/types.h"

namespace mirage::pipeline {

/// One epoch and the truth at its time.
struct SourceStep {
  core::Epoch epoch;
  /// The true position of each agent at the epoch, where known.
  std::vector<std::optional<Vec3>> truth_m;
  /// Simulations of anchor channels: the true specular paths per anchor (PathTruth::va_id refers
  /// to the source's channel VA set).
  std::vector<std::vector<channel::PathTruth>> paths;
  /// Simulations without a channel model behind their ranges (ranging with multipath): the ids of
  /// the channel VAs whose paths were measured, for the map's truth.
  std::vector<int> measured_channel_vas;
  /// Simulations of arrival stamps: per record of epoch.toas, per stamp, whether it is the direct
  /// path without an NLOS delay (the truth of a method's line-of-sight labels); empty otherwise.
  std::vector<std::vector<bool>> direct_stamps;
  double simulate_s = 0.0;  ///< CPU time spent making this epoch (s)
};

/// A source of epochs for one run.
class EpochSource {
 public:
  virtual ~EpochSource() = default;
  /// The next epoch, or nothing at the end.
  virtual std::optional<SourceStep> Next() = 0;
  /// The agents' true positions at the start (time start_s()), when known: the prior of a run
  /// that is told where it starts.
  [[nodiscard]] virtual std::optional<std::vector<Vec3>> TrueStart() const = 0;
  /// The time of the start (s): the first epoch's time, or earlier when the agents are placed
  /// before anything is measured (a joint run starts at rest at t = 0 and measures from step 1).
  [[nodiscard]] virtual double start_s() const = 0;
  /// Records dropped because they arrived older than their epoch.
  [[nodiscard]] virtual int out_of_order() const { return 0; }
};

}  // namespace mirage::pipeline
