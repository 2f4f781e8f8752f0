// SPDX-License-Identifier: MIT
// The simulated measurements of one Monte-Carlo run, step by step: the trajectory (shifted by
// the run's grid offset), the visible specular paths, and per anchor either a CIR followed by
// MPC extraction or range-level draws. The Monte-Carlo driver and `mirage simulate` both use it,
// so a recording written by `mirage simulate` holds exactly the ranges the driver's tracker sees.
#pragma once

#include <memory>
#include <vector>

#include "mirage/channel/cir_synthesizer.h"
#include "mirage/channel/range_level_simulator.h"
#include "mirage/core/measurements.h"
#include "mirage/core/rng.h"
#include "mirage/dsp/mpc_extractor.h"
#include "mirage/geometry/trajectory.h"
#include "mirage/geometry/virtual_anchor.h"
#include "mirage/pipeline/experiment_config.h"
#include "mirage/pipeline/recording.h"

namespace mirage::pipeline {

/// What every run of an experiment shares; immutable after construction (thread-safe to read).
struct SimulationContext {
  explicit SimulationContext(const MintExperimentConfig& config);

  const MintExperimentConfig* config = nullptr;
  geometry::VirtualAnchorSet channel_vas;  ///< VAs of the simulated room, up to channel_max_order
  std::unique_ptr<channel::CirSynthesizer> synthesizer;
  std::unique_ptr<dsp::MpcExtractor> extractor;
  std::unique_ptr<channel::RangeLevelSimulator> range_level;  ///< with MeasurementModel::kRangeLevel
};

/// The measurements of run `run` of trajectory `trajectory`. All randomness comes from
/// Rng(seed, trajectory * 1'000'003 + run) sub-streams (one per anchor and purpose, so that
/// adding an anchor shifts no other anchor's noise).
class RunSimulator {
 public:
  RunSimulator(const SimulationContext& context, int trajectory, int run);

  [[nodiscard]] const std::vector<geometry::TrajectorySample>& samples() const { return samples_; }
  [[nodiscard]] const Vec2& offset_m() const { return offset_m_; }
  /// The stream for the tracker's initial-position draw.
  [[nodiscard]] core::Rng& init_rng() { return init_rng_; }

  /// Simulates the channels of step k; returns the true paths per anchor. Must be called for
  /// k = 0, 1, ... in order (the random streams advance).
  const std::vector<std::vector<channel::PathTruth>>& Simulate(std::size_t k);
  /// The ranges of the step last simulated, one entry per anchor: the MPC extractor's output
  /// (CIR model) or the range-level draws.
  void Measure(std::vector<core::AnchorRanges>& measurements) const;

 private:
  const SimulationContext& context_;
  std::vector<geometry::TrajectorySample> samples_;
  Vec2 offset_m_ = Vec2::Zero();
  std::vector<core::Rng> diffuse_rng_, noise_rng_, ranges_rng_;  // one stream per anchor
  core::Rng init_rng_;
  std::vector<channel::SynthesizedCir> cirs_;
  std::vector<core::AnchorRanges> range_level_;
  std::vector<std::vector<channel::PathTruth>> truths_;
};

/// Simulates one run and returns it as a recording (anchors, ranges, truth), as `mirage simulate`
/// writes it. Times without any range of any anchor cannot be written to ranges.csv and are left out.
Recording SimulateRecording(const MintExperimentConfig& config, int trajectory, int run);

}  // namespace mirage::pipeline
