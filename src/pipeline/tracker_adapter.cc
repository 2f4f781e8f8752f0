// SPDX-License-Identifier: MIT
#include "mirage/pipeline/tracker_adapter.h"

namespace mirage::pipeline {

int KnownVaOrder(const MintExperimentConfig& config) {
  return config.method == Method::kSlam ? config.slam.prior_max_order : config.mint.max_order;
}

TrackerAdapter::TrackerAdapter(const MintExperimentConfig& config, const geometry::VirtualAnchorSet& known_vas,
                               double range_sigma_at_unit_sinr_m) {
  if (config.method == Method::kSlam) {
    slam_ = std::make_unique<methods::slam::SlamTracker>(config.slam, known_vas, config.known_plan,
                                                         range_sigma_at_unit_sinr_m);
  } else {
    mint_ = std::make_unique<methods::mint::MintTracker>(config.mint, known_vas, config.known_plan,
                                                         range_sigma_at_unit_sinr_m);
  }
}

TrackerAdapter::~TrackerAdapter() = default;

void TrackerAdapter::Initialize(double t_s, const Vec2& p0_m) {
  if (slam_) {
    slam_->Initialize(t_s, p0_m);
  } else {
    mint_->Initialize(t_s, p0_m);
  }
}

TrackerStep TrackerAdapter::Step(double t_s, std::span<const core::AnchorRanges> measurements) {
  TrackerStep out;
  if (slam_) {
    const auto step = slam_->Step(t_s, measurements);
    out.position_m = step.position_m;
    out.covariance_m2 = step.position_covariance;
    for (const auto& a : step.associations) {
      if (a.sinr) out.sinr_estimates.emplace_back(a.va_id, *a.sinr);
    }
    out.associations = static_cast<int>(step.associations.size());
    out.rejected_update = step.update.rejection == estimation::UpdateRejection::kNotPositiveDefinite;
    out.discovered = step.discovered;
    out.relocalized = step.relocalized;
    return out;
  }
  const auto step = mint_->Step(t_s, measurements);
  out.position_m = step.position_m;
  out.covariance_m2 = step.position_covariance;
  for (const auto& a : step.associations) {
    if (a.sinr) out.sinr_estimates.emplace_back(a.va_id, *a.sinr);
  }
  out.associations = static_cast<int>(step.associations.size());
  out.relocalized = step.relocalized;
  out.constrained = step.constrained;
  out.rejected_update = step.update.rejection == estimation::UpdateRejection::kNotPositiveDefinite;
  return out;
}

std::vector<methods::slam::MapVa> TrackerAdapter::Map() const {
  if (slam_) return slam_->Map();
  return {};
}

}  // namespace mirage::pipeline
