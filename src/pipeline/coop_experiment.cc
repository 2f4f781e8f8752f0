// SPDX-License-Identifier: MIT
#include "mirage/pipeline/coop_experiment.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <fmt/format.h>

#include "mirage/channel/specular_path.h"
#include "mirage/core/constants.h"
#include "mirage/core/rng.h"
#include "mirage/core/units.h"
#include "mirage/estimation/ekf_update.h"
#include "mirage/estimation/measurement_row.h"
#include "mirage/estimation/motion/constant_velocity.h"
#include "mirage/geometry/image_source.h"
#include "mirage/geometry/trajectory.h"
#include "mirage/methods/coop/cir_link_signal.h"
#include "mirage/pipeline/parallel_jobs.h"

namespace mirage::pipeline {
namespace {

using methods::coop::Link;
using methods::coop::LinkKind;
using Clock = std::chrono::steady_clock;

// Divergence: an agent ends farther than this from its true position.
constexpr double kDivergedM = 0.5;

// What every run of one variant shares: the pulse-dependent channel and extraction.
struct VariantContext {
  CoopVariant variant;
  channel::ChannelOptions channel;
  std::unique_ptr<channel::CirSynthesizer> synthesizer;
  std::unique_ptr<dsp::MpcExtractor> extractor;
  std::vector<Link> links;
};

// The provided (filter's) floor plan of one run, with the true offset of each of its walls
// relative to it along its normal (true minus provided).
struct ProvidedPlan {
  geometry::FloorPlan plan;
  std::vector<int> true_index;      // provided wall -> true wall
  std::vector<double> true_offset_m;
  int biased = -1;                  // provided index of the biased wall
};

ProvidedPlan MakeProvidedPlan(const CoopExperimentConfig& config, const CoopVariant& variant, core::Rng rng) {
  ProvidedPlan out;
  std::vector<geometry::Wall> walls;
  const auto& truth = config.true_plan.walls();
  for (std::size_t s = 0; s < truth.size(); ++s) {
    // Draw for every wall, used or not, so that the draws do not depend on in_plan or r
    // (common random numbers across variants): U(-r/2, r/2) per coordinate (Sec. IV-E).
    const Vec2 unit(rng.Uniform(-0.5, 0.5), rng.Uniform(-0.5, 0.5));
    if (!config.in_plan[s]) continue;
    Vec2 shift = variant.wall_error_m * unit;
    const Vec2 n = geometry::WallNormal(truth[s]);
    if (variant.biased_wall && static_cast<int>(s) == config.wall_bias.wall) {
      shift += config.wall_bias.offset_m * n;
      out.biased = static_cast<int>(walls.size());
    }
    geometry::Wall w = truth[s];
    w.start_m += shift;
    w.end_m += shift;
    walls.push_back(w);
    out.true_index.push_back(static_cast<int>(s));
    out.true_offset_m.push_back(-n.dot(shift));
  }
  out.plan = geometry::FloorPlan(std::move(walls), config.true_plan.obstacles());
  return out;
}

// Agent positions per step (step 0 = start), one step per second; an agent whose polyline is
// shorter than the run stays at its last point.
std::vector<std::vector<Vec2>> SampleTruth(const CoopExperimentConfig& config) {
  std::vector<std::vector<Vec2>> truth(static_cast<std::size_t>(config.agents.size()));
  for (std::size_t a = 0; a < config.agents.size(); ++a) {
    const auto samples = geometry::SampleTrajectory(config.agents[a].waypoints_m, config.agents[a].speed_m_per_step, 1.0);
    for (int n = 0; n <= config.steps; ++n) {
      const auto i = std::min(static_cast<std::size_t>(n), samples.size() - 1);
      truth[a].push_back(samples[i].position_m);
    }
  }
  return truth;
}

std::vector<Vec2> AgentsAt(const std::vector<std::vector<Vec2>>& truth, int agents, int step) {
  std::vector<Vec2> out;
  for (int m = 0; m < agents; ++m) out.push_back(truth[static_cast<std::size_t>(m)][static_cast<std::size_t>(step)]);
  return out;
}

// The specular paths of one link on the true plan, with the antenna coupling of a self link,
// and the distance the DM is referred to (Eq. 1: the DM starts with the first arrival).
struct LinkChannel {
  std::vector<channel::SpecularPath> paths;
  double dm_reference_m = 0.0;
};

LinkChannel SimulateLink(const CoopExperimentConfig& config, const Link& link, const methods::coop::LinkEnds& ends) {
  LinkChannel out;
  const double carrier_hz = config.channel.pulse.carrier_hz;
  const auto sequences = geometry::VisibleImagePaths(config.true_plan, ends.tx_m, ends.rx_m, config.simulated_max_order);
  double first_reflection_m = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < sequences.size(); ++i) {
    const auto& walls = sequences[i];
    const double length_m = geometry::ComputeImagePath(config.true_plan, walls, ends.tx_m, ends.rx_m).length_m;
    double gain = 1.0;
    for (const int s : walls) gain *= config.true_plan.walls()[static_cast<std::size_t>(s)].reflection_coeff;
    if (link.kind == LinkKind::kSelf && walls.empty()) {
      gain = std::sqrt(core::DbToPowerRatio(config.self_coupling_db));  // the antenna coupling
    } else if (!walls.empty()) {
      first_reflection_m = std::min(first_reflection_m, length_m);
    }
    channel::SpecularPath path;
    path.va_id = static_cast<int>(i);
    path.order = static_cast<int>(walls.size());
    path.delay_s = length_m / config.channel.medium.speed_mps;
    // Free-space amplitude (1 m reference), reflection losses and the carrier phase.
    path.amplitude = gain / length_m * std::polar(1.0, -2.0 * core::kPi * carrier_hz * path.delay_s);
    out.paths.push_back(path);
  }
  // Relative and anchor links: the DM starts at the LOS delay (blocked or not), as for MINT. A
  // self link has no LOS worth the name; its DM starts with the first reflection.
  out.dm_reference_m = link.kind == LinkKind::kSelf ? first_reflection_m : (ends.rx_m - ends.tx_m).norm();
  if (!std::isfinite(out.dm_reference_m)) out.dm_reference_m = std::max(config.antennas.spacing_m, 0.1);
  return out;
}

// The posterior position error bound of the variant (see CoopVariantResult::peb_m): the filter's
// covariance recursion on the true trajectory and walls, with the true SINRs.
std::vector<std::vector<double>> PositionErrorBound(const CoopExperimentConfig& config, const VariantContext& v,
                                                    const std::vector<std::vector<Vec2>>& truth) {
  // The true plan restricted to the provided walls: the filter's model with exact walls.
  std::vector<geometry::Wall> walls;
  for (std::size_t s = 0; s < config.true_plan.walls().size(); ++s) {
    if (config.in_plan[s]) walls.push_back(config.true_plan.walls()[s]);
  }
  const geometry::FloorPlan plan(std::move(walls), config.true_plan.obstacles());
  methods::coop::CoopOptions options = config.coop;
  options.wall_update = v.variant.wall_update;
  options.wall_sigma_m = v.variant.wall_sigma_m;
  methods::coop::CoopTracker model(options, plan, v.links, config.antennas,
                                   config.anchor ? std::optional<Vec2>(config.anchor->position_m) : std::nullopt,
                                   methods::coop::PulseFactsOf(v.synthesizer->pulse(), v.channel.medium));
  const int agents = v.variant.agents;
  const std::vector<Vec2> start = AgentsAt(truth, agents, 0);
  model.Initialize(start, 0.0);
  estimation::State state = model.state();
  const double sigma1_m = v.synthesizer->pulse().range_sigma_at_unit_sinr_m(v.channel.medium.speed_mps);
  const Vec2 anchor_m = config.anchor ? config.anchor->position_m : Vec2::Zero();
  std::vector<std::vector<double>> peb(static_cast<std::size_t>(config.steps) + 1);
  for (int step = 0; step <= config.steps; ++step) {
    if (step > 0) {
      const estimation::ConstantVelocity motion(methods::coop::CoopMotion(options, step - state.t_s()), 2, agents);
      estimation::Propagate(state, step, {&motion});
      const std::vector<Vec2> at = AgentsAt(truth, agents, step);
      std::vector<estimation::MeasurementRow> rows;
      for (std::size_t l = 0; l < v.links.size(); ++l) {
        const auto ends = methods::coop::AntennaPositions(v.links[l], at, anchor_m, config.antennas);
        const LinkChannel link_channel = SimulateLink(config, v.links[l], ends);
        for (const auto& path : model.ExpectedPaths(static_cast<int>(l), at, plan)) {
          const double length_m = path.range_m();
          double gain = 1.0;
          for (const int s : path.walls) gain *= plan.walls()[static_cast<std::size_t>(s)].reflection_coeff;
          const double sinr = v.synthesizer->TrueSinr(Complex(gain / length_m, 0.0), length_m / v.channel.medium.speed_mps,
                                                      link_channel.dm_reference_m);
          // The model's layout is the layout of `state` (a copy of its initial state).
          rows.push_back(model.JacobianRow(v.links[l], path, sigma1_m * sigma1_m / std::max(sinr, 1e-12)));
        }
      }
      if (!rows.empty()) {
        // Every path measured exactly at its mean: zero innovations, only the covariance moves.
        const std::vector<double> zero(rows.size(), 0.0);
        estimation::Update(state, rows, zero);
      }
    }
    for (int m = 0; m < agents; ++m) {
      peb[static_cast<std::size_t>(step)].push_back(
          std::sqrt(state.Covariance(estimation::BlockKey(estimation::blocks::kPosition, m)).trace()));
    }
  }
  return peb;
}

CoopRun RunOne(const CoopExperimentConfig& config, const VariantContext& v,
               const std::vector<std::vector<Vec2>>& truth, int run) {
  const core::Rng run_rng(config.seed, static_cast<std::uint64_t>(run));
  const ProvidedPlan provided = MakeProvidedPlan(config, v.variant, run_rng.Substream("plan"));
  methods::coop::CoopOptions options = config.coop;
  options.wall_update = v.variant.wall_update;
  options.wall_sigma_m = v.variant.wall_sigma_m;
  const Vec2 anchor_m = config.anchor ? config.anchor->position_m : Vec2::Zero();
  methods::coop::CoopTracker tracker(options, provided.plan, v.links, config.antennas,
                                     v.variant.anchor ? std::optional<Vec2>(anchor_m) : std::nullopt,
                                     methods::coop::PulseFactsOf(v.synthesizer->pulse(), v.channel.medium));
  const int agents = v.variant.agents;
  tracker.Initialize(AgentsAt(truth, agents, 0), 0.0);
  // Per link, noise and DM streams named after the link, so that a link sees the same draws in
  // every variant that has it.
  std::vector<core::Rng> diffuse_rng, noise_rng;
  for (const auto& link : v.links) {
    diffuse_rng.push_back(run_rng.Substream(link.Name() + " diffuse"));
    noise_rng.push_back(run_rng.Substream(link.Name() + " noise"));
  }
  const auto& provided_walls = provided.plan.walls();
  // The translation that best explains the wall offset errors, weighted by their precision
  // (the floor plan's frame, Sec. IV-E), and each wall's error after removing it.
  const auto frame = [&](Vec2& translation, std::vector<double>& wall_error) {
    translation.setZero();
    wall_error.assign(provided_walls.size(), 0.0);
    if (!options.wall_update) {
      // Walls fixed at the provided plan, which defines the frame: the error is the plan's.
      for (std::size_t s = 0; s < provided_walls.size(); ++s) wall_error[s] = -provided.true_offset_m[s];
      return;
    }
    Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
    Vec2 b = Vec2::Zero();
    for (std::size_t s = 0; s < provided_walls.size(); ++s) {
      wall_error[s] = tracker.WallOffset(static_cast<int>(s)) - provided.true_offset_m[s];
      const Vec2 n = geometry::WallNormal(provided_walls[s]);
      const double sigma = std::max(tracker.WallOffsetSigma(static_cast<int>(s)), 1e-6);
      A += n * n.transpose() / (sigma * sigma);
      b += n * wall_error[s] / (sigma * sigma);
    }
    translation = A.ldlt().solve(b);
    for (std::size_t s = 0; s < provided_walls.size(); ++s) wall_error[s] -= geometry::WallNormal(provided_walls[s]).dot(translation);
  };

  CoopRun out;
  std::vector<core::Cir> cirs(v.links.size());
  Vec2 translation;
  std::vector<double> wall_error;
  for (int step = 0; step <= config.steps; ++step) {
    const std::vector<Vec2> at = AgentsAt(truth, agents, step);
    int associated = 0, expected = 0;
    if (step > 0) {
      for (std::size_t l = 0; l < v.links.size(); ++l) {
        const auto ends = methods::coop::AntennaPositions(v.links[l], at, anchor_m, config.antennas);
        const LinkChannel link_channel = SimulateLink(config, v.links[l], ends);
        cirs[l] = v.synthesizer->Synthesize(link_channel.paths, link_channel.dm_reference_m, diffuse_rng[l],
                                            noise_rng[l]).cir;
      }
      std::vector<methods::coop::CirLinkSignal> signals;
      signals.reserve(cirs.size());
      for (const auto& cir : cirs) signals.emplace_back(*v.extractor, cir);
      std::vector<const methods::coop::LinkSignal*> pointers;
      for (const auto& s : signals) pointers.push_back(&s);
      const auto info = tracker.Step(step, pointers);
      for (const auto& li : info.links) {
        associated += li.associated;
        expected += li.expected;
      }
    }
    frame(translation, wall_error);
    std::vector<double> error, relative;
    std::vector<Vec2> estimate;
    std::vector<Eigen::Matrix2d> covariance;
    for (int m = 0; m < agents; ++m) {
      const Vec2 diff = tracker.Position(m) - at[static_cast<std::size_t>(m)];
      error.push_back(diff.norm());
      relative.push_back((diff - translation).norm());
      estimate.push_back(tracker.Position(m));
      covariance.push_back(tracker.PositionCovariance(m));
    }
    out.error_m.push_back(std::move(error));
    out.relative_error_m.push_back(std::move(relative));
    out.estimate_m.push_back(std::move(estimate));
    out.covariance_m2.push_back(std::move(covariance));
    out.associated.push_back(associated);
    out.expected.push_back(expected);
    if (provided.biased >= 0) out.bias_wall_error_m.push_back(wall_error[static_cast<std::size_t>(provided.biased)]);
  }
  double sum = 0.0;
  for (const double e : wall_error) sum += e * e;
  out.wall_rms_error_m = std::sqrt(sum / static_cast<double>(std::max<std::size_t>(1, wall_error.size())));
  for (const double e : out.error_m.back()) out.diverged = out.diverged || e > kDivergedM;
  return out;
}

}  // namespace

