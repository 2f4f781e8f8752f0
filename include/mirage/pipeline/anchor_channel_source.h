// SPDX-License-Identifier: MIT
// Simulated epochs of the channels between the anchors and one agent walking a trajectory: per
// epoch and anchor the visible specular paths of the true floor plan (image sources up to the
// simulated order), then either a CIR with diffuse multipath and noise followed by MPC extraction,
// or range-level draws at each path's CRLB, or a ranging system's one range per anchor. Run i of
// trajectory t draws all its randomness from Rng(seed, t * 1000003 + i) sub-streams, one per
// anchor and purpose, so results do not depend on the thread count and adding an anchor shifts
// no other anchor's noise. `mirage simulate` writes exactly these epochs as recorded data.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "mirage/channel/cir_synthesizer.h"
#include "mirage/channel/range_level_simulator.h"
#include "mirage/core/rng.h"
#include "mirage/dsp/mpc_extractor.h"
#include "mirage/geometry/trajectory.h"
#include "mirage/geometry/virtual_anchor.h"
#include "mirage/pipeline/epoch_source.h"
#include "mirage/pipeline/experiment.h"

namespace mirage::pipeline {

/// What every run of an experiment shares; immutable after construction (thread-safe to read).
struct AnchorChannelContext {
  explicit AnchorChannelContext(const Experiment& experiment);
  const Experiment* experiment = nullptr;
  geometry::VirtualAnchorSet channel_vas;  ///< VAs of the simulated room, up to channel_max_order
  std::unique_ptr<channel::CirSynthesizer> synthesizer;
  std::unique_ptr<dsp::MpcExtractor> extractor;
  std::unique_ptr<channel::RangeLevelSimulator> range_level;  ///< with MeasurementModel::kRangeLevel
};

/// The random stream of run `run` of trajectory `trajectory` (joint runs: trajectory 0).
core::Rng RunRng(std::uint64_t seed, int trajectory, int run);

/// The epochs of one run.
class AnchorChannelSource final : public EpochSource {
 public:
  AnchorChannelSource(const AnchorChannelContext& context, int trajectory, int run);

  std::optional<SourceStep> Next() override;
  [[nodiscard]] std::optional<std::vector<Vec3>> TrueStart() const override;
  [[nodiscard]] double start_s() const override { return samples_.front().t_s; }

  /// The run's offset on the run grid.
  [[nodiscard]] const Vec2& offset_m() const { return offset_m_; }
  /// The stream of the estimator's perturbed start.
  [[nodiscard]] core::Rng& init_rng() { return init_rng_; }

 private:
  [[nodiscard]] Vec3 TruthAt(std::size_t k) const;

  const AnchorChannelContext& context_;
  const TrajectorySpec& trajectory_;
  std::vector<geometry::TrajectorySample> samples_;
  Vec2 offset_m_ = Vec2::Zero();
  std::vector<core::Rng> diffuse_rng_, noise_rng_, ranges_rng_;  // one stream per anchor
  core::Rng init_rng_;
  std::size_t next_ = 0;
};

}  // namespace mirage::pipeline
