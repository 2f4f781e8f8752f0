// SPDX-License-Identifier: MIT
#include "mirage/io/report.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "mirage/core/constants.h"
#include "mirage/io/output_file.h"

namespace mirage::io {
namespace {

// The recording's measurement file (ranges.csv, toa.csv or tdoa.csv) and its scenario key.
std::string MeasurementFileKey(const RecordingFiles& f) { return f.pairwise_tdoa() ? "tdoa" : f.toa_stamps() ? "toa" : "ranges"; }
std::string MeasurementFile(const RecordingFiles& f) { return f.pairwise_tdoa() ? f.tdoa : f.toa_stamps() ? f.toa : f.ranges; }

using nlohmann::json;
using pipeline::GroupSummary;

json ErrorJson(const eval::ErrorStats& e) {
  return {{"rmse", e.rmse}, {"mean", e.mean}, {"p50", e.p50}, {"p90", e.p90}, {"p95", e.p95}, {"max", e.max}};
}

json HealthJson(const pipeline::HealthSummary& h) {
  return {{"drifted_runs", h.drifted_runs},
          {"steps_without_association", h.steps_without_association},
          {"lost_track_episodes", h.lost_track_episodes},
          {"rejected_updates", h.rejected_updates},
          {"constrained_steps", h.constrained_steps},
          {"steps_outside_plan", h.steps_outside_plan},
          {"out_of_order_records", h.out_of_order_records},
          {"largest_covariance_growth", h.largest_covariance_growth}};
}

// The keys every group, variant and the top level carry.
json GroupJson(const GroupSummary& g, const std::string& bound) {
  json j;
  j["runs"] = g.runs;
  j["steps"] = g.steps;
  // Recorded data without truth: no error block (null), as the divergence is unknown too.
  j["position_error_m"] = g.has_truth ? ErrorJson(g.error) : json(nullptr);
  j["diverged_runs"] = g.has_truth ? json(g.diverged_runs) : json(nullptr);
  j["failure_rate_1m"] = g.has_truth ? json(g.failure_rate_1m) : json(nullptr);
  j["failure_rate_2m"] = g.has_truth ? json(g.failure_rate_2m) : json(nullptr);
  j["no_fix_steps"] = g.no_fix_steps;
  // 3-D methods: the height error; methods that compute DOPs: their distribution (a DOP may be
  // infinite: JSON null).
  if (g.height_error) j["height_error_m"] = ErrorJson(*g.height_error);
  const auto dop_json = [](const pipeline::DopStats& d) {
    const auto finite = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
    return json{{"count", d.count}, {"p50", finite(d.p50)}, {"max", finite(d.max)}, {"rms", finite(d.rms)}};
  };
  if (g.hdop) j["hdop"] = dop_json(*g.hdop);
  if (g.vdop) j["vdop"] = dop_json(*g.vdop);
  if (g.los_labels) {
    const auto& l = *g.los_labels;
    const auto optional = [](std::optional<double> v) { return v ? json(*v) : json(nullptr); };
    j["los_labels"] = {{"precision", optional(l.Precision())},
                       {"recall", optional(l.Recall())},
                       {"true_positives", l.true_positives},
                       {"false_positives", l.false_positives},
                       {"false_negatives", l.false_negatives}};
  }
  j["final_error_m"] = g.has_truth ? json{{"mean", g.final_error_mean_m}, {"p90", g.final_error_p90_m}} : json(nullptr);
  if (g.bound_mean_m) {
    j["peb_m"] = {{"mean", *g.bound_mean_m}, {"p50", *g.bound_p50_m}, {"rms", *g.bound_rms_m}, {"kind", bound},
                  {"missing_steps", g.bound_missing_steps}};
    j["rmse_over_rms_peb"] = g.has_truth ? json(g.error.rmse / *g.bound_rms_m) : json(nullptr);
    j["tracked_rmse_over_rms_peb"] = g.tracked_rmse_over_bound ? json(*g.tracked_rmse_over_bound) : json(nullptr);
  } else {
    j["peb_m"] = nullptr;
  }
  j["associations_per_step"] = g.associations_per_step;
  j["expected_per_step"] = g.expected_per_step;
  j["health"] = HealthJson(g.health);
  return j;
}

json SinrJson(const std::map<std::string, pipeline::SinrStats>& stats) {
  json j = json::object();
  for (const auto& [key, s] : stats) {
    j[key] = {{"count", s.count}, {"mean", s.mean_db}, {"p10", s.p10_db}, {"p50", s.p50_db}, {"p90", s.p90_db}};
  }
  return j;
}

// The method's block: its effective options and what it estimated beyond positions.
json MethodJson(const pipeline::Variant& variant, const pipeline::VariantSummary& s) {
  json j;
  j["options"] = json::parse(variant.experiment.method.options_json);
  const GroupSummary& g = s.overall;
  if (g.map) {
    const auto& m = *g.map;
    j["map"] = {{"ospa_m", {{"mean", m.ospa_mean_m}, {"p50", m.ospa_p50_m}}},
                {"discovered_vas", m.discovered_mean},
                {"scored_vas", m.estimated_mean},
                {"true_vas", m.true_mean},
                {"matched_vas", m.matched_mean},
                {"false_vas", m.false_mean},
                {"unscored_vas", m.unscored_mean},
                {"matched_error_m", m.matched_error_mean_m ? json(*m.matched_error_mean_m) : json(nullptr)},
                {"note", "means over the runs; scored: map features (anchors excluded) the method counts as its map; "
                         "true: VAs of order >= 1 visible at some step of the run; matched: OSPA pairs closer than "
                         "the cut-off, per anchor"}};
  }
  if (g.walls) {
    const auto& w = *g.walls;
    j["floor_plan"] = {{"relative_error_p90_m", w.relative_error_p90_m},
                       {"biased_wall_final_mean_abs_m", w.biased_wall_final_mean_abs_m ? json(*w.biased_wall_final_mean_abs_m) : json(nullptr)},
                       {"biased_wall_final_p90_abs_m", w.biased_wall_final_p90_abs_m ? json(*w.biased_wall_final_p90_abs_m) : json(nullptr)},
                       {"wall_rms_error_mean_m", w.rms_error_mean_m},
                       {"note", "errors in the estimated plan's frame: the translation the walls' offsets explain "
                                "removed (Kulmer Sec. IV-E)"}};
  }
  if (!s.estimated_sinr.empty()) {
    j["sinr_db"] = {{"true", SinrJson(s.true_sinr)},
                    {"estimated", SinrJson(s.estimated_sinr)},
                    {"estimated_minus_true", SinrJson(s.sinr_estimate_error)},
                    {"note", "true: every visible specular path at every step (Lafer Eq. 3.25 with the simulated DM "
                             "and noise); estimated: the method's online estimate when it made one (SINR 0 counted "
                             "as -40 dB)"}};
  }
  return j;
}

json RunHealthJson(const pipeline::Variant& variant, const pipeline::ExperimentResult& result, const pipeline::RunRecord& run,
                   bool grid) {
  const auto& h = run.health;
  json j = {{"trajectory", result.variants[static_cast<std::size_t>(run.variant)].groups[static_cast<std::size_t>(run.group)]},
            {"run", run.run},
            {"steps", h.steps},
            {"steps_without_association", h.steps_without_association},
            {"lost_track_episodes", h.lost_track_episodes},
            {"rejected_updates", h.rejected_updates},
            {"constrained_steps", h.constrained_steps},
            {"covariance_growth", h.covariance_growth},
            {"steps_outside_plan", h.steps_outside_plan},
            {"out_of_order_records", h.out_of_order_records},
            {"started", h.started},
            {"epochs_before_start", h.epochs_before_start},
            {"drifted", h.drifted},
            {"drift_reason", h.drift_reason}};
  if (grid) j["variant"] = variant.name;
  json alignment = json::array();
  for (const auto& agent : run.agents) {
    if (!agent.alignment) continue;
    const Vec3 t = agent.alignment->TranslationM();
    alignment.push_back({{"agent", agent.name},
                         {"rotation_deg", agent.alignment->AngleRad() * 180.0 / std::numbers::pi},
                         {"translation_m", {t.x(), t.y(), t.z()}}});
  }
  if (!alignment.empty()) j["alignment"] = alignment;
  return j;
}

std::vector<const pipeline::RunRecord*> AllRuns(const pipeline::ExperimentResult& result) {
  std::vector<const pipeline::RunRecord*> runs;
  for (const auto& run : result.runs) runs.push_back(&run);
  return runs;
}

std::string OptionalNumber(const std::optional<double>& v) { return v ? fmt::format("{:.5f}", *v) : std::string(); }

}  // namespace

json MakeJsonReport(const Scenario& scenario, const pipeline::ExperimentResult& result,
                    const std::vector<pipeline::VariantSummary>& summaries) {
  const pipeline::Experiment& base = scenario.variants.front().experiment;
  const bool grid = scenario.has_grid();
  // The top level: the one variant, or over a grid all runs of all variants together.
  const auto runs = AllRuns(result);
  const GroupSummary overall = grid ? pipeline::SummarizeRuns("all", runs) : summaries.front().overall;
  json j = GroupJson(overall, result.variants.front().bound);
  j["scenario"] = base.name;
  j["scenario_file"] = scenario.file;
  j["method"] = scenario.method->name;
  j["seed"] = base.seed;
  j["runs_per_trajectory"] = base.runs;
  j["divergence_rule"] = eval::Describe(base.divergence);
  double simulate_s = 0.0, estimate_s = 0.0;
  for (const auto& s : summaries) {
    simulate_s += s.simulate_s;
    estimate_s += s.estimate_s;
  }
  const double steps = std::max(1, overall.steps);
  j["timing"] = {{"wall_s", result.wall_s},
                 {"steps_per_s", steps / result.wall_s},
                 {"us_per_step", 1e6 * result.wall_s / steps},
                 {"simulate_us_per_step", 1e6 * simulate_s / steps},
                 {"estimate_us_per_step", 1e6 * estimate_s / steps},
                 {"threads", base.threads},
                 {"note", "wall time over all steps of all runs; simulate and estimate are CPU times (simulate "
                          "includes the extraction of range sets from simulated CIRs)"}};
  json health_runs = json::array();
  for (const auto& run : result.runs) {
    health_runs.push_back(RunHealthJson(scenario.variants[static_cast<std::size_t>(run.variant)], result, run, grid));
  }
  j["health"]["runs"] = health_runs;
  json groups = json::array();
  for (const auto& g : summaries.front().groups) {
    json gj = GroupJson(g, result.variants.front().bound);
    gj["name"] = g.name;
    groups.push_back(gj);
  }
  j["groups"] = groups;
  j[scenario.method->name] = MethodJson(scenario.variants.front(), summaries.front());
  if (grid) {
    json variants = json::array();
    for (std::size_t v = 0; v < summaries.size(); ++v) {
      json vj = GroupJson(summaries[v].overall, result.variants[v].bound);
      vj["name"] = summaries[v].name;
      json overrides = json::object();
      for (const auto& [key, value] : scenario.variants[v].overrides) overrides[key] = value;
      vj["overrides"] = overrides;
      vj[scenario.method->name] = MethodJson(scenario.variants[v], summaries[v]);
      variants.push_back(vj);
    }
    j["variants"] = variants;
  }
  if (scenario.recording_files) {
    const auto& f = *scenario.recording_files;
    j["recorded_data"] = {{f.toa_stamps() ? "mics" : "anchors", f.toa_stamps() ? f.mics : f.anchors},
                          {MeasurementFileKey(f), MeasurementFile(f)},
                          {"truth", f.truth ? json(*f.truth) : json(nullptr)},
                          {"alignment", base.align_rigid ? "rigid (Bordoy 2020 Eq. 3.49-3.52; per run in health.runs)" : "none"},
                          {"epochs", base.recording->steps.size()}};
  }
  return j;
}

std::string FormatResultTable(const Scenario& scenario, const pipeline::ExperimentResult& result,
                              const std::vector<pipeline::VariantSummary>& summaries) {
  const pipeline::Experiment& base = scenario.variants.front().experiment;
  const bool grid = scenario.has_grid();
  std::string out = fmt::format("mirage run: {} (method {}, seed {}, {} runs per {})\n", base.name, scenario.method->name,
                                base.seed, base.runs, base.method.joint ? "variant" : "trajectory");
  const std::string bound = result.variants.front().bound.empty() ? "bound" : result.variants.front().bound;
  out += fmt::format("{:<28} {:>5} {:>7} {:>8} {:>8} {:>8} {:>8} {:>9} {:>9} {:>10}\n", grid ? "variant" : "trajectory",
                     "runs", "steps", "rmse_m", "p50_m", "p90_m", "max_m", "diverged", "peb_m", "rmse/peb");
  const auto row = [&](const std::string& name, const GroupSummary& g) {
    const std::string label = name.size() > 28 ? name.substr(0, 25) + "..." : name;
    if (!g.has_truth || g.steps == 0) {  // no truth, or no run started: no errors to show
      const std::string diverged = g.has_truth ? std::to_string(g.diverged_runs) : "-";
      out += fmt::format("{:<28} {:>5} {:>7} {:>8} {:>8} {:>8} {:>8} {:>9} {:>9} {:>10}\n", label, g.runs, g.steps, "-",
                         "-", "-", "-", diverged, "-", "-");
      return;
    }
    const std::string peb = g.bound_rms_m ? fmt::format("{:.4f}", *g.bound_rms_m) : "-";
    const std::string ratio = g.bound_rms_m ? fmt::format("{:.2f}", g.error.rmse / *g.bound_rms_m) : "-";
    out += fmt::format("{:<28} {:>5} {:>7} {:>8.4f} {:>8.4f} {:>8.4f} {:>8.4f} {:>9} {:>9} {:>10}\n", label, g.runs,
                       g.steps, g.error.rmse, g.error.p50, g.error.p90, g.error.max, g.diverged_runs, peb, ratio);
  };
  if (grid) {
    for (const auto& s : summaries) row(s.name, s.overall);
  } else {
    for (const auto& g : summaries.front().groups) row(g.name, g);
    if (summaries.front().groups.size() > 1) row("all", summaries.front().overall);
  }
  if (!result.variants.front().bound.empty()) out += fmt::format("(peb_m: the RMS of the {} position bound)\n", bound);
  if (scenario.recording_files) {
    const auto& f = *scenario.recording_files;
    out += fmt::format("recorded data: {} ({} epochs){}\n", MeasurementFile(f), base.recording->steps.size(),
                       !scenario.recording_files->truth ? "; no truth file, so no position error"
                       : base.align_rigid                ? "; estimates rigidly aligned to the truth's frame"
                                                         : "");
  }
  const auto& front = summaries.front();
  if (front.overall.map && !grid) {
    out += fmt::format("{:<16} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>12}\n", "map (mean/run)", "ospa_m", "found", "scored",
                       "true", "matched", "false", "matched_err_m");
    const auto map_row = [&](const GroupSummary& g) {
      if (!g.map) return;
      const auto& m = *g.map;
      out += fmt::format("{:<16} {:>9.3f} {:>9.1f} {:>9.1f} {:>9.1f} {:>9.1f} {:>9.1f} {:>12}\n", g.name, m.ospa_mean_m,
                         m.discovered_mean, m.estimated_mean, m.true_mean, m.matched_mean, m.false_mean,
                         m.matched_error_mean_m ? fmt::format("{:.3f}", *m.matched_error_mean_m) : "-");
    };
    for (const auto& g : front.groups) map_row(g);
    if (front.groups.size() > 1) map_row(front.overall);
  }
  if (!grid && !front.true_sinr.empty()) {
    out += "SINR (dB)        true p10/p50/p90        estimated p10/p50/p90   est-true p50\n";
    for (const auto& [key, t] : front.true_sinr) {
      std::string est = "-", err = "-";
      if (const auto it = front.estimated_sinr.find(key); it != front.estimated_sinr.end()) {
        est = fmt::format("{:6.1f} {:6.1f} {:6.1f}", it->second.p10_db, it->second.p50_db, it->second.p90_db);
      }
      if (const auto it = front.sinr_estimate_error.find(key); it != front.sinr_estimate_error.end()) {
        err = fmt::format("{:6.1f}", it->second.p50_db);
      }
      out += fmt::format("{:<16} {:6.1f} {:6.1f} {:6.1f}    {:<22}  {}\n", key, t.p10_db, t.p50_db, t.p90_db, est, err);
    }
  }
  // The runs that drifted away, said on the console (up to 5; the JSON lists every run's health).
  int drifted = 0;
  for (const auto& run : result.runs) {
    if (!run.health.drifted) continue;
    if (++drifted <= 5) {
      const auto& groups = result.variants[static_cast<std::size_t>(run.variant)].groups;
      out += fmt::format("warning: {}{} run {} {}{}\n", grid ? scenario.variants[static_cast<std::size_t>(run.variant)].name + ", " : "",
                         groups[static_cast<std::size_t>(run.group)], run.run,
                         run.health.started ? "drifted away: " : "", run.health.drift_reason);
    }
  }
  if (drifted > 5) {
    out += fmt::format("warning: {} runs drifted away or never started in all (the JSON report's health block lists them)\n",
                       drifted);
  }
  double simulate_s = 0.0, estimate_s = 0.0;
  int steps = 0;
  for (const auto& s : summaries) {
    simulate_s += s.simulate_s;
    estimate_s += s.estimate_s;
    steps += s.overall.steps;
  }
  out += fmt::format("timing: {:.2f} s wall, {:.0f} steps/s; per step {:.0f} us simulate + {:.0f} us estimate (CPU)\n",
                     result.wall_s, std::max(steps, 1) / result.wall_s, 1e6 * simulate_s / std::max(steps, 1),
                     1e6 * estimate_s / std::max(steps, 1));
  return out;
}

void WriteJson(const std::string& path, const json& json) {
  OutputFile file(path);
  file.stream() << json.dump(2) << "\n";
  file.Commit();
}

std::vector<std::string> WriteCsv(const std::string& dir, const Scenario& scenario, const pipeline::ExperimentResult& result,
                                  const std::vector<pipeline::VariantSummary>& summaries) {
  std::vector<std::string> written;
  const bool grid = scenario.has_grid();
  const std::string lead = grid ? "variant," : "";
  const auto group_name = [&](const pipeline::RunRecord& run) -> const std::string& {
    return result.variants[static_cast<std::size_t>(run.variant)].groups[static_cast<std::size_t>(run.group)];
  };
  // 3-D estimates (a z with its own variance) add the z columns.
  bool three_d = false;
  for (const auto& run : result.runs) {
    for (const auto& agent : run.agents) {
      for (const auto& s : agent.steps) three_d = three_d || s.covariance_m2(2, 2) > 0.0;
    }
  }
  {
    OutputFile file(dir + "/tracks.csv");
    auto& out = file.stream();
    out << lead << "trajectory,run,step,t_s,x_true_m,y_true_m,x_est_m,y_est_m,error_m,sigma_x_m,sigma_y_m,peb_m,"
        << "associations,relocalized" << (three_d ? ",z_true_m,z_est_m,sigma_z_m" : "") << "\n";
    for (const auto& run : result.runs) {
      for (const auto& agent : run.agents) {
        for (std::size_t k = 0; k < agent.steps.size(); ++k) {
          const auto& s = agent.steps[k];
          if (grid) out << run.variant << ",";
          out << fmt::format("{},{},{},{:.3f},{},{},{:.5f},{:.5f},{},{:.5f},{:.5f},{},{},{}", agent.name, run.run, k, s.t_s,
                             OptionalNumber(s.truth_m ? std::optional(s.truth_m->x()) : std::nullopt),
                             OptionalNumber(s.truth_m ? std::optional(s.truth_m->y()) : std::nullopt), s.estimate_m.x(),
                             s.estimate_m.y(), OptionalNumber(s.error_m), std::sqrt(s.covariance_m2(0, 0)),
                             std::sqrt(s.covariance_m2(1, 1)), OptionalNumber(s.bound_m), s.associations,
                             s.relocalized ? 1 : 0);
          if (three_d) {
            out << fmt::format(",{},{:.5f},{:.5f}", OptionalNumber(s.truth_m ? std::optional(s.truth_m->z()) : std::nullopt),
                               s.estimate_m.z(), std::sqrt(s.covariance_m2(2, 2)));
          }
          out << "\n";
        }
      }
    }
    file.Commit();
    written.push_back(file.path());
  }
  {
    OutputFile file(dir + "/runs.csv");
    auto& out = file.stream();
    out << lead << "trajectory,run,offset_x_m,offset_y_m,steps,rmse_m,p90_m,diverged\n";
    for (const auto& run : result.runs) {
      for (const auto& agent : run.agents) {
        std::vector<double> errors;
        for (const auto& s : agent.steps) {
          if (s.error_m) errors.push_back(*s.error_m);
        }
        const bool known = !errors.empty() && errors.size() == agent.steps.size();
        const auto e = eval::ComputeErrorStats(errors);
        if (grid) out << run.variant << ",";
        out << fmt::format("{},{},{:.4f},{:.4f},{},{},{},{}\n", agent.name, run.run, run.offset_m.x(), run.offset_m.y(),
                           agent.steps.size(), known ? fmt::format("{:.5f}", e.rmse) : "",
                           known ? fmt::format("{:.5f}", e.p90) : "", known ? (agent.diverged ? "1" : "0") : "");
      }
    }
    file.Commit();
    written.push_back(file.path());
  }
  const bool any_paths = std::any_of(result.runs.begin(), result.runs.end(), [](const auto& r) { return !r.paths.empty(); });
  if (any_paths) {
    // The path truth of the first run of each trajectory (all runs would be tens of megabytes):
    // delay, amplitude, true and estimated SINR of every visible specular path.
    OutputFile file(dir + "/paths.csv");
    auto& out = file.stream();
    out << lead << "trajectory,run,step,anchor_id,va_id,order,delay_s,range_m,amplitude_re,amplitude_im,true_sinr_db,"
        << "estimated_sinr_db\n";
    for (const auto& run : result.runs) {
      if (run.run != 0) continue;
      const auto& e = scenario.variants[static_cast<std::size_t>(run.variant)].experiment;
      for (const auto& p : run.paths) {
        if (grid) out << run.variant << ",";
        out << fmt::format("{},{},{},{},{},{},{:.6e},{:.5f},{:.6e},{:.6e},{:.2f},{}\n", group_name(run), run.run, p.step,
                           e.anchors[static_cast<std::size_t>(p.anchor)].id, p.va_id, p.order, p.delay_s,
                           p.delay_s * e.channel.medium.speed_mps, p.amplitude.real(), p.amplitude.imag(), p.true_sinr_db,
                           p.estimated_sinr_db ? fmt::format("{:.2f}", *p.estimated_sinr_db) : "");
      }
    }
    file.Commit();
    written.push_back(file.path());
  }
  const bool any_map = std::any_of(result.runs.begin(), result.runs.end(), [](const auto& r) { return !r.map.empty(); });
  if (any_map) {
    // The map at the end of every run: every feature with its covariance and the method's columns.
    std::vector<std::string> attributes;
    for (const auto& run : result.runs) {
      if (!run.map.empty()) {
        for (const auto& [name, value] : run.map.front().attributes) attributes.push_back(name);
        break;
      }
    }
    OutputFile file(dir + "/map.csv");
    auto& out = file.stream();
    out << lead << "trajectory,run,va_id,anchor_id,origin,x_m,y_m,cov_xx_m2,cov_xy_m2,cov_yy_m2";
    for (const auto& a : attributes) out << "," << a;
    out << "\n";
    for (const auto& run : result.runs) {
      const auto& e = scenario.variants[static_cast<std::size_t>(run.variant)].experiment;
      for (const auto& f : run.map) {
        if (grid) out << run.variant << ",";
        out << fmt::format("{},{},{},{},{},{:.5f},{:.5f},{:.6e},{:.6e},{:.6e}", group_name(run), run.run, f.id,
                           e.anchors[static_cast<std::size_t>(f.anchor_index)].id, f.origin, f.position_m.x(),
                           f.position_m.y(), f.covariance_m2(0, 0), f.covariance_m2(0, 1), f.covariance_m2(1, 1));
        for (const auto& [name, value] : f.attributes) out << "," << value;
        out << "\n";
      }
    }
    file.Commit();
    written.push_back(file.path());
  }
  if (grid) {
    {
      OutputFile file(dir + "/variants.csv");
      auto& out = file.stream();
      out << "variant,name,runs,error_p50_m,error_p90_m,error_rmse_m,final_mean_m,final_p90_m,diverged_runs,peb_rms_m,"
             "tracked_rmse_over_peb,relative_p90_m,biased_wall_final_mean_abs_m,wall_rms_error_m,associated_per_step,"
             "expected_per_step,drifted_runs\n";
      for (std::size_t v = 0; v < summaries.size(); ++v) {
        const GroupSummary& g = summaries[v].overall;
        const auto walls = g.walls;
        out << fmt::format("{},\"{}\",{},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{},{},{},{},{},{},{:.3f},{:.3f},{}\n", v,
                           summaries[v].name, g.runs, g.error.p50, g.error.p90, g.error.rmse, g.final_error_mean_m,
                           g.final_error_p90_m, g.diverged_runs, OptionalNumber(g.bound_rms_m),
                           g.tracked_rmse_over_bound ? fmt::format("{:.4f}", *g.tracked_rmse_over_bound) : "",
                           walls ? fmt::format("{:.6f}", walls->relative_error_p90_m) : "",
                           walls && walls->biased_wall_final_mean_abs_m ? fmt::format("{:.6f}", *walls->biased_wall_final_mean_abs_m) : "",
                           walls ? fmt::format("{:.6f}", walls->rms_error_mean_m) : "", g.associations_per_step,
                           g.expected_per_step, g.health.drifted_runs);
      }
      file.Commit();
      written.push_back(file.path());
    }
    OutputFile file(dir + "/error_by_step.csv");
    auto& out = file.stream();
    out << "variant,step,mean_error_m,peb_m\n";
    for (std::size_t v = 0; v < summaries.size(); ++v) {
      const GroupSummary& g = summaries[v].overall;
      for (std::size_t k = 0; k < g.error_by_step_m.size(); ++k) {
        out << fmt::format("{},{},{:.6f},{:.6f}\n", v, k, g.error_by_step_m[k], g.bound_by_step_m[k]);
      }
    }
    file.Commit();
    written.push_back(file.path());
  }
  return written;
}

}  // namespace mirage::io