std::string CoopVariant::Name() const {
  std::string name = fmt::format("M{}{} Tp{}ns r{}mm {} sseg{}mm", agents, anchor ? " anchor" : "",
                                 fmt::format("{:g}", pulse_duration_s * 1e9), fmt::format("{:g}", wall_error_m * 1e3),
                                 wall_update ? "su" : "nosu", fmt::format("{:g}", wall_sigma_m * 1e3));
  if (biased_wall) name += " bias";
  return name;
}

std::vector<std::string> Validate(const CoopExperimentConfig& config) {
  std::vector<std::string> problems;
  if (config.runs < 1) problems.push_back("runs must be >= 1");
  if (config.steps < 1) problems.push_back("steps must be >= 1");
  if (config.agents.size() < 2) problems.push_back("at least 2 agents");
  if (config.in_plan.size() != config.true_plan.walls().size()) problems.push_back("in_plan must have one flag per wall");
  if (config.simulated_max_order < 1 || config.simulated_max_order > 3) problems.push_back("simulated_max_order must be in 1..3");
  if (config.variants.empty()) problems.push_back("no variants");
  for (const auto& v : config.variants) {
    if (v.agents < 2 || v.agents > static_cast<int>(config.agents.size())) {
      problems.push_back(fmt::format("variant {}: agents must be in 2..{}", v.Name(), config.agents.size()));
    }
    if (v.anchor && !config.anchor) problems.push_back(fmt::format("variant {}: no anchor in the scenario", v.Name()));
    if (v.biased_wall && config.wall_bias.wall < 0) problems.push_back(fmt::format("variant {}: no wall_bias", v.Name()));
  }
  if (config.wall_bias.wall >= 0 &&
      (config.wall_bias.wall >= static_cast<int>(config.in_plan.size()) || !config.in_plan[static_cast<std::size_t>(config.wall_bias.wall)])) {
    problems.push_back("wall_bias must name a wall of the provided plan");
  }
  for (auto& p : channel::Validate(config.channel)) problems.push_back("channel: " + p);
  for (auto& p : methods::coop::Validate(config.coop)) problems.push_back("coop: " + p);
  return problems;
}

