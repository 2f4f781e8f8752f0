// SPDX-License-Identifier: MIT
#include "mirage/pipeline/mint_experiment.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>

#include "mirage/channel/cir_synthesizer.h"
#include "mirage/channel/specular_path.h"
#include "mirage/core/rng.h"
#include "mirage/core/units.h"
#include "mirage/dsp/mpc_extractor.h"
#include "mirage/eval/error_stats.h"
#include "mirage/eval/position_error_bound.h"
#include "mirage/geometry/trajectory.h"
#include "mirage/pipeline/tracker_adapter.h"

namespace mirage::pipeline {
namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

// Identifies a VA across two VA sets built from corresponding walls: anchor and wall sequence.
using VaKey = std::pair<int, std::vector<int>>;

struct Shared {
  const MintExperimentConfig* config = nullptr;
  geometry::VirtualAnchorSet channel_vas;
  geometry::VirtualAnchorSet known_vas;
  std::vector<int> known_to_channel;  // known VA id -> channel VA id, or -1
  std::unique_ptr<channel::CirSynthesizer> synthesizer;
  std::unique_ptr<dsp::MpcExtractor> extractor;
  std::unique_ptr<channel::RangeLevelSimulator> range_level;
};

RunRecord RunOne(const Shared& shared, int trajectory, int run) {
  const MintExperimentConfig& config = *shared.config;
  const TrajectorySpec& spec = config.trajectories[static_cast<std::size_t>(trajectory)];
  const auto stream = static_cast<std::uint64_t>(trajectory) * 1'000'003ULL + static_cast<std::uint64_t>(run);
  const core::Rng run_rng(config.seed, stream);
  // One stream per anchor and purpose, so that adding an anchor shifts no other CIR's noise.
  std::vector<core::Rng> diffuse_rng, noise_rng;
  for (std::size_t a = 0; a < config.anchors_m.size(); ++a) {
    diffuse_rng.push_back(run_rng.Substream("diffuse/" + std::to_string(a)));
    noise_rng.push_back(run_rng.Substream("noise/" + std::to_string(a)));
  }
  core::Rng init_rng = run_rng.Substream("init");
  core::Rng ranges_rng = run_rng.Substream("ranges");

  RunRecord record;
  record.trajectory = trajectory;
  record.run = run;
  record.offset_m = RunOffset(config.run_grid, run);
  const auto samples = geometry::SampleTrajectory(spec.waypoints_m, spec.speed_mps, spec.dt_s, record.offset_m);

  const double sigma1_m = shared.synthesizer->pulse().range_sigma_at_unit_sinr_m();
  TrackerAdapter tracker(config, shared.known_vas, sigma1_m);
  // The thesis starts at the known start point with variance sigma_i^2 (Tab. 3.1); optionally
  // the start is drawn from that distribution instead.
  const double sigma_i = config.mint.initial_position_sigma_m;
  const Vec2 start_error = Vec2(init_rng.Normal(0.0, sigma_i), init_rng.Normal(0.0, sigma_i));
  const Vec2 p0 = samples.front().position_m + (config.perturb_initial_position ? start_error : Vec2(Vec2::Zero()));
  tracker.Initialize(samples.front().t_s, p0);

  const int anchors = static_cast<int>(config.anchors_m.size());
  std::vector<core::AnchorRanges> measurements(static_cast<std::size_t>(anchors));
  std::vector<eval::RangeInformation> information;
  std::map<int, std::size_t> path_index_by_channel_va;  // channel VA id -> index in record.paths (this step)
  std::set<int> visible_channel_ids;                    // channel VAs seen at any step (map truth)
  record.steps.reserve(samples.size());

  for (const auto& sample : samples) {
    const auto t_sim = Clock::now();
    information.clear();
    path_index_by_channel_va.clear();
    const int step_index = static_cast<int>(record.steps.size());
    std::vector<channel::SynthesizedCir> cirs;
    cirs.reserve(static_cast<std::size_t>(anchors));
    for (int a = 0; a < anchors; ++a) {
      const auto paths = channel::ComputeSpecularPaths(shared.channel_vas, a, config.plan, sample.position_m,
                                                       config.channel.pulse.carrier_hz);
      const double los_distance_m =
          std::max((sample.position_m - config.anchors_m[static_cast<std::size_t>(a)]).norm(), 0.01);
      std::vector<channel::PathTruth> truths;
      if (shared.range_level) {
        measurements[static_cast<std::size_t>(a)] = shared.range_level->Simulate(a, paths, los_distance_m, ranges_rng, &truths);
      } else {
        cirs.push_back(shared.synthesizer->Synthesize(paths, los_distance_m, diffuse_rng[static_cast<std::size_t>(a)],
                                                      noise_rng[static_cast<std::size_t>(a)]));
        truths = cirs.back().paths;
      }
      for (const auto& truth : truths) {
        information.push_back({shared.channel_vas[truth.va_id].position_m, truth.sinr});
        path_index_by_channel_va[truth.va_id] = record.paths.size();
        visible_channel_ids.insert(truth.va_id);
        record.paths.push_back({step_index, a, truth.va_id, truth.order, truth.delay_s, truth.amplitude,
                                core::PowerRatioToDb(truth.sinr), std::nullopt});
      }
    }
    const auto t_est = Clock::now();
    for (int a = 0; a < anchors && !shared.range_level; ++a) {
      auto& m = measurements[static_cast<std::size_t>(a)];
      m.anchor_index = a;
      m.ranges.clear();
      for (const auto& mpc : shared.extractor->Extract(cirs[static_cast<std::size_t>(a)].cir)) {
        m.ranges.push_back({mpc.range_m, std::abs(mpc.amplitude)});
      }
    }
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

    StepRecord s;
    s.t_s = sample.t_s;
    s.truth_m = sample.position_m;
    s.estimate_m = step.position_m;
    s.covariance_m2 = step.covariance_m2;
    s.error_m = (step.position_m - sample.position_m).norm();
    s.peb_m = eval::PositionErrorBound(sample.position_m, information, sigma1_m);
    s.associations = step.associations;
    s.relocalized = step.relocalized;
    if (step.relocalized) ++record.relocalizations;
    if (step.constrained) ++record.constrained_steps;
    if (step.rejected_update) ++record.rejected_updates;
    record.steps.push_back(s);
  }
  std::vector<double> errors;
  errors.reserve(record.steps.size());
  for (const auto& s : record.steps) errors.push_back(s.error_m);
  record.diverged = eval::IsDiverged(errors, config.divergence);
  if (config.method == Method::kSlam) {
    record.map = tracker.Map();
    record.map_score = EvaluateMap(record.map, shared.channel_vas, visible_channel_ids, config.map_cutoff_m);
  }
  return record;
}

}  // namespace

