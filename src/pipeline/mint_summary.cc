// SPDX-License-Identifier: MIT
#include "mirage/pipeline/mint_summary.h"

#include <cmath>
#include <numeric>

namespace mirage::pipeline {
namespace {

SinrStats Stats(const std::vector<double>& values_db) {
  SinrStats s;
  s.count = values_db.size();
  if (values_db.empty()) return s;
  s.mean_db = std::accumulate(values_db.begin(), values_db.end(), 0.0) / static_cast<double>(values_db.size());
  s.p10_db = eval::Percentile(values_db, 10.0);
  s.p50_db = eval::Percentile(values_db, 50.0);
  s.p90_db = eval::Percentile(values_db, 90.0);
  return s;
}

GroupSummary Group(const std::string& name, const std::vector<const RunRecord*>& runs, bool has_truth, bool simulated) {
  GroupSummary g;
  g.name = name;
  g.has_truth = has_truth;
  g.runs = static_cast<int>(runs.size());
  std::vector<double> errors, pebs;
  for (const RunRecord* run : runs) {
    g.steps += static_cast<int>(run->steps.size());
    if (run->diverged) ++g.diverged_runs;
    g.relocalizations += run->relocalizations;
    g.constrained_steps += run->constrained_steps;
    g.rejected_updates += run->rejected_updates;
    for (const auto& s : run->steps) {
      if (s.error_m) errors.push_back(*s.error_m);
      if (s.peb_m) {
        pebs.push_back(*s.peb_m);
      } else {
        if (simulated) ++g.peb_singular_steps;  // recorded data have no PEB at all
      }
    }
  }
  g.error = eval::ComputeErrorStats(errors);
  std::vector<double> ospa;
  MapSummary map;
  double matched_error_sum_m = 0.0;
  int matched_pairs = 0;
  for (const RunRecord* run : runs) {
    if (!run->map_score) continue;
    const MapScore& m = *run->map_score;
    ospa.push_back(m.ospa_m);
    map.discovered_mean += m.discovered;
    map.estimated_mean += m.estimated;
    map.true_mean += m.true_vas;
    map.matched_mean += m.matched;
    map.false_mean += m.false_vas;
    map.filtered_mean += m.filtered;
    if (m.matched_mean_error_m) {
      matched_error_sum_m += *m.matched_mean_error_m * m.matched;
      matched_pairs += m.matched;
    }
  }
  if (!ospa.empty()) {
    const auto n = static_cast<double>(ospa.size());
    map.ospa_mean_m = std::accumulate(ospa.begin(), ospa.end(), 0.0) / n;
    map.ospa_p50_m = eval::Percentile(ospa, 50.0);
    map.discovered_mean /= n;
    map.estimated_mean /= n;
    map.true_mean /= n;
    map.matched_mean /= n;
    map.false_mean /= n;
    map.filtered_mean /= n;
    if (matched_pairs > 0) map.matched_error_mean_m = matched_error_sum_m / matched_pairs;
    g.map = map;
  }
  if (!pebs.empty()) {
    g.peb_mean_m = std::accumulate(pebs.begin(), pebs.end(), 0.0) / static_cast<double>(pebs.size());
    g.peb_p50_m = eval::Percentile(pebs, 50.0);
    g.peb_rms_m = std::sqrt(std::inner_product(pebs.begin(), pebs.end(), pebs.begin(), 0.0) / static_cast<double>(pebs.size()));
  }
  return g;
}

}  // namespace

std::string OrderName(int order) { return order == 0 ? "los" : "order" + std::to_string(order); }

MintSummary Summarize(const MintExperimentConfig& config, const MintExperimentResult& result) {
  MintSummary summary;
  std::vector<const RunRecord*> all;
  std::vector<std::vector<const RunRecord*>> by_trajectory(config.trajectories.size());
  std::map<std::string, std::vector<double>> true_db, estimated_db, error_db;
  for (const auto& run : result.runs) {
    all.push_back(&run);
    by_trajectory[static_cast<std::size_t>(run.trajectory)].push_back(&run);
    summary.simulate_s += run.simulate_s;
    summary.estimate_s += run.estimate_s;
    for (const auto& p : run.paths) {
      const std::string key = OrderName(p.order);
      true_db[key].push_back(p.true_sinr_db);
      if (p.estimated_sinr_db) {
        estimated_db[key].push_back(*p.estimated_sinr_db);
        error_db[key].push_back(*p.estimated_sinr_db - p.true_sinr_db);
      }
    }
  }
  summary.overall = Group("all", all, result.has_truth, result.simulated);
  for (std::size_t t = 0; t < config.trajectories.size(); ++t) {
    summary.trajectories.push_back(Group(config.trajectories[t].name, by_trajectory[t], result.has_truth, result.simulated));
  }
  for (const auto& [key, values] : true_db) summary.true_sinr[key] = Stats(values);
  for (const auto& [key, values] : estimated_db) summary.estimated_sinr[key] = Stats(values);
  for (const auto& [key, values] : error_db) summary.sinr_estimate_error[key] = Stats(values);
  summary.wall_s = result.wall_s;
  return summary;
}

}  // namespace mirage::pipeline