CoopExperimentResult RunCoopExperiment(const CoopExperimentConfig& config, const CoopProgress& progress) {
  if (const auto problems = Validate(config); !problems.empty()) {
    throw std::invalid_argument("RunCoopExperiment: " + problems.front());
  }
  const auto t_start = Clock::now();
  CoopExperimentResult result;
  result.truth_m = SampleTruth(config);
  std::vector<VariantContext> contexts;
  for (const auto& variant : config.variants) {
    VariantContext v;
    v.variant = variant;
    v.channel = config.channel;
    v.channel.pulse.duration_s = variant.pulse_duration_s;
    v.synthesizer = std::make_unique<channel::CirSynthesizer>(v.channel);
    v.extractor = std::make_unique<dsp::MpcExtractor>(config.mpc, v.synthesizer->pulse(), v.synthesizer->sample_count(),
                                                      v.channel.sample_period_s, v.channel.medium);
    v.links = methods::coop::EnumerateLinks(variant.agents, variant.anchor);
    contexts.push_back(std::move(v));
  }
  const int variants = static_cast<int>(contexts.size());
  result.variants.resize(contexts.size());
  for (int i = 0; i < variants; ++i) {
    result.variants[static_cast<std::size_t>(i)].variant = contexts[static_cast<std::size_t>(i)].variant;
    result.variants[static_cast<std::size_t>(i)].runs.resize(static_cast<std::size_t>(config.runs));
  }
  // Jobs: the bound of each variant, then every run of every variant.
  const int total = variants * (config.runs + 1);
  RunJobs(
      total, config.threads,
      [&](int job) {
        if (job < variants) {
          auto& v = result.variants[static_cast<std::size_t>(job)];
          v.peb_m = PositionErrorBound(config, contexts[static_cast<std::size_t>(job)], result.truth_m);
        } else {
          const int variant = (job - variants) / config.runs;
          const int run = (job - variants) % config.runs;
          result.variants[static_cast<std::size_t>(variant)].runs[static_cast<std::size_t>(run)] =
              RunOne(config, contexts[static_cast<std::size_t>(variant)], result.truth_m, run);
        }
      },
      progress);
  result.wall_s = std::chrono::duration<double>(Clock::now() - t_start).count();
  return result;
}

}  // namespace mirage::pipeline
