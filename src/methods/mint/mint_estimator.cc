// SPDX-License-Identifier: MIT
#include "mirage/methods/mint/mint_estimator.h"

#include <vector>

#include "mirage/channel/raised_cosine_pulse.h"

namespace mirage::methods::mint {
namespace {

std::vector<Vec2> PlanarAnchors(const World& world) {
  std::vector<Vec2> out;
  for (const auto& a : world.anchors) out.push_back(a.position_m.head<2>());
  return out;
}

}  // namespace

double RangeSigmaAtUnitSinr(const World& world) {
  return channel::RaisedCosinePulse(world.channel.pulse).range_sigma_at_unit_sinr_m(world.channel.medium.speed_mps);
}

MintEstimator::MintEstimator(const MintOptions& options, const World& world)
    : world_(world),
      search_(options.relocalization),
      start_(world.physical.speed_mps),
      vas_(geometry::VirtualAnchorSet::Generate(PlanarAnchors(world_), world_.floor_plan, options.max_order)),
      tracker_(options, vas_, world_.floor_plan, RangeSigmaAtUnitSinr(world_)) {}

void MintEstimator::Initialize(const Prior& prior) { tracker_.Initialize(prior.t_s, prior.positions_m.front().head<2>()); }

bool MintEstimator::InitializeFromEpoch(const core::Epoch& epoch) {
  const auto start_m = start_.Add(epoch.t_s, SearchFloorPlan(vas_, world_.floor_plan, epoch.range_sets, search_));
  if (!start_m) return false;
  tracker_.Initialize(epoch.t_s, *start_m);
  return true;
}

StepOutput MintEstimator::Process(const core::Epoch& epoch) {
  const MintStepResult step = tracker_.Step(epoch.t_s, epoch.range_sets);
  StepOutput out;
  AgentEstimate agent;
  agent.position_m.head<2>() = step.position_m;
  agent.position_m.z() = world_.agent_height_m.value_or(0.0);
  agent.covariance_m2.topLeftCorner<2, 2>() = step.position_covariance;
  out.agents.push_back(agent);
  out.associations = static_cast<int>(step.associations.size());
  out.expected = step.visible_count;
  out.relocalized = step.relocalized;
  out.constrained = step.constrained;
  out.rejected_update = step.update.rejection == estimation::UpdateRejection::kNotPositiveDefinite;
  for (const auto& a : step.associations) {
    if (a.sinr) out.sinr_estimates.push_back({a.anchor_index, vas_[a.va_id].walls, *a.sinr});
  }
  return out;
}

}  // namespace mirage::methods::mint
