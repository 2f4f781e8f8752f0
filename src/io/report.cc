// SPDX-License-Identifier: MIT
#include "mirage/io/report.h"

#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "mirage/io/output_file.h"
#include "mirage/pipeline/tracker_adapter.h"

namespace mirage::io {
namespace {

using nlohmann::json;

json ErrorJson(const eval::ErrorStats& e) {
  return {{"rmse", e.rmse}, {"mean", e.mean}, {"p50", e.p50}, {"p90", e.p90}, {"p95", e.p95}, {"max", e.max}};
}

json PebJson(const pipeline::GroupSummary& g) {
  if (!g.peb_mean_m) return nullptr;
  return {{"mean", *g.peb_mean_m}, {"p50", *g.peb_p50_m}, {"rms", *g.peb_rms_m}, {"singular_steps", g.peb_singular_steps}};
}

json GroupJson(const pipeline::GroupSummary& g) {
  json j = {{"name", g.name},
            {"runs", g.runs},
            {"steps", g.steps},
            // Recorded data without truth: no error block (null), as the divergence is unknown too.
            {"position_error_m", g.has_truth ? ErrorJson(g.error) : json(nullptr)},
            {"diverged_runs", g.has_truth ? json(g.diverged_runs) : json(nullptr)},
            {"peb_m", PebJson(g)}};
  j["rmse_over_mean_peb"] = g.peb_mean_m ? json(g.error.rmse / *g.peb_mean_m) : json(nullptr);
  j["rmse_over_rms_peb"] = g.peb_rms_m ? json(g.error.rmse / *g.peb_rms_m) : json(nullptr);
  if (g.map) {
    const auto& m = *g.map;
    j["map"] = {{"ospa_m", {{"mean", m.ospa_mean_m}, {"p50", m.ospa_p50_m}}},
                {"discovered_vas", m.discovered_mean},
                {"scored_vas", m.estimated_mean},
                {"true_vas", m.true_mean},
                {"matched_vas", m.matched_mean},
                {"false_vas", m.false_mean},
                {"filtered_vas", m.filtered_mean},
                {"matched_error_m", m.matched_error_mean_m ? json(*m.matched_error_mean_m) : json(nullptr)},
                {"note", "means over the runs; scored: map VAs (anchors excluded) not filtered and associated at "
                         "least once; true: VAs of order >= 1 visible at some step of the run; matched: OSPA "
                         "pairs closer than the cut-off, per anchor"}};
  }
  j["tracker_events"] = {{"relocalizations", g.relocalizations},
                         {"constrained_steps", g.constrained_steps},
                         {"rejected_updates", g.rejected_updates}};
  return j;
}

const char* MeasurementModelName(pipeline::MeasurementModel model) {
  switch (model) {
    case pipeline::MeasurementModel::kCir: return "cir";
    case pipeline::MeasurementModel::kRangeLevel: return "ranges";
    case pipeline::MeasurementModel::kRecorded: return "recorded";
  }
  return "?";
}

json SinrJson(const std::map<std::string, pipeline::SinrStats>& stats) {
  json j = json::object();
  for (const auto& [key, s] : stats) {
    j[key] = {{"count", s.count}, {"mean", s.mean_db}, {"p10", s.p10_db}, {"p50", s.p50_db}, {"p90", s.p90_db}};
  }
  return j;
}

}  // namespace

json MakeJsonReport(const Scenario& scenario, const pipeline::MintExperimentResult& result,
                    const pipeline::MintSummary& summary) {
  const auto& config = scenario.mint;
  const auto& overall = summary.overall;
  json j = GroupJson(overall);
  j.erase("name");
  j["scenario"] = config.name;
  j["scenario_file"] = scenario.file;
  j["method"] = scenario.method;
  j["seed"] = config.seed;
  j["runs_per_trajectory"] = config.runs;
  j["divergence_rule"] = eval::Describe(config.divergence);
  const double steps = std::max(1, overall.steps);
  j["timing"] = {{"wall_s", summary.wall_s},
                 {"steps_per_s", steps / summary.wall_s},
                 {"us_per_step", 1e6 * summary.wall_s / steps},
                 {"simulate_us_per_step", 1e6 * summary.simulate_s / steps},
                 {"estimate_us_per_step", 1e6 * summary.estimate_s / steps},
                 {"threads", config.threads}};
  j["sinr_db"] = {{"true", SinrJson(summary.true_sinr)},
                  {"estimated", SinrJson(summary.estimated_sinr)},
                  {"estimated_minus_true", SinrJson(summary.sinr_estimate_error)},
                  {"note", "true: every visible specular path at every step (Eq. 3.25 with the simulated DM and "
                           "noise); estimated: the tracker's online moment estimate (Eq. 3.26) when it made one; "
                           "an estimate of SINR 0 is counted as -40 dB"}};
  if (scenario.recording_files) {
    const auto& f = *scenario.recording_files;
    j["recorded_data"] = {{"anchors", f.anchors},
                          {"ranges", f.ranges},
                          {"truth", f.truth ? json(*f.truth) : json(nullptr)},
                          {"steps", config.recording->steps.size()}};
  }
  json trajectories = json::array();
  for (const auto& g : summary.trajectories) trajectories.push_back(GroupJson(g));
  j["trajectories"] = trajectories;
  j["config"] = {
      {"pulse_duration_s", config.channel.pulse.duration_s},
      {"rolloff", config.channel.pulse.rolloff},
      {"carrier_hz", config.channel.pulse.carrier_hz},
      {"sample_period_s", config.channel.sample_period_s},
      {"snr_at_1m_db", config.channel.snr_at_1m_db},
      {"diffuse_enabled", config.channel.diffuse.enabled},
      {"diffuse_power_ratio_db", config.channel.diffuse.power_ratio_db},
      {"channel_max_order", config.channel_max_order},
      {"max_components", config.mpc.max_components},
      {"measurement_model", MeasurementModelName(config.measurement_model)},
      {"cutoff_m", config.method == pipeline::Method::kSlam ? config.slam.cutoff_m : config.mint.cutoff_m},
      {"variance_estimation", config.method == pipeline::Method::kSlam ? config.slam.variance.enabled
                                                                      : config.mint.variance.enabled},
      {"tracker_max_order", pipeline::KnownVaOrder(config)},
      {"map_cutoff_m", config.map_cutoff_m},
      {"known_virtual_anchors", result.known_vas.size()},
  };
  return j;
}

std::string FormatResultTable(const Scenario& scenario, const pipeline::MintSummary& summary) {
  std::string out = fmt::format("mirage run: {} (method {}, seed {}, {} runs per trajectory)\n", scenario.mint.name,
                                scenario.method, scenario.mint.seed, scenario.mint.runs);
  out += fmt::format("{:<16} {:>5} {:>6} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>9} {:>9} {:>9}\n", "trajectory", "runs",
                     "steps", "rmse_m", "mean_m", "p50_m", "p90_m", "p95_m", "max_m", "diverged", "peb_m", "rmse/peb");
  const auto row = [&](const pipeline::GroupSummary& g) {
    if (!g.has_truth) {
      out += fmt::format("{:<16} {:>5} {:>6} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>9} {:>9} {:>9}\n", g.name, g.runs,
                         g.steps, "-", "-", "-", "-", "-", "-", "-", "-", "-");
      return;
    }
    const std::string peb = g.peb_mean_m ? fmt::format("{:.4f}", *g.peb_mean_m) : "-";
    const std::string ratio = g.peb_mean_m ? fmt::format("{:.1f}", g.error.rmse / *g.peb_mean_m) : "-";
    out += fmt::format("{:<16} {:>5} {:>6} {:>8.4f} {:>8.4f} {:>8.4f} {:>8.4f} {:>8.4f} {:>8.4f} {:>9} {:>9} {:>9}\n",
                       g.name, g.runs, g.steps, g.error.rmse, g.error.mean, g.error.p50, g.error.p90, g.error.p95,
                       g.error.max, g.diverged_runs, peb, ratio);
  };
  for (const auto& g : summary.trajectories) row(g);
  if (summary.trajectories.size() > 1) row(summary.overall);
  if (scenario.recording_files) {
    out += fmt::format("recorded data: {} ({} steps){}\n", scenario.recording_files->ranges,
                       scenario.mint.recording->steps.size(),
                       scenario.recording_files->truth ? "" : "; no truth file, so no position error");
  }
  if (summary.overall.map) {
    out += fmt::format("{:<16} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>12}\n", "map (mean/run)", "ospa_m", "found",
                       "scored", "true", "matched", "false", "matched_err_m");
    const auto map_row = [&](const pipeline::GroupSummary& g) {
      if (!g.map) return;
      const auto& m = *g.map;
      out += fmt::format("{:<16} {:>9.3f} {:>9.1f} {:>9.1f} {:>9.1f} {:>9.1f} {:>9.1f} {:>12}\n", g.name, m.ospa_mean_m,
                         m.discovered_mean, m.estimated_mean, m.true_mean, m.matched_mean, m.false_mean,
                         m.matched_error_mean_m ? fmt::format("{:.3f}", *m.matched_error_mean_m) : "-");
    };
    for (const auto& g : summary.trajectories) map_row(g);
    if (summary.trajectories.size() > 1) map_row(summary.overall);
  }
  out += "SINR (dB)        true p10/p50/p90        estimated p10/p50/p90   est-true p50\n";
  for (const auto& [key, t] : summary.true_sinr) {
    std::string est = "-", err = "-";
    if (const auto it = summary.estimated_sinr.find(key); it != summary.estimated_sinr.end()) {
      est = fmt::format("{:6.1f} {:6.1f} {:6.1f}", it->second.p10_db, it->second.p50_db, it->second.p90_db);
    }
    if (const auto it = summary.sinr_estimate_error.find(key); it != summary.sinr_estimate_error.end()) {
      err = fmt::format("{:6.1f}", it->second.p50_db);
    }
    out += fmt::format("{:<16} {:6.1f} {:6.1f} {:6.1f}    {:<22}  {}\n", key, t.p10_db, t.p50_db, t.p90_db, est, err);
  }
  const double steps = std::max(1, summary.overall.steps);
  out += fmt::format("timing: {:.2f} s wall, {:.0f} steps/s; per step {:.0f} us simulate + {:.0f} us estimate (CPU)\n",
                     summary.wall_s, steps / summary.wall_s, 1e6 * summary.simulate_s / steps,
                     1e6 * summary.estimate_s / steps);
  return out;
}

void WriteJson(const std::string& path, const nlohmann::json& json) {
  OutputFile out_file(path);
  auto& out = out_file.stream();
  out << json.dump(2) << "\n";
  out_file.Commit();
}

std::vector<std::string> WriteCsv(const std::string& dir, const Scenario& scenario,
                                  const pipeline::MintExperimentResult& result) {
  const auto& config = scenario.mint;
  std::vector<std::string> written;
  {
    OutputFile out_file(dir + "/tracks.csv");
    auto& out = out_file.stream();
    out << "trajectory,run,step,t_s,x_true_m,y_true_m,x_est_m,y_est_m,error_m,sigma_x_m,sigma_y_m,peb_m,associations,"
           "relocalized\n";
    for (const auto& run : result.runs) {
      const std::string& name = config.trajectories[static_cast<std::size_t>(run.trajectory)].name;
      for (std::size_t k = 0; k < run.steps.size(); ++k) {
        const auto& s = run.steps[k];
        const auto optional_number = [](const std::optional<double>& v) {
          return v ? fmt::format("{:.5f}", *v) : std::string();
        };
        out << fmt::format("{},{},{},{:.3f},{},{},{:.5f},{:.5f},{},{:.5f},{:.5f},{},{},{}\n", name, run.run, k, s.t_s,
                           optional_number(s.truth_m ? std::optional(s.truth_m->x()) : std::nullopt),
                           optional_number(s.truth_m ? std::optional(s.truth_m->y()) : std::nullopt),
                           s.estimate_m.x(), s.estimate_m.y(), optional_number(s.error_m),
                           std::sqrt(s.covariance_m2(0, 0)), std::sqrt(s.covariance_m2(1, 1)),
                           s.peb_m ? fmt::format("{:.5f}", *s.peb_m) : "", s.associations, s.relocalized ? 1 : 0);
      }
    }
    out_file.Commit();
    written.push_back(out_file.path());
  }
  {
    OutputFile out_file(dir + "/runs.csv");
    auto& out = out_file.stream();
    out << "trajectory,run,offset_x_m,offset_y_m,steps,rmse_m,p90_m,diverged\n";
    for (const auto& run : result.runs) {
      const auto errors = pipeline::StepErrors(run.steps);
      const auto e = eval::ComputeErrorStats(errors);
      const bool known = result.has_truth;
      out << fmt::format("{},{},{:.4f},{:.4f},{},{},{},{}\n",
                         config.trajectories[static_cast<std::size_t>(run.trajectory)].name, run.run, run.offset_m.x(),
                         run.offset_m.y(), run.steps.size(), known ? fmt::format("{:.5f}", e.rmse) : "",
                         known ? fmt::format("{:.5f}", e.p90) : "", known ? (run.diverged ? "1" : "0") : "");
    }
    out_file.Commit();
    written.push_back(out_file.path());
  }
  {
    // The per-path ground truth of the first run of each trajectory (all runs would be tens of
    // megabytes): delay, amplitude, true and estimated SINR of every visible specular path.
    OutputFile out_file(dir + "/paths.csv");
    auto& out = out_file.stream();
    out << "trajectory,run,step,anchor_id,va_id,order,delay_s,range_m,amplitude_re,amplitude_im,true_sinr_db,"
           "estimated_sinr_db\n";
    for (const auto& run : result.runs) {
      if (run.run != 0) continue;
      const std::string& name = config.trajectories[static_cast<std::size_t>(run.trajectory)].name;
      for (const auto& p : run.paths) {
        out << fmt::format("{},{},{},{},{},{},{:.6e},{:.5f},{:.6e},{:.6e},{:.2f},{}\n", name, run.run, p.step,
                           config.anchor_ids[static_cast<std::size_t>(p.anchor)], p.va_id, p.order, p.delay_s,
                           p.delay_s * config.channel.medium.speed_mps, p.amplitude.real(), p.amplitude.imag(),
                           p.true_sinr_db, p.estimated_sinr_db ? fmt::format("{:.2f}", *p.estimated_sinr_db) : "");
      }
    }
    out_file.Commit();
    written.push_back(out_file.path());
  }
  if (config.method == pipeline::Method::kSlam) {
    // The SLAM map at the end of every run, with the match to the true VAs.
    OutputFile out_file(dir + "/map.csv");
    auto& out = out_file.stream();
    out << "trajectory,run,va_id,anchor_id,origin,order,x_m,y_m,cov_xx_m2,cov_xy_m2,cov_yy_m2,sigma_range_m,"
           "associations,discovered_step,filtered\n";
    for (const auto& run : result.runs) {
      const std::string& name = config.trajectories[static_cast<std::size_t>(run.trajectory)].name;
      for (const auto& va : run.map) {
        const char* origin = va.origin == methods::slam::MapVaOrigin::kAnchor  ? "anchor"
                             : va.origin == methods::slam::MapVaOrigin::kPrior ? "prior"
                                                                                : "discovered";
        out << fmt::format("{},{},{},{},{},{},{:.5f},{:.5f},{:.6e},{:.6e},{:.6e},{},{},{},{}\n", name, run.run, va.id,
                           config.anchor_ids[static_cast<std::size_t>(va.anchor_index)], origin, va.order,
                           va.position_m.x(), va.position_m.y(), va.covariance_m2(0, 0), va.covariance_m2(0, 1),
                           va.covariance_m2(1, 1), va.sigma_m ? fmt::format("{:.5f}", *va.sigma_m) : "",
                           va.associations, va.discovered_step, va.filtered ? 1 : 0);
      }
    }
    out_file.Commit();
    written.push_back(out_file.path());
  }
  {
    OutputFile out_file(dir + "/virtual_anchors.csv");
    auto& out = out_file.stream();
    out << "va_id,anchor_id,order,x_m,y_m,walls,reflection_gain\n";
    for (const auto& va : result.known_vas.all()) {
      std::string walls;
      for (const int w : va.walls) {
        if (!walls.empty()) walls += ' ';
        walls += std::to_string(w);
      }
      out << fmt::format("{},{},{},{:.4f},{:.4f},{},{:.4f}\n", va.id,
                         config.anchor_ids[static_cast<std::size_t>(va.anchor_index)], va.order, va.position_m.x(),
                         va.position_m.y(), walls, va.reflection_gain);
    }
    out_file.Commit();
    written.push_back(out_file.path());
  }
  return written;
}

}  // namespace mirage::io
