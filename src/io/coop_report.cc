// SPDX-License-Identifier: MIT
#include "mirage/io/coop_report.h"

#include <cmath>
#include <filesystem>
#include <sstream>

#include <fmt/format.h>

#include "mirage/eval/error_stats.h"
#include "mirage/io/input_error.h"
#include "mirage/io/output_file.h"

namespace mirage::io {

using nlohmann::json;

std::string FormatCoopTable(const pipeline::CoopExperimentConfig& config,
                            const std::vector<pipeline::CoopVariantSummary>& summary) {
  std::ostringstream out;
  out << fmt::format("{}: {} runs x {} steps per variant (errors per agent, cm)\n", config.name, config.runs,
                     config.steps);
  out << fmt::format("{:<38} {:>6} {:>6} {:>6} {:>7} {:>6} {:>5} {:>6} {:>7} {:>7} {:>7} {:>9}\n", "variant", "p50",
                     "p90", "rmse", "rel p90", "final", "div", "peb", "rmse/pb", "bias", "walls", "assoc/exp");
  for (const auto& s : summary) {
    out << fmt::format("{:<38} {:>6.2f} {:>6.2f} {:>6.2f} {:>7.2f} {:>6.2f} {:>5} {:>6.2f} {:>7.2f} {:>7} {:>7.2f} {:>4.1f}/{:<4.1f}\n",
                       s.name, 100 * s.error_p50_m, 100 * s.error_p90_m, 100 * s.error_rmse_m, 100 * s.relative_p90_m,
                       100 * s.final_mean_m, fmt::format("{}/{}", s.diverged, s.runs), 100 * s.peb_rms_m,
                       s.rmse_over_peb, s.has_bias ? fmt::format("{:.2f}", 100 * s.bias_final_mean_abs_m) : "-",
                       100 * s.wall_rms_mean_m, s.associated_per_step, s.expected_per_step);
  }
  out << "p50/p90/rmse: pooled over steps, agents and runs; rel: relative to the estimated floor plan; final: mean "
         "error at the last step; div: runs with an agent > 0.5 m off at the end; peb: posterior bound (RMS); bias: "
         "|biased wall offset error| at the end; walls: final RMS wall offset error\n";
  return out.str();
}

json MakeCoopJson(const std::string& scenario_file, const pipeline::CoopExperimentConfig& config,
                  const pipeline::CoopExperimentResult& result,
                  const std::vector<pipeline::CoopVariantSummary>& summary) {
  json variants = json::array();
  int total_runs = 0;
  for (const auto& s : summary) {
    total_runs += s.runs;
    json v = {{"name", s.name},
              {"agents", s.variant.agents},
              {"anchor", s.variant.anchor},
              {"pulse_duration_ns", s.variant.pulse_duration_s * 1e9},
              {"wall_error_mm", s.variant.wall_error_m * 1e3},
              {"biased_wall", s.variant.biased_wall},
              {"wall_update", s.variant.wall_update},
              {"wall_sigma_mm", s.variant.wall_sigma_m * 1e3},
              {"runs", s.runs},
              {"position_error_m",
               {{"p50", s.error_p50_m}, {"p90", s.error_p90_m}, {"rmse", s.error_rmse_m}, {"relative_p90", s.relative_p90_m},
                {"final_mean", s.final_mean_m}, {"final_p90", s.final_p90_m}}},
              {"diverged_runs", s.diverged},
              {"peb_rms_m", s.peb_rms_m},
              {"rmse_over_peb", s.rmse_over_peb},
              {"tracked_rmse_over_peb", s.tracked_rmse_over_peb},
              {"wall_rms_error_m", s.wall_rms_mean_m},
              {"associated_per_step", s.associated_per_step},
              {"expected_per_step", s.expected_per_step}};
    if (s.has_bias) {
      v["biased_wall_final_error_m"] = {{"mean_abs", s.bias_final_mean_abs_m}, {"p90_abs", s.bias_final_p90_abs_m}};
    } else {
      v["biased_wall_final_error_m"] = nullptr;
    }
    variants.push_back(std::move(v));
  }
  return {{"scenario", scenario_file},
          {"name", config.name},
          {"method", "coop"},
          {"seed", config.seed},
          {"runs", config.runs},
          {"steps", config.steps},
          {"variants", variants},
          {"timing",
           {{"wall_s", result.wall_s},
            {"runs", total_runs},
            {"runs_per_s", result.wall_s > 0.0 ? total_runs / result.wall_s : 0.0},
            {"steps_per_s", result.wall_s > 0.0 ? total_runs * static_cast<double>(config.steps) / result.wall_s : 0.0}}}};
}

std::vector<std::string> WriteCoopCsv(const std::string& dir, const pipeline::CoopExperimentConfig& config,
                                      const pipeline::CoopExperimentResult& result,
                                      const std::vector<pipeline::CoopVariantSummary>& summary) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(dir + ": cannot create the CSV directory: " + ec.message());
  std::vector<std::string> written;
  {
    OutputFile out_file(dir + "/variants.csv");
    auto& out = out_file.stream();
    out << "variant,agents,anchor,pulse_duration_ns,wall_error_mm,biased_wall,wall_update,wall_sigma_mm,runs,"
           "error_p50_m,error_p90_m,error_rmse_m,relative_p90_m,final_mean_m,final_p90_m,diverged_runs,peb_rms_m,"
           "rmse_over_peb,biased_wall_final_mean_abs_m,wall_rms_error_m,associated_per_step,expected_per_step\n";
    for (const auto& s : summary) {
      out << fmt::format("{},{},{},{:g},{:g},{},{},{:g},{},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{},{:.6f},{:.4f},{},{:.6f},{:.3f},{:.3f}\n",
                         s.name, s.variant.agents, s.variant.anchor ? 1 : 0, s.variant.pulse_duration_s * 1e9,
                         s.variant.wall_error_m * 1e3, s.variant.biased_wall ? 1 : 0, s.variant.wall_update ? 1 : 0,
                         s.variant.wall_sigma_m * 1e3, s.runs, s.error_p50_m, s.error_p90_m, s.error_rmse_m,
                         s.relative_p90_m, s.final_mean_m, s.final_p90_m, s.diverged, s.peb_rms_m, s.rmse_over_peb,
                         s.has_bias ? fmt::format("{:.6f}", s.bias_final_mean_abs_m) : "", s.wall_rms_mean_m,
                         s.associated_per_step, s.expected_per_step);
    }
    out_file.Commit();
    written.push_back(out_file.path());
  }
  {
    OutputFile out_file(dir + "/error_by_step.csv");
    auto& out = out_file.stream();
    out << "variant,step,mean_error_m,peb_m\n";
    for (const auto& s : summary) {
      for (std::size_t n = 0; n < s.error_by_step_m.size(); ++n) {
        out << fmt::format("{},{},{:.6f},{:.6f}\n", s.name, n, s.error_by_step_m[n],
                           n < s.peb_by_step_m.size() ? s.peb_by_step_m[n] : 0.0);
      }
    }
    out_file.Commit();
    written.push_back(out_file.path());
  }
  // Per step of every run: one row per agent, for the steps with an update (1..N, at t = n s).
  // The columns of the MINT report's tracks.csv, led by the variant's index in the grid.
  {
    OutputFile out_file(dir + "/tracks.csv");
    auto& out = out_file.stream();
    out << "variant,trajectory,run,step,t_s,x_true_m,y_true_m,x_est_m,y_est_m,error_m,sigma_x_m,sigma_y_m,peb_m,"
           "associations,relocalized\n";
    for (std::size_t v = 0; v < result.variants.size(); ++v) {
      const auto& variant = result.variants[v];
      for (std::size_t r = 0; r < variant.runs.size(); ++r) {
        const auto& run = variant.runs[r];
        for (std::size_t a = 0; a < static_cast<std::size_t>(variant.variant.agents); ++a) {
          for (std::size_t n = 1; n < run.estimate_m.size(); ++n) {
            const Vec2& truth = result.truth_m[a][n];
            const Vec2& estimate = run.estimate_m[n][a];
            const Eigen::Matrix2d& covariance = run.covariance_m2[n][a];
            out << fmt::format("{},{},{},{},{:.3f},{:.5f},{:.5f},{:.5f},{:.5f},{:.5f},{:.5f},{:.5f},{:.5f},{},0\n", v,
                               config.agents[a].name, r, n - 1, static_cast<double>(n), truth.x(), truth.y(),
                               estimate.x(), estimate.y(), run.error_m[n][a], std::sqrt(covariance(0, 0)),
                               std::sqrt(covariance(1, 1)), variant.peb_m[n][a], run.associated[n]);
          }
        }
      }
    }
    out_file.Commit();
    written.push_back(out_file.path());
  }
  {
    OutputFile out_file(dir + "/runs.csv");
    auto& out = out_file.stream();
    out << "variant,trajectory,run,offset_x_m,offset_y_m,steps,rmse_m,p90_m,diverged\n";
    const eval::DivergenceRule rule;
    for (std::size_t v = 0; v < result.variants.size(); ++v) {
      const auto& variant = result.variants[v];
      for (std::size_t r = 0; r < variant.runs.size(); ++r) {
        const auto& run = variant.runs[r];
        for (std::size_t a = 0; a < static_cast<std::size_t>(variant.variant.agents); ++a) {
          std::vector<double> errors;
          for (std::size_t n = 1; n < run.error_m.size(); ++n) errors.push_back(run.error_m[n][a]);
          const auto e = eval::ComputeErrorStats(errors);
          out << fmt::format("{},{},{},{:.4f},{:.4f},{},{:.5f},{:.5f},{}\n", v, config.agents[a].name, r, 0.0, 0.0,
                             errors.size(), e.rmse, e.p90, eval::IsDiverged(errors, rule) ? 1 : 0);
        }
      }
    }
    out_file.Commit();
    written.push_back(out_file.path());
  }
  return written;
}

