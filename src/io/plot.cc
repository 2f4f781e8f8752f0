// SPDX-License-Identifier: MIT
#include "mirage/io/plot.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
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

json PlotData(const Scenario& scenario, const pipeline::MintExperimentResult& result,
              const pipeline::MintSummary& summary) {
  const auto& config = scenario.mint;
  json walls = json::array();
  for (const auto& w : config.plan.walls()) {
    walls.push_back({w.start_m.x(), w.start_m.y(), w.end_m.x(), w.end_m.y(), w.reflection_coeff, w.label});
  }
  json obstacles = json::array();
  for (const auto& o : config.plan.obstacles()) obstacles.push_back({o.center_m.x(), o.center_m.y(), o.radius_m});
  json anchors = json::array();
  for (std::size_t a = 0; a < config.anchors_m.size(); ++a) {
    anchors.push_back({config.anchors_m[a].x(), config.anchors_m[a].y(), config.anchor_ids[a]});
  }
  json vas = json::array();
  // SLAM: the true VAs of the simulated room (what the map should find); MINT: the known ones.
  const bool slam = config.method == pipeline::Method::kSlam;
  for (const auto& va : (slam ? result.channel_vas : result.known_vas).all()) {
    if (va.order > 0) vas.push_back({va.position_m.x(), va.position_m.y(), va.order, va.anchor_index});
  }
  json trajectories = json::array();
  for (std::size_t t = 0; t < config.trajectories.size(); ++t) {
    json runs = json::array();
    json errors = json::array();
    json truth = json::array();
    json ellipses = json::array();
    json map = json::array();
    // The truth and ellipses of the run closest to the grid centre among the runs present.
    int central = -1;
    double central_offset_m = 0.0;
    for (const auto& run : result.runs) {
      if (run.trajectory != static_cast<int>(t)) continue;
      if (central < 0 || run.offset_m.norm() < central_offset_m) {
        central = run.run;
        central_offset_m = run.offset_m.norm();
      }
    }
    for (const auto& run : result.runs) {
      if (run.trajectory != static_cast<int>(t)) continue;
      json est = json::array();
      for (std::size_t k = 0; k < run.steps.size(); ++k) {
        const auto& s = run.steps[k];
        est.push_back({s.estimate_m.x(), s.estimate_m.y()});
        if (s.error_m) errors.push_back(*s.error_m);
        if (run.run == central) {
          if (s.truth_m) truth.push_back({s.truth_m->x(), s.truth_m->y()});
          if (k % 20 == 0) {
            ellipses.push_back({s.estimate_m.x(), s.estimate_m.y(), s.covariance_m2(0, 0), s.covariance_m2(0, 1),
                                s.covariance_m2(1, 1)});
          }
        }
      }
      runs.push_back({{"run", run.run}, {"diverged", run.diverged}, {"estimate", est}});
      if (run.run == central && config.method == pipeline::Method::kSlam) {
        // The SLAM map of the central run: estimated VAs with covariances (anchors excluded).
        for (const auto& va : run.map) {
          if (va.origin == methods::slam::MapVaOrigin::kAnchor) continue;
          map.push_back({{"x", va.position_m.x()},
                         {"y", va.position_m.y()},
                         {"cov", {va.covariance_m2(0, 0), va.covariance_m2(0, 1), va.covariance_m2(1, 1)}},
                         {"anchor", va.anchor_index},
                         {"discovered", va.origin == methods::slam::MapVaOrigin::kDiscovered},
                         {"filtered", va.filtered}});
        }
      }
    }
    trajectories.push_back({{"name", config.trajectories[t].name},
                            {"truth", truth},
                            {"central_run", central},
                            {"runs", runs},
                            {"errors", errors},
                            {"ellipses", ellipses},
                            {"map", map}});
  }
  return {{"title", config.name},
          {"walls", walls},
          {"obstacles", obstacles},
          {"anchors", anchors},
          {"vas", vas},
          {"trajectories", trajectories},
          {"table", FormatResultTable(scenario, summary)}};
}

}  // namespace

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

void WritePlot(const std::string& png_path, const std::string& script_path, const Scenario& scenario,
               const pipeline::MintExperimentResult& result, const pipeline::MintSummary& summary) {
  RenderPlot(png_path, script_path, PlotData(scenario, result, summary));
}

}  // namespace mirage::io
