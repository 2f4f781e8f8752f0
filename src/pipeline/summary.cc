// SPDX-License-Identifier: MIT
#include "mirage/pipeline/summary.h"

#include <algorithm>
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

double Mean(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

std::optional<MapSummary> SummarizeMaps(std::span<const RunRecord* const> runs) {
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
    map.unscored_mean += m.filtered;
    if (m.matched_mean_error_m) {
      matched_error_sum_m += *m.matched_mean_error_m * m.matched;
      matched_pairs += m.matched;
    }
  }
  if (ospa.empty()) return std::nullopt;
  const auto n = static_cast<double>(ospa.size());
  map.ospa_mean_m = Mean(ospa);
  map.ospa_p50_m = eval::Percentile(ospa, 50.0);
  map.discovered_mean /= n;
  map.estimated_mean /= n;
  map.true_mean /= n;
  map.matched_mean /= n;
  map.false_mean /= n;
  map.unscored_mean /= n;
  if (matched_pairs > 0) map.matched_error_mean_m = matched_error_sum_m / matched_pairs;
  return map;
}

std::optional<DopStats> SummarizeDops(const std::vector<double>& dops) {
  if (dops.empty()) return std::nullopt;
  DopStats s;
  s.count = dops.size();
  s.p50 = eval::Percentile(dops, 50.0);
  s.max = *std::max_element(dops.begin(), dops.end());
  s.rms = std::sqrt(std::inner_product(dops.begin(), dops.end(), dops.begin(), 0.0) / static_cast<double>(dops.size()));
  return s;
}

}  // namespace

std::string OrderName(int order) { return order == 0 ? "los" : "order" + std::to_string(order); }

GroupSummary SummarizeRuns(const std::string& name, std::span<const RunRecord* const> runs) {
  GroupSummary g;
  g.name = name;
  g.runs = static_cast<int>(runs.size());
  std::vector<double> errors, bounds, finals, relative, bias_finals, tracked_errors, tracked_bounds;
  std::vector<double> height_errors, hdops, vdops;
  double associations = 0.0, expected = 0.0, wall_rms = 0.0;
  int failures_1m = 0, failures_2m = 0;
  int epochs = 0, wall_runs = 0;
  std::size_t longest = 0;
  for (const RunRecord* run : runs) {
    for (const auto& agent : run->agents) longest = std::max(longest, agent.steps.size());
  }
  std::vector<double> error_sum(longest, 0.0), bound_sum(longest, 0.0);
  std::vector<int> error_count(longest, 0), bound_count(longest, 0);
  for (const RunRecord* run : runs) {
    const bool diverged = run->diverged();
    if (diverged) ++g.diverged_runs;
    const RunHealth& h = run->health;
    g.health.drifted_runs += h.drifted ? 1 : 0;
    g.health.steps_without_association += h.steps_without_association;
    g.health.lost_track_episodes += h.lost_track_episodes;
    g.health.rejected_updates += h.rejected_updates;
    g.health.constrained_steps += h.constrained_steps;
    g.health.steps_outside_plan += h.steps_outside_plan;
    g.health.out_of_order_records += h.out_of_order_records;
    g.health.largest_covariance_growth = std::max(g.health.largest_covariance_growth, h.covariance_growth);
    for (const auto& agent : run->agents) {
      g.steps += static_cast<int>(agent.steps.size());
      for (std::size_t k = 0; k < agent.steps.size(); ++k) {
        const TrackStep& s = agent.steps[k];
        if (!s.truth_m) g.has_truth = false;
        if (!s.fixed) ++g.no_fix_steps;
        if (s.error_m) {
          failures_1m += (!s.fixed || *s.error_m > 1.0) ? 1 : 0;
          failures_2m += (!s.fixed || *s.error_m > 2.0) ? 1 : 0;
          errors.push_back(*s.error_m);
          error_sum[k] += *s.error_m;
          ++error_count[k];
          if (!diverged) tracked_errors.push_back(*s.error_m);
        }
        if (s.relative_error_m) relative.push_back(*s.relative_error_m);
        if (s.height_error_m) height_errors.push_back(*s.height_error_m);
        if (s.los_labels) {
          if (!g.los_labels) g.los_labels.emplace();
          *g.los_labels += *s.los_labels;
        }
        if (s.hdop) hdops.push_back(*s.hdop);
        if (s.vdop) vdops.push_back(*s.vdop);
        if (s.bound_m) {
          bounds.push_back(*s.bound_m);
          bound_sum[k] += *s.bound_m;
          ++bound_count[k];
          if (!diverged) tracked_bounds.push_back(*s.bound_m);
        } else if (s.truth_m && !run->paths.empty()) {
          ++g.bound_missing_steps;
        }
      }
      if (!agent.steps.empty() && agent.steps.back().error_m) finals.push_back(*agent.steps.back().error_m);
    }
    // Associations are per epoch (all agents together): count each epoch once.
    if (!run->agents.empty()) {
      for (const auto& s : run->agents.front().steps) {
        associations += s.associations;
        expected += s.expected;
        ++epochs;
      }
    }
    if (run->walls) {
      ++wall_runs;
      wall_rms += run->walls->rms_error_m;
      if (!run->walls->biased_wall_error_m.empty()) bias_finals.push_back(std::abs(run->walls->biased_wall_error_m.back()));
    }
  }
  g.error = eval::ComputeErrorStats(errors);
  if (!height_errors.empty()) g.height_error = eval::ComputeErrorStats(height_errors);
  g.hdop = SummarizeDops(hdops);
  g.vdop = SummarizeDops(vdops);
  if (!errors.empty()) {
    g.failure_rate_1m = static_cast<double>(failures_1m) / static_cast<double>(errors.size());
    g.failure_rate_2m = static_cast<double>(failures_2m) / static_cast<double>(errors.size());
  }
  if (!finals.empty()) {
    g.final_error_mean_m = Mean(finals);
    g.final_error_p90_m = eval::Percentile(finals, 90.0);
  }
  if (!bounds.empty()) {
    g.bound_mean_m = Mean(bounds);
    g.bound_p50_m = eval::Percentile(bounds, 50.0);
    g.bound_rms_m = std::sqrt(std::inner_product(bounds.begin(), bounds.end(), bounds.begin(), 0.0) /
                              static_cast<double>(bounds.size()));
  }
  if (!tracked_errors.empty() && !tracked_bounds.empty()) {
    const double rmse = eval::ComputeErrorStats(tracked_errors).rmse;
    const double rms = std::sqrt(std::inner_product(tracked_bounds.begin(), tracked_bounds.end(), tracked_bounds.begin(), 0.0) /
                                 static_cast<double>(tracked_bounds.size()));
    if (rms > 0.0) g.tracked_rmse_over_bound = rmse / rms;
  }
  if (epochs > 0) {
    g.associations_per_step = associations / epochs;
    g.expected_per_step = expected / epochs;
  }
  g.map = SummarizeMaps(runs);
  if (wall_runs > 0) {
    WallSummary w;
    if (!relative.empty()) w.relative_error_p90_m = eval::Percentile(relative, 90.0);
    if (!bias_finals.empty()) {
      w.biased_wall_final_mean_abs_m = Mean(bias_finals);
      w.biased_wall_final_p90_abs_m = eval::Percentile(bias_finals, 90.0);
    }
    w.rms_error_mean_m = wall_rms / wall_runs;
    g.walls = w;
  }
  for (std::size_t k = 0; k < longest; ++k) {
    g.error_by_step_m.push_back(error_count[k] > 0 ? error_sum[k] / error_count[k] : 0.0);
    g.bound_by_step_m.push_back(bound_count[k] > 0 ? bound_sum[k] / bound_count[k] : 0.0);
  }
  return g;
}

