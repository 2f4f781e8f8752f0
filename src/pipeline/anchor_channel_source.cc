// SPDX-License-Identifier: MIT
#include "mirage/pipeline/anchor_channel_source.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "mirage/channel/ranging_simulator.h"
#include "mirage/channel/specular_path.h"
#include "mirage/geometry/visibility.h"

namespace mirage::pipeline {
namespace {

std::vector<Vec2> PlanarAnchors(const Experiment& experiment) {
  std::vector<Vec2> out;
  for (const auto& a : experiment.anchors) out.push_back(a.position_m.head<2>());
  return out;
}

double Seconds(std::chrono::steady_clock::duration d) { return std::chrono::duration<double>(d).count(); }

}  // namespace

core::Rng RunRng(std::uint64_t seed, int trajectory, int run) {
  const auto stream = static_cast<std::uint64_t>(trajectory) * 1'000'003ULL + static_cast<std::uint64_t>(run);
  return core::Rng(seed, stream);
}

AnchorChannelContext::AnchorChannelContext(const Experiment& e) : experiment(&e) {
  const bool channel = e.measurement_model == MeasurementModel::kCir || e.measurement_model == MeasurementModel::kRangeLevel;
  if (channel || (e.measurement_model == MeasurementModel::kRanging && e.ranging.multipath)) {
    channel_vas = geometry::VirtualAnchorSet::Generate(PlanarAnchors(e), e.plan, e.channel_max_order);
  }
  if (!channel) return;
  synthesizer = std::make_unique<channel::CirSynthesizer>(e.channel);
  extractor = std::make_unique<dsp::MpcExtractor>(e.mpc, synthesizer->pulse(), synthesizer->sample_count(),
                                                  e.channel.sample_period_s, e.channel.medium);
  if (e.measurement_model == MeasurementModel::kRangeLevel) {
    range_level = std::make_unique<channel::RangeLevelSimulator>(e.range_level, *synthesizer);
  }
}

AnchorChannelSource::AnchorChannelSource(const AnchorChannelContext& context, int trajectory, int run)
    : context_(context),
      trajectory_(context.experiment->trajectories[static_cast<std::size_t>(trajectory)]),
      init_rng_(RunRng(context.experiment->seed, trajectory, run).Substream("init")) {
  const Experiment& e = *context.experiment;
  const core::Rng run_rng = RunRng(e.seed, trajectory, run);
  for (std::size_t a = 0; a < e.anchors.size(); ++a) {
    diffuse_rng_.push_back(run_rng.Substream("diffuse/" + std::to_string(a)));
    noise_rng_.push_back(run_rng.Substream("noise/" + std::to_string(a)));
    ranges_rng_.push_back(run_rng.Substream((e.measurement_model == MeasurementModel::kRanging ? "ranging/" : "ranges/") +
                                            std::to_string(a)));
  }
  offset_m_ = RunOffset(e.run_grid, run);
  samples_ = geometry::SampleTrajectory(trajectory_.waypoints_m, trajectory_.speed_mps, trajectory_.dt_s, offset_m_,
                                        trajectory_.turn_radius_m, trajectory_.stops);
}

Vec3 AnchorChannelSource::TruthAt(std::size_t k) const {
  return Vec3(samples_[k].position_m.x(), samples_[k].position_m.y(), trajectory_.height_m);
}

std::optional<std::vector<Vec3>> AnchorChannelSource::TrueStart() const { return std::vector<Vec3>{TruthAt(0)}; }

std::optional<SourceStep> AnchorChannelSource::Next() {
  if (next_ >= samples_.size()) return std::nullopt;
  const auto start = std::chrono::steady_clock::now();
  const std::size_t k = next_++;
  const Experiment& e = *context_.experiment;
  const Vec2& position_m = samples_[k].position_m;
  SourceStep step;
  step.epoch.t_s = samples_[k].t_s;
  step.truth_m = {TruthAt(k)};
  step.paths.resize(e.anchors.size());
  for (std::size_t a = 0; a < e.anchors.size(); ++a) {
    core::RangeSet set;
    set.t_s = samples_[k].t_s;
    set.anchor_id = e.anchors[a].id;
    set.anchor_index = static_cast<int>(a);
    if (e.measurement_model == MeasurementModel::kRanging) {
      // The 3-D line of sight, and with multipath every visible reflection (a vertical wall keeps
      // the height difference, so a path's 3-D length follows from its planar one).
      std::vector<double> ranges_m{(TruthAt(k) - e.anchors[a].position_m).norm()};
      if (e.ranging.multipath) {
        const double dz_m = trajectory_.height_m - e.anchors[a].position_m.z();
        for (const int id : geometry::VisibleVirtualAnchors(context_.channel_vas, static_cast<int>(a), e.plan, position_m,
                                                            e.channel_max_order)) {
          const auto& va = context_.channel_vas[id];
          if (va.order == 0) continue;
          const double planar_m = (va.position_m - position_m).norm();
          ranges_m.push_back(std::sqrt(planar_m * planar_m + dz_m * dz_m));
          step.measured_channel_vas.push_back(id);
        }
      }
      set.ranges = channel::SimulateRanging(e.ranging, ranges_m, ranges_rng_[a]);
    } else {
      const auto paths = channel::ComputeSpecularPaths(context_.channel_vas, static_cast<int>(a), e.plan, position_m,
                                                       e.channel.pulse.carrier_hz, e.channel.medium);
      // The path-loss reference of the SNR; 1 cm keeps a tag on top of an anchor finite.
      const double los_distance_m = std::max((position_m - e.anchors[a].position_m.head<2>()).norm(), 0.01);
      if (context_.range_level) {
        set.ranges = context_.range_level->Simulate(static_cast<int>(a), paths, los_distance_m, ranges_rng_[a], &step.paths[a]).ranges;
      } else {
        const auto cir = context_.synthesizer->Synthesize(paths, los_distance_m, diffuse_rng_[a], noise_rng_[a]);
        step.paths[a] = cir.paths;
        for (const auto& mpc : context_.extractor->Extract(cir.cir)) set.ranges.push_back({mpc.range_m, std::abs(mpc.amplitude)});
      }
    }
    step.epoch.range_sets.push_back(std::move(set));
  }
  step.simulate_s = Seconds(std::chrono::steady_clock::now() - start);
  return step;
}

}  // namespace mirage::pipeline
