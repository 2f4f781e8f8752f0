// SPDX-License-Identifier: MIT
#include "mirage/pipeline/link_source.h"

#include <algorithm>
#include <chrono>

#include "mirage/channel/link_channel.h"
#include "mirage/geometry/trajectory.h"
#include "mirage/pipeline/anchor_channel_source.h"

namespace mirage::pipeline {

JointTruth SampleJointTruth(const Experiment& e) {
  JointTruth truth;
  const std::size_t agents = e.agents > 0 ? static_cast<std::size_t>(e.agents) : e.trajectories.size();
  std::vector<std::vector<geometry::TrajectorySample>> samples;
  std::size_t longest = 0;
  for (std::size_t a = 0; a < agents; ++a) {
    const TrajectorySpec& t = e.trajectories[a];
    samples.push_back(geometry::SampleTrajectory(t.waypoints_m, t.speed_mps, t.dt_s, Vec2::Zero(), t.turn_radius_m, t.stops));
    longest = std::max(longest, samples.back().size());
    truth.names.push_back(t.name);
  }
  const std::size_t steps = e.steps > 0 ? static_cast<std::size_t>(e.steps) : longest - 1;
  const double dt_s = e.trajectories.front().dt_s;
  truth.positions_m.resize(agents);
  for (std::size_t a = 0; a < agents; ++a) {
    for (std::size_t n = 0; n <= steps; ++n) {
      const auto& s = samples[a][std::min(n, samples[a].size() - 1)];
      truth.positions_m[a].emplace_back(s.position_m.x(), s.position_m.y(), e.trajectories[a].height_m);
    }
  }
  for (std::size_t n = 0; n <= steps; ++n) truth.t_s.push_back(static_cast<double>(n) * dt_s);
  return truth;
}

LinkContext::LinkContext(const Experiment& e, std::vector<channel::LinkSpec> link_specs)
    : experiment(&e),
      links(std::move(link_specs)),
      truth(SampleJointTruth(e)),
      synthesizer(std::make_unique<channel::CirSynthesizer>(e.channel)) {}

LinkSource::LinkSource(const LinkContext& context, int run) : context_(context) {
  const core::Rng run_rng = RunRng(context.experiment->seed, 0, run);
  for (const auto& link : context.links) {
    diffuse_rng_.push_back(run_rng.Substream(link.id + " diffuse"));
    noise_rng_.push_back(run_rng.Substream(link.id + " noise"));
  }
}

std::optional<std::vector<Vec3>> LinkSource::TrueStart() const {
  std::vector<Vec3> start;
  for (const auto& agent : context_.truth.positions_m) start.push_back(agent.front());
  return start;
}

std::optional<SourceStep> LinkSource::Next() {
  if (next_ >= context_.truth.t_s.size()) return std::nullopt;
  const auto start = std::chrono::steady_clock::now();
  const std::size_t n = next_++;
  const Experiment& e = *context_.experiment;
  std::vector<Vec2> agents_m, anchors_m;
  SourceStep step;
  step.epoch.t_s = context_.truth.t_s[n];
  for (const auto& agent : context_.truth.positions_m) {
    agents_m.push_back(agent[n].head<2>());
    step.truth_m.emplace_back(agent[n]);
  }
  for (const auto& a : e.anchors) anchors_m.push_back(a.position_m.head<2>());
  channel::LinkPathOptions options;
  options.max_order = e.channel_max_order;
  options.carrier_hz = e.channel.pulse.carrier_hz;
  options.speed_mps = e.channel.medium.speed_mps;
  options.self_coupling_db = e.self_coupling_db;
  for (std::size_t l = 0; l < context_.links.size(); ++l) {
    const channel::LinkSpec& link = context_.links[l];
    const Vec2 tx_m = channel::EndPosition(link.tx, agents_m, anchors_m);
    const Vec2 rx_m = channel::EndPosition(link.rx, agents_m, anchors_m);
    options.min_reference_m = std::max((link.tx.offset_m - link.rx.offset_m).norm(), 0.1);
    const channel::LinkPaths paths = channel::ComputeLinkPaths(e.plan, tx_m, rx_m, link.self(), options);
    core::CirRecord record;
    record.t_s = step.epoch.t_s;
    record.link_id = link.id;
    record.link_index = static_cast<int>(l);
    record.cir = context_.synthesizer->Synthesize(paths.paths, paths.dm_reference_m, diffuse_rng_[l], noise_rng_[l]).cir;
    step.epoch.cirs.push_back(std::move(record));
  }
  step.simulate_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return step;
}

}  // namespace mirage::pipeline
