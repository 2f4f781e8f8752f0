// SPDX-License-Identifier: MIT
#include "mirage/pipeline/mint_experiment.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "mirage/channel/cir_synthesizer.h"
#include "mirage/channel/specular_path.h"
#include "mirage/core/rng.h"
#include "mirage/core/units.h"
#include "mirage/dsp/mpc_extractor.h"
#include "mirage/eval/error_stats.h"
#include "mirage/eval/position_error_bound.h"
#include "mirage/geometry/trajectory.h"
#include "mirage/pipeline/parallel_jobs.h"
#include "mirage/pipeline/run_simulator.h"
#include "mirage/pipeline/tracker_adapter.h"

namespace mirage::pipeline {
namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

// Identifies a VA across two VA sets built from corresponding walls: anchor and wall sequence.
using VaKey = std::pair<int, std::vector<int>>;

struct Shared {
  explicit Shared(const MintExperimentConfig& config) : simulation(config) {}
  SimulationContext simulation;
  geometry::VirtualAnchorSet known_vas;
  std::vector<int> known_to_channel;  // known VA id -> channel VA id, or -1
};

// Fills a step record from the tracker's output; truth and PEB when known.
StepRecord MakeStepRecord(double t_s, const std::optional<Vec2>& truth_m, const TrackerStep& step) {
  StepRecord s;
  s.t_s = t_s;
  s.truth_m = truth_m;
  s.estimate_m = step.position_m;
  s.covariance_m2 = step.covariance_m2;
  if (truth_m) s.error_m = (step.position_m - *truth_m).norm();
  s.associations = step.associations;
  s.relocalized = step.relocalized;
  return s;
}

void CountEvents(const TrackerStep& step, RunRecord& record) {
  if (step.relocalized) ++record.relocalizations;
  if (step.constrained) ++record.constrained_steps;
  if (step.rejected_update) ++record.rejected_updates;
}

RunRecord RunOne(const Shared& shared, int trajectory, int run) {
  const MintExperimentConfig& config = *shared.simulation.config;
  RunSimulator simulator(shared.simulation, trajectory, run);
  const auto& samples = simulator.samples();

  RunRecord record;
  record.trajectory = trajectory;
  record.run = run;
  record.offset_m = simulator.offset_m();

  const double sigma1_m = shared.simulation.synthesizer->pulse().range_sigma_at_unit_sinr_m(config.channel.medium.speed_mps);
  TrackerAdapter tracker(config, shared.known_vas, sigma1_m);
  // The thesis starts at the known start point with variance sigma_i^2 (Tab. 3.1); optionally
  // the start is drawn from that distribution instead, with the sigma_i of the method that runs.
  const double sigma_i = config.method == Method::kSlam ? config.slam.initial_position_sigma_m
                                                        : config.mint.initial_position_sigma_m;
  core::Rng& init_rng = simulator.init_rng();
  const Vec2 start_error = Vec2(init_rng.Normal(0.0, sigma_i), init_rng.Normal(0.0, sigma_i));
  const Vec2 p0 = samples.front().position_m + (config.perturb_initial_position ? start_error : Vec2(Vec2::Zero()));
  tracker.Initialize(samples.front().t_s, p0);

  std::vector<core::AnchorRanges> measurements;
  std::vector<eval::RangeInformation> information;
  std::map<int, std::size_t> path_index_by_channel_va;  // channel VA id -> index in record.paths (this step)
  std::set<int> visible_channel_ids;                    // channel VAs seen at any step (map truth)
  record.steps.reserve(samples.size());

  for (std::size_t k = 0; k < samples.size(); ++k) {
    const auto& sample = samples[k];
    const auto t_sim = Clock::now();
    information.clear();
    path_index_by_channel_va.clear();
    const int step_index = static_cast<int>(k);
    const auto& truths = simulator.Simulate(k);
    for (std::size_t a = 0; a < truths.size(); ++a) {
      for (const auto& truth : truths[a]) {
        information.push_back({shared.simulation.channel_vas[truth.va_id].position_m, truth.sinr});
        path_index_by_channel_va[truth.va_id] = record.paths.size();
        visible_channel_ids.insert(truth.va_id);
        record.paths.push_back({step_index, static_cast<int>(a), truth.va_id, truth.order, truth.delay_s,
                                truth.amplitude, core::PowerRatioToDb(truth.sinr), std::nullopt});
      }
    }
    const auto t_est = Clock::now();
    simulator.Measure(measurements);
    const auto step = tracker.Step(sample.t_s, measurements);
    const auto t_end = Clock::now();
    record.simulate_s += Seconds(t_est - t_sim);
    record.estimate_s += Seconds(t_end - t_est);

    for (const auto& [va_id, sinr] : step.sinr_estimates) {
      if (va_id < 0 || va_id >= static_cast<int>(shared.known_to_channel.size())) continue;  // discovered VA
      const int channel_id = shared.known_to_channel[static_cast<std::size_t>(va_id)];
      const auto it = path_index_by_channel_va.find(channel_id);
      if (it == path_index_by_channel_va.end()) continue;  // associated a VA the channel does not have now
      // SINR 0 ("zero or complex") is reported at -40 dB so that it stays a finite statistic.
      record.paths[it->second].estimated_sinr_db = core::PowerRatioToDb(std::max(sinr, 1e-4));
    }

    StepRecord s = MakeStepRecord(sample.t_s, sample.position_m, step);
    s.peb_m = eval::PositionErrorBound(sample.position_m, information, sigma1_m);
    CountEvents(step, record);
    record.steps.push_back(s);
  }
  record.diverged = eval::IsDiverged(StepErrors(record.steps), config.divergence);
  if (config.method == Method::kSlam) {
    record.map = tracker.Map();
    record.map_score = EvaluateMap(record.map, shared.simulation.channel_vas, visible_channel_ids, config.map_cutoff_m);
  }
  return record;
}

// The one run over recorded data: the tracker sees the recorded ranges; errors and the map score
// exist only with truth (the true VAs are those of the scenario's floor plan visible from the
// true positions at the recorded steps).
RunRecord RunRecorded(const Shared& shared) {
  const MintExperimentConfig& config = *shared.simulation.config;
  const Recording& recording = *config.recording;
  RunRecord record;
  const double sigma1_m = shared.simulation.synthesizer->pulse().range_sigma_at_unit_sinr_m(config.channel.medium.speed_mps);
  TrackerAdapter tracker(config, shared.known_vas, sigma1_m);
  const double t0_s = recording.steps.front().t_s;
  const std::optional<Vec2> start_m = config.start_m ? config.start_m : recording.TruthAt(t0_s);
  tracker.Initialize(t0_s, *start_m);  // the scenario loader ensures one of the two exists
  std::set<int> visible_channel_ids;
  record.steps.reserve(recording.steps.size());
  for (const auto& recorded : recording.steps) {
    const auto t_est = Clock::now();
    const auto step = tracker.Step(recorded.t_s, recorded.anchors);
    record.estimate_s += Seconds(Clock::now() - t_est);
    const std::optional<Vec2> truth_m = recording.TruthAt(recorded.t_s);
    if (truth_m && config.method == Method::kSlam) {
      for (std::size_t a = 0; a < config.anchors_m.size(); ++a) {
        for (const auto& path : channel::ComputeSpecularPaths(shared.simulation.channel_vas, static_cast<int>(a),
                                                              config.plan, *truth_m, config.channel.pulse.carrier_hz,
                                                              config.channel.medium)) {
          visible_channel_ids.insert(path.va_id);
        }
      }
    }
    CountEvents(step, record);
    record.steps.push_back(MakeStepRecord(recorded.t_s, truth_m, step));
  }
  if (recording.has_truth()) record.diverged = eval::IsDiverged(StepErrors(record.steps), config.divergence);
  if (config.method == Method::kSlam) {
    record.map = tracker.Map();
    if (recording.has_truth()) {
      record.map_score = EvaluateMap(record.map, shared.simulation.channel_vas, visible_channel_ids, config.map_cutoff_m);
    }
  }
  return record;
}

}  // namespace

