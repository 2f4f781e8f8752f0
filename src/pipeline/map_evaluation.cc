// SPDX-License-Identifier: MIT
#include "mirage/pipeline/map_evaluation.h"

#include "mirage/eval/ospa.h"

namespace mirage::pipeline {

MapScore EvaluateMap(std::span<const methods::MapFeature> map, const geometry::VirtualAnchorSet& channel_vas,
                     const std::set<int>& visible_channel_ids, double cutoff_m) {
  // VAs of different anchors must never be paired. Shifting each anchor's VAs far apart along x
  // makes every cross-anchor distance exceed the cut-off, so one OSPA over the union equals the
  // OSPA with cross-anchor pairs forbidden (they cost c either way).
  constexpr double kAnchorSeparation_m = 1e6;
  const auto lift = [&](const Vec2& p, int anchor) { return Vec2(p + Vec2(kAnchorSeparation_m * anchor, 0.0)); };
  MapScore score;
  std::vector<Vec2> estimated, truth;
  std::vector<Vec2> estimated_m, truth_m;
  for (const auto& va : map) {
    if (va.origin == "discovered") ++score.discovered;
    if (va.origin == "anchor") continue;
    if (!va.scored) {
      ++score.filtered;
      continue;
    }
    estimated.push_back(lift(va.position_m, va.anchor_index));
    estimated_m.push_back(va.position_m);
  }
  for (const int id : visible_channel_ids) {
    const auto& va = channel_vas[id];
    if (va.order == 0) continue;
    truth.push_back(lift(va.position_m, va.anchor_index));
    truth_m.push_back(va.position_m);
  }
  score.estimated = static_cast<int>(estimated.size());
  score.true_vas = static_cast<int>(truth.size());
  const eval::OspaResult ospa = eval::Ospa(estimated, truth, cutoff_m, 1.0);
  score.ospa_m = ospa.distance_m;
  score.ospa_localization_m = ospa.localization_m;
  score.ospa_cardinality_m = ospa.cardinality_m;
  double sum_m = 0.0;
  for (std::size_t i = 0; i < ospa.assignment.size(); ++i) {
    const int j = ospa.assignment[i];
    if (j < 0) continue;
    ++score.matched;
    sum_m += (estimated_m[i] - truth_m[static_cast<std::size_t>(j)]).norm();
  }
  score.false_vas = score.estimated - score.matched;
  if (score.matched > 0) score.matched_mean_error_m = sum_m / score.matched;
  return score;
}

}  // namespace mirage::pipeline