MintExperimentResult RunMintExperiment(const MintExperimentConfig& config, const ProgressCallback& progress) {
  const auto t_start = Clock::now();
  Shared shared;
  shared.config = &config;
  shared.channel_vas = geometry::VirtualAnchorSet::Generate(config.anchors_m, config.plan, config.channel_max_order);
  shared.known_vas =
      geometry::VirtualAnchorSet::Generate(config.known_anchors_m, config.known_plan, KnownVaOrder(config));
  std::map<VaKey, int> channel_by_key;
  for (const auto& va : shared.channel_vas.all()) channel_by_key[{va.anchor_index, va.walls}] = va.id;
  for (const auto& va : shared.known_vas.all()) {
    const auto it = channel_by_key.find({va.anchor_index, va.walls});
    shared.known_to_channel.push_back(it == channel_by_key.end() ? -1 : it->second);
  }
  shared.synthesizer = std::make_unique<channel::CirSynthesizer>(config.channel);
  shared.extractor = std::make_unique<dsp::MpcExtractor>(config.mpc, shared.synthesizer->pulse(),
                                                         shared.synthesizer->sample_count(),
                                                         config.channel.sample_period_s);
  if (config.measurement_model == MeasurementModel::kRangeLevel) {
    shared.range_level = std::make_unique<channel::RangeLevelSimulator>(config.range_level, *shared.synthesizer);
  }

  const int trajectories = static_cast<int>(config.trajectories.size());
  const int total = trajectories * config.runs;
  MintExperimentResult result;
  result.runs.resize(static_cast<std::size_t>(total));
  std::atomic<int> next{0};
  std::atomic<int> finished{0};
  // An exception in a worker (out of memory) must reach the caller, not std::terminate.
  std::mutex error_mutex;
  std::exception_ptr error;
  const auto worker = [&]() {
    for (int job = next++; job < total; job = next++) {
      try {
        result.runs[static_cast<std::size_t>(job)] = RunOne(shared, job / config.runs, job % config.runs);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = total;  // stop handing out jobs
        return;
      }
      const int done = ++finished;
      if (progress) progress(done, total);
    }
  };
  int threads = config.threads > 0 ? config.threads : static_cast<int>(std::thread::hardware_concurrency());
  threads = std::clamp(threads, 1, std::max(1, total));
  if (threads == 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    for (int i = 0; i < threads; ++i) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
  }
  if (error) std::rethrow_exception(error);
  result.known_vas = std::move(shared.known_vas);
  result.channel_vas = std::move(shared.channel_vas);
  result.wall_s = Seconds(Clock::now() - t_start);
  return result;
}

}  // namespace mirage::pipeline
