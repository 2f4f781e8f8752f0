// SPDX-License-Identifier: MIT
#include "mirage/pipeline/run_simulator.h"

#include <algorithm>
#include <string>

#include "mirage/channel/specular_path.h"

namespace mirage::pipeline {
namespace {

core::Rng RunRng(const MintExperimentConfig& config, int trajectory, int run) {
  const auto stream = static_cast<std::uint64_t>(trajectory) * 1'000'003ULL + static_cast<std::uint64_t>(run);
  return core::Rng(config.seed, stream);
}

}  // namespace

SimulationContext::SimulationContext(const MintExperimentConfig& c) : config(&c) {
  channel_vas = geometry::VirtualAnchorSet::Generate(c.anchors_m, c.plan, c.channel_max_order);
  synthesizer = std::make_unique<channel::CirSynthesizer>(c.channel);
  extractor = std::make_unique<dsp::MpcExtractor>(c.mpc, synthesizer->pulse(), synthesizer->sample_count(),
                                                  c.channel.sample_period_s, c.channel.medium);
  if (c.measurement_model == MeasurementModel::kRangeLevel) {
    range_level = std::make_unique<channel::RangeLevelSimulator>(c.range_level, *synthesizer);
  }
}

RunSimulator::RunSimulator(const SimulationContext& context, int trajectory, int run)
    : context_(context),
      init_rng_(RunRng(*context.config, trajectory, run).Substream("init")) {
  const MintExperimentConfig& config = *context.config;
  const core::Rng run_rng = RunRng(config, trajectory, run);
  for (std::size_t a = 0; a < config.anchors_m.size(); ++a) {
    diffuse_rng_.push_back(run_rng.Substream("diffuse/" + std::to_string(a)));
    noise_rng_.push_back(run_rng.Substream("noise/" + std::to_string(a)));
    ranges_rng_.push_back(run_rng.Substream("ranges/" + std::to_string(a)));
  }
  const TrajectorySpec& spec = config.trajectories[static_cast<std::size_t>(trajectory)];
  offset_m_ = RunOffset(config.run_grid, run);
  samples_ = geometry::SampleTrajectory(spec.waypoints_m, spec.speed_mps, spec.dt_s, offset_m_);
  truths_.resize(config.anchors_m.size());
}

const std::vector<std::vector<channel::PathTruth>>& RunSimulator::Simulate(std::size_t k) {
  const MintExperimentConfig& config = *context_.config;
  const Vec2& position_m = samples_[k].position_m;
  cirs_.clear();
  range_level_.clear();
  for (std::size_t a = 0; a < config.anchors_m.size(); ++a) {
    const auto paths = channel::ComputeSpecularPaths(context_.channel_vas, static_cast<int>(a), config.plan,
                                                     position_m, config.channel.pulse.carrier_hz, config.channel.medium);
    // The path-loss reference of the SNR; 1 cm keeps a tag on top of an anchor finite.
    const double los_distance_m = std::max((position_m - config.anchors_m[a]).norm(), 0.01);
    if (context_.range_level) {
      range_level_.push_back(context_.range_level->Simulate(static_cast<int>(a), paths, los_distance_m, ranges_rng_[a], &truths_[a]));
    } else {
      cirs_.push_back(context_.synthesizer->Synthesize(paths, los_distance_m, diffuse_rng_[a], noise_rng_[a]));
      truths_[a] = cirs_.back().paths;
    }
  }
  return truths_;
}

void RunSimulator::Measure(std::vector<core::AnchorRanges>& measurements) const {
  if (context_.range_level) {
    measurements = range_level_;
    return;
  }
  measurements.resize(cirs_.size());
  for (std::size_t a = 0; a < cirs_.size(); ++a) {
    auto& m = measurements[a];
    m.anchor_index = static_cast<int>(a);
    m.ranges.clear();
    for (const auto& mpc : context_.extractor->Extract(cirs_[a].cir)) m.ranges.push_back({mpc.range_m, std::abs(mpc.amplitude)});
  }
}

Recording SimulateRecording(const MintExperimentConfig& config, int trajectory, int run) {
  const SimulationContext context(config);
  RunSimulator simulator(context, trajectory, run);
  Recording recording;
  recording.anchor_ids = config.anchor_ids;
  recording.anchors_m = config.anchors_m;
  recording.anchor_heights_m.assign(config.anchors_m.size(), std::nullopt);
  std::vector<core::AnchorRanges> measurements;
  for (std::size_t k = 0; k < simulator.samples().size(); ++k) {
    simulator.Simulate(k);
    simulator.Measure(measurements);
    const auto& sample = simulator.samples()[k];
    recording.truth.push_back({sample.t_s, sample.position_m});
    const bool any = std::any_of(measurements.begin(), measurements.end(), [](const auto& m) { return !m.ranges.empty(); });
    if (any) recording.steps.push_back({sample.t_s, measurements});
  }
  return recording;
}

}  // namespace mirage::pipeline