std::vector<VariantSummary> Summarize(std::span<const Variant> variants, const ExperimentResult& result) {
  std::vector<VariantSummary> out;
  for (std::size_t v = 0; v < variants.size(); ++v) {
    VariantSummary s;
    s.name = variants[v].name;
    const auto& groups = result.variants[v].groups;
    std::vector<const RunRecord*> all;
    std::vector<std::vector<const RunRecord*>> by_group(groups.size());
    std::map<std::string, std::vector<double>> true_db, estimated_db, error_db;
    for (const auto& run : result.runs) {
      if (run.variant != static_cast<int>(v)) continue;
      all.push_back(&run);
      by_group[static_cast<std::size_t>(run.group)].push_back(&run);
      s.simulate_s += run.simulate_s;
      s.estimate_s += run.estimate_s;
      for (const auto& p : run.paths) {
        const std::string key = OrderName(p.order);
        true_db[key].push_back(p.true_sinr_db);
        if (p.estimated_sinr_db) {
          estimated_db[key].push_back(*p.estimated_sinr_db);
          error_db[key].push_back(*p.estimated_sinr_db - p.true_sinr_db);
        }
      }
    }
    s.overall = SummarizeRuns("all", all);
    for (std::size_t g = 0; g < groups.size(); ++g) s.groups.push_back(SummarizeRuns(groups[g], by_group[g]));
    for (const auto& [key, values] : true_db) s.true_sinr[key] = Stats(values);
    for (const auto& [key, values] : estimated_db) s.estimated_sinr[key] = Stats(values);
    for (const auto& [key, values] : error_db) s.sinr_estimate_error[key] = Stats(values);
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace mirage::pipeline
