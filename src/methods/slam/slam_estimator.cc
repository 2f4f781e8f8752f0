// SPDX-License-Identifier: MIT
#include "mirage/methods/slam/slam_estimator.h"

#include <algorithm>
#include <vector>

#include <fmt/format.h>

#include "mirage/estimation/init/position_fix.h"
#include "mirage/methods/mint/mint_estimator.h"

namespace mirage::methods::slam {
namespace {

std::vector<Vec2> PlanarAnchors(const World& world) {
  std::vector<Vec2> out;
  for (const auto& a : world.anchors) out.push_back(a.position_m.head<2>());
  return out;
}

// MINT's relocalization score over the plan's LOS and first-order VAs, with the recovery's match
// tolerance: the start search of a run without a start point.
mint::RelocalizationOptions StartSearch(const SlamOptions& options) {
  mint::RelocalizationOptions search;
  search.max_order = 1;
  search.match_tolerance_m = options.recovery.match_tolerance_m;
  return search;
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
      range_sigma_m_(options.range_sigma_m),
      search_(StartSearch(options)),
      start_(world.physical.speed_mps),
      search_vas_(geometry::VirtualAnchorSet::Generate(PlanarAnchors(world_), world_.floor_plan, 1)),
      known_vas_(geometry::VirtualAnchorSet::Generate(PlanarAnchors(world_), world_.floor_plan, options.prior_max_order)),
      tracker_(options, known_vas_, world_.floor_plan, mint::RangeSigmaAtUnitSinr(world_)) {}

void SlamEstimator::Initialize(const Prior& prior) { tracker_.Initialize(prior.t_s, prior.positions_m.front().head<2>()); }

bool SlamEstimator::InitializeFromEpoch(const core::Epoch& epoch) {
  std::vector<Vec3> anchors_m;
  std::vector<double> ranges_m;
  for (const auto& set : epoch.range_sets) {
    if (set.ranges.empty()) continue;
    // The earliest range is the line of sight when it is not blocked.
    const auto earliest = std::min_element(set.ranges.begin(), set.ranges.end(),
                                           [](const auto& a, const auto& b) { return a.range_m < b.range_m; });
    anchors_m.push_back(world_.anchors.at(static_cast<std::size_t>(set.anchor_index)).position_m);
    ranges_m.push_back(earliest->range_m);
  }
  const double height_m = world_.agent_height_m.value_or(0.0);
  if (const auto fix = estimation::FixPosition(anchors_m, ranges_m, height_m, range_sigma_m_);
      fix && fix->rms_m <= 3.0 * range_sigma_m_ && (world_.floor_plan.walls().empty() ||
                                                    world_.floor_plan.Encloses(fix->position_m.head<2>()))) {
    tracker_.Initialize(epoch.t_s, fix->position_m.head<2>());
    return true;
  }
  const auto start_m = start_.Add(epoch.t_s, mint::SearchFloorPlan(search_vas_, world_.floor_plan, epoch.range_sets, search_));
  if (!start_m) return false;
  tracker_.Initialize(epoch.t_s, *start_m);
  return true;
}

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
