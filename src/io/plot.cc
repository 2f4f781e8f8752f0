// SPDX-License-Identifier: MIT
#include "mirage/io/plot.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <vector>

#include <nlohmann/json.hpp>

#include "mirage/io/input_error.h"
#include "mirage/io/report.h"

extern char** environ;

namespace mirage::io {
namespace {

using nlohmann::json;

std::string Interpreter() {
  if (const char* env = std::getenv("MIRAGE_PYTHON"); env != nullptr && *env != '\0') return env;
  if (std::filesystem::exists("/usr/bin/python3")) return "/usr/bin/python3";
  return "python3";
}

// Runs argv without a shell (paths may contain anything) and returns the exit status.
int Run(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawnp(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) return -1;
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

json PlotData(const Scenario& scenario, const pipeline::ExperimentResult& result,
              const std::vector<pipeline::VariantSummary>& summaries, const std::string& table) {
  const pipeline::Experiment& e = scenario.variants.front().experiment;
  json walls = json::array();
  for (const auto& w : e.plan.walls()) {
    walls.push_back({w.start_m.x(), w.start_m.y(), w.end_m.x(), w.end_m.y(), w.reflection_coeff, w.label});
  }
  json obstacles = json::array();
  for (const auto& o : e.plan.obstacles()) obstacles.push_back({o.center_m.x(), o.center_m.y(), o.radius_m});
  json anchors = json::array();
  for (const auto& a : e.anchors) anchors.push_back({a.position_m.x(), a.position_m.y(), a.id});
  json vas = json::array();
  for (const auto& va : result.variants.front().channel_vas.all()) {
    if (va.order > 0 && va.order <= 2) vas.push_back({va.position_m.x(), va.position_m.y(), va.order, va.anchor_index});
  }
  // Per tracked agent of the first variant: every run's estimate, the truth, errors and ellipses of
  // the run closest to the run grid's centre, and that run's map.
  std::map<std::string, json> by_agent;
  std::vector<std::string> order;
  std::map<std::string, std::pair<int, double>> central;  // agent -> (run, offset)
  for (const auto& run : result.runs) {
    if (run.variant != 0) continue;
    for (const auto& agent : run.agents) {
      const auto it = central.find(agent.name);
      if (it == central.end() || run.offset_m.norm() < it->second.second) central[agent.name] = {run.run, run.offset_m.norm()};
    }
  }
  for (const auto& run : result.runs) {
    if (run.variant != 0) continue;
    for (const auto& agent : run.agents) {
      if (!by_agent.count(agent.name)) {
        order.push_back(agent.name);
        by_agent[agent.name] = {{"name", agent.name}, {"truth", json::array()}, {"runs", json::array()},
                                {"errors", json::array()}, {"ellipses", json::array()}, {"map", json::array()}};
      }
      json& t = by_agent[agent.name];
      const bool is_central = central[agent.name].first == run.run;
      json est = json::array();
      for (std::size_t k = 0; k < agent.steps.size(); ++k) {
        const auto& s = agent.steps[k];
        est.push_back({s.estimate_m.x(), s.estimate_m.y()});
        if (s.error_m) t["errors"].push_back(*s.error_m);
        if (is_central) {
          if (s.truth_m) t["truth"].push_back({s.truth_m->x(), s.truth_m->y()});
          if (k % 20 == 0) {
            t["ellipses"].push_back({s.estimate_m.x(), s.estimate_m.y(), s.covariance_m2(0, 0), s.covariance_m2(0, 1),
                                     s.covariance_m2(1, 1)});
          }
        }
      }
      t["runs"].push_back({{"run", run.run}, {"diverged", agent.diverged}, {"estimate", est}});
      if (is_central) {
        for (const auto& f : run.map) {
          if (f.origin == "anchor") continue;
          t["map"].push_back({{"x", f.position_m.x()},
                              {"y", f.position_m.y()},
                              {"cov", {f.covariance_m2(0, 0), f.covariance_m2(0, 1), f.covariance_m2(1, 1)}},
                              {"anchor", f.anchor_index},
                              {"discovered", f.origin == "discovered"},
                              {"filtered", !f.scored}});
        }
      }
    }
  }
  json trajectories = json::array();
  for (const auto& name : order) trajectories.push_back(by_agent[name]);
  json variants = json::array();
  if (scenario.has_grid()) {
    // Per variant its error CDF, as at most kCdfPoints quantiles of all its errors (the smallest
    // and the largest included): a picture needs no more, and a 300-run grid has 10^5 per variant.
    constexpr std::size_t kCdfPoints = 400;
    std::vector<std::vector<double>> errors(summaries.size());
    for (const auto& run : result.runs) {
      if (run.variant < 0 || static_cast<std::size_t>(run.variant) >= errors.size()) continue;
      for (const auto& agent : run.agents) {
        for (const auto& step : agent.steps) {
          if (step.error_m) errors[static_cast<std::size_t>(run.variant)].push_back(*step.error_m);
        }
      }
    }
    for (std::size_t v = 0; v < summaries.size(); ++v) {
      auto& sorted = errors[v];
      std::sort(sorted.begin(), sorted.end());
      json cdf = json::array();
      if (!sorted.empty()) {
        const std::size_t points = std::min(kCdfPoints, sorted.size());
        for (std::size_t i = 0; i < points; ++i) {
          const std::size_t index = points == 1 ? sorted.size() - 1 : i * (sorted.size() - 1) / (points - 1);
          cdf.push_back({sorted[index], static_cast<double>(index + 1) / static_cast<double>(sorted.size())});
        }
      }
      const auto& s = summaries[v];
      variants.push_back({{"name", s.name},
                          {"error_by_step", s.overall.error_by_step_m},
                          {"peb_by_step", s.overall.bound_by_step_m},
                          {"error_cdf", cdf}});
    }
  }
  return {{"title", e.name},
          {"walls", walls},
          {"obstacles", obstacles},
          {"anchors", anchors},
          {"vas", vas},
          {"trajectories", trajectories},
          {"variants", variants},
          {"table", table}};
}


void RenderPlot(const std::string& png_path, const std::string& script_path, const nlohmann::json& data) {
  const std::string data_path = png_path + ".json";
  WriteJson(data_path, data);
  if (!std::filesystem::exists(script_path)) throw InputError(script_path + ": plotting script not found");
  // Rendered beside the target under a temporary name with the same extension (matplotlib picks
  // the format from it) and renamed once complete, so a failed render leaves no half picture.
  const std::filesystem::path target(png_path);
  const std::filesystem::path temporary =
      target.parent_path() / (".tmp-" + std::to_string(::getpid()) + "-" + target.filename().string());
  const int status = Run({Interpreter(), script_path, data_path, temporary.string()});
  std::error_code ec;
  if (status != 0) {
    std::filesystem::remove(temporary, ec);
    throw InputError(png_path + ": the plot renderer failed (exit " + std::to_string(status) + "); " + Interpreter() +
                     " needs matplotlib (Debian: python3-matplotlib)");
  }
  std::filesystem::rename(temporary, target, ec);
  if (ec) throw InputError(png_path + ": cannot replace the file (" + ec.message() + ")");
}


}  // namespace mirage::io
