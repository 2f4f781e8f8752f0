// SPDX-License-Identifier: MIT
#include "mirage/methods/slam/slam_estimator.h"

#include <vector>

#include <fmt/format.h>

#include "mirage/methods/mint/mint_estimator.h"

namespace mirage::methods::slam {
namespace {

std::vector<Vec2> PlanarAnchors(const World& world) {
  std::vector<Vec2> out;
  for (const auto& a : world.anchors) out.push_back(a.position_m.head<2>());
  return out;
}

const char* OriginName(MapVaOrigin origin) {
  switch (origin) {
    case MapVaOrigin::kAnchor: return "anchor";
    case MapVaOrigin::kPrior: return "prior";
    case MapVaOrigin::kDiscovered: break;
  }
  return "discovered";
}

}  // namespace

SlamEstimator::SlamEstimator(const SlamOptions& options, const World& world)
    : world_(world),
      known_vas_(geometry::VirtualAnchorSet::Generate(PlanarAnchors(world_), world_.floor_plan, options.prior_max_order)),
      tracker_(options, known_vas_, world_.floor_plan, mint::RangeSigmaAtUnitSinr(world_)) {}

void SlamEstimator::Initialize(const Prior& prior) { tracker_.Initialize(prior.t_s, prior.positions_m.front().head<2>()); }

StepOutput SlamEstimator::Process(const core::Epoch& epoch) {
  const SlamStepResult step = tracker_.Step(epoch.t_s, epoch.range_sets);
  StepOutput out;
  AgentEstimate agent;
  agent.position_m.head<2>() = step.position_m;
  agent.position_m.z() = world_.agent_height_m.value_or(0.0);
  agent.covariance_m2.topLeftCorner<2, 2>() = step.position_covariance;
  out.agents.push_back(agent);
  out.associations = static_cast<int>(step.associations.size());
  out.relocalized = step.relocalized;
  out.rejected_update = step.update.rejection == estimation::UpdateRejection::kNotPositiveDefinite;
  for (const auto& a : step.associations) {
    // Only VAs of the given floor plan have a known wall sequence to compare with the truth.
    if (a.sinr && a.va_id < kFirstDiscoveredVaId) out.sinr_estimates.push_back({a.anchor_index, known_vas_[a.va_id].walls, *a.sinr});
  }
  return out;
}

std::vector<MapFeature> SlamEstimator::Map() const {
  std::vector<MapFeature> out;
  for (const MapVa& va : tracker_.Map()) {
    MapFeature f;
    f.id = va.id;
    f.anchor_index = va.anchor_index;
    f.origin = OriginName(va.origin);
    f.position_m = va.position_m;
    f.covariance_m2 = va.covariance_m2;
    // The map proper: VAs the track used (associated at least once) and the VA filter keeps.
    f.scored = va.origin != MapVaOrigin::kAnchor && !va.filtered && va.associations > 0;
    f.attributes = {{"order", std::to_string(va.order)},
                    {"sigma_range_m", va.sigma_m ? fmt::format("{:.5f}", *va.sigma_m) : ""},
                    {"associations", std::to_string(va.associations)},
                    {"discovered_step", std::to_string(va.discovered_step)},
                    {"filtered", va.filtered ? "1" : "0"}};
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace mirage::methods::slam