std::vector<double> StepErrors(const std::vector<StepRecord>& steps) {
  std::vector<double> errors;
  errors.reserve(steps.size());
  for (const auto& s : steps) {
    if (s.error_m) errors.push_back(*s.error_m);
  }
  return errors;
}

MintExperimentResult RunMintExperiment(const MintExperimentConfig& config, const ProgressCallback& progress) {
  const auto t_start = Clock::now();
  Shared shared(config);
  shared.known_vas =
      geometry::VirtualAnchorSet::Generate(config.known_anchors_m, config.known_plan, KnownVaOrder(config));
  std::map<VaKey, int> channel_by_key;
  for (const auto& va : shared.simulation.channel_vas.all()) channel_by_key[{va.anchor_index, va.walls}] = va.id;
  for (const auto& va : shared.known_vas.all()) {
    const auto it = channel_by_key.find({va.anchor_index, va.walls});
    shared.known_to_channel.push_back(it == channel_by_key.end() ? -1 : it->second);
  }
  if (config.recording) {
    MintExperimentResult result;
    result.has_truth = config.recording->has_truth();
    result.simulated = false;
    result.runs.push_back(RunRecorded(shared));
    if (progress) progress(1, 1);
    result.known_vas = std::move(shared.known_vas);
    result.channel_vas = std::move(shared.simulation.channel_vas);
    result.wall_s = Seconds(Clock::now() - t_start);
    return result;
  }

  const int trajectories = static_cast<int>(config.trajectories.size());
  const int total = trajectories * config.runs;
  MintExperimentResult result;
  result.runs.resize(static_cast<std::size_t>(total));
  RunJobs(
      total, config.threads,
      [&](int job) {
        result.runs[static_cast<std::size_t>(job)] = RunOne(shared, job / config.runs, job % config.runs);
      },
      progress);
  result.known_vas = std::move(shared.known_vas);
  result.channel_vas = std::move(shared.simulation.channel_vas);
  result.wall_s = Seconds(Clock::now() - t_start);
  return result;
}

}  // namespace mirage::pipeline