json CoopPlotData(const pipeline::CoopExperimentConfig& config, const pipeline::CoopExperimentResult& result,
                  const std::vector<pipeline::CoopVariantSummary>& summary) {
  json walls = json::array();
  for (std::size_t s = 0; s < config.true_plan.walls().size(); ++s) {
    const auto& w = config.true_plan.walls()[s];
    walls.push_back({w.start_m.x(), w.start_m.y(), w.end_m.x(), w.end_m.y(), w.label, static_cast<bool>(config.in_plan[s])});
  }
  json obstacles = json::array();
  for (const auto& o : config.true_plan.obstacles()) obstacles.push_back({o.center_m.x(), o.center_m.y(), o.radius_m});
  json truth = json::array();
  for (const auto& agent : result.truth_m) {
    json track = json::array();
    for (const auto& p : agent) track.push_back({p.x(), p.y()});
    truth.push_back(track);
  }
  // The first run of the variant with the most agents (the first such in the grid).
  json estimate = json::array();
  std::string shown;
  std::size_t best = 0;
  for (std::size_t v = 0; v < result.variants.size(); ++v) {
    if (result.variants[v].variant.agents > result.variants[best].variant.agents) best = v;
  }
  if (!result.variants.empty() && !result.variants[best].runs.empty()) {
    const auto& run = result.variants[best].runs.front();
    shown = result.variants[best].variant.Name();
    for (int m = 0; m < result.variants[best].variant.agents; ++m) {
      json track = json::array();
      for (const auto& step : run.estimate_m) track.push_back({step[static_cast<std::size_t>(m)].x(), step[static_cast<std::size_t>(m)].y()});
      estimate.push_back(track);
    }
  }
  json variants = json::array();
  for (const auto& s : summary) {
    variants.push_back({{"name", s.name},
                        {"p50", s.error_p50_m},
                        {"p90", s.error_p90_m},
                        {"rmse", s.error_rmse_m},
                        {"peb", s.peb_rms_m},
                        {"diverged", s.diverged},
                        {"runs", s.runs},
                        {"error_by_step", s.error_by_step_m},
                        {"peb_by_step", s.peb_by_step_m}});
  }
  json anchor = nullptr;
  if (config.anchor) anchor = {config.anchor->position_m.x(), config.anchor->position_m.y(), config.anchor->id};
  return {{"title", config.name},   {"walls", walls},       {"obstacles", obstacles}, {"anchor", anchor},
          {"truth", truth},         {"estimate", estimate}, {"estimate_variant", shown},
          {"variants", variants}};
}

}  // namespace mirage::io
