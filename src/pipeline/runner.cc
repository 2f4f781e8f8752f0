// SPDX-License-Identifier: MIT
#include "mirage/pipeline/runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>

#include <fmt/format.h>

#include "mirage/core/units.h"
#include "mirage/eval/position_error_bound.h"
#include "mirage/geometry/visibility.h"
#include "mirage/pipeline/acoustic_source.h"
#include "mirage/pipeline/anchor_channel_source.h"
#include "mirage/pipeline/given_plan.h"
#include "mirage/pipeline/link_source.h"
#include "mirage/pipeline/parallel_jobs.h"
#include "mirage/pipeline/recorded_source.h"
#include "mirage/pipeline/uwb_tdoa_source.h"
#include "mirage/pipeline/wall_frame.h"

namespace mirage::pipeline {
namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

// Identifies a specular path across VA sets built from the same walls: anchor and wall sequence.
using PathKey = std::pair<int, std::vector<int>>;

// What the runs of one variant share; immutable once built.
struct VariantContext {
  const Experiment* experiment = nullptr;
  bool joint = false;
  int groups = 1;
  std::vector<std::string> group_names;
  std::unique_ptr<AnchorChannelContext> anchors;  // single-agent simulations
  std::unique_ptr<LinkContext> links;             // joint simulations of link CIRs
  geometry::VirtualAnchorSet channel_vas;         // the true plan's VAs (the map's truth)
  std::map<PathKey, int> channel_va_by_key;       // their ids by anchor and walls
  double sigma1_m = 0.0;                          // CRLB scale of the pulse (snapshot PEB)
  geometry::FloorPlan true_given_plan;            // the given plan's walls at their true places
};

methods::World MakeWorld(const VariantContext& vc, const GivenPlan& given, int group) {
  const Experiment& e = *vc.experiment;
  methods::World world;
  for (const auto& a : e.anchors) world.anchors.push_back({a.id, a.position_m});
  world.floor_plan = given.plan;
  world.channel = e.channel;
  world.mpc = e.mpc;
  world.physical = PhysicalKeysOf(e);
  world.emission_times_known = e.measurement_model == MeasurementModel::kAcoustic && e.acoustic.emission_time_known;
  if (e.recording) {
    world.agents = {"recorded"};
    world.agent_height_m = e.recorded_height_m;
  } else if (vc.joint) {
    world.agents = vc.links->truth.names;
    world.agent_height_m = e.trajectories.front().height_m;
  } else {
    const TrajectorySpec& t = e.trajectories[static_cast<std::size_t>(group)];
    world.agents = {t.name};
    world.agent_height_m = t.height_m;
  }
  return world;
}

// The error of an estimate: in the plane for a planar estimate (its z known, zero variance), in
// 3-D otherwise.
double EstimateError(const Vec3& position_m, const Eigen::Matrix3d& covariance_m2, const Vec3& truth_m) {
  if (covariance_m2(2, 2) == 0.0) return (position_m.head<2>() - truth_m.head<2>()).norm();
  return (position_m - truth_m).norm();
}

// The track's estimates rigidly aligned to its truth (Experiment::align_rigid): the transform from
// the epochs with a fix and truth, applied to every estimate and covariance, the errors anew.
void AlignToTruth(AgentTrack& agent) {
  std::vector<Vec3> truth_m, estimate_m;
  bool planar = true;
  for (const auto& s : agent.steps) {
    if (!s.truth_m || !s.fixed) continue;
    truth_m.push_back(*s.truth_m);
    estimate_m.push_back(s.estimate_m);
    planar = planar && s.covariance_m2(2, 2) == 0.0;
  }
  agent.alignment = eval::AlignRigid(truth_m, estimate_m, planar);
  if (!agent.alignment) return;
  const Eigen::Matrix3d& R = agent.alignment->rotation;
  for (auto& s : agent.steps) {
    s.estimate_m = agent.alignment->Apply(s.estimate_m);
    s.covariance_m2 = R * s.covariance_m2 * R.transpose();
    if (!s.truth_m) continue;
    s.error_m = EstimateError(s.estimate_m, s.covariance_m2, *s.truth_m);
    if (s.height_error_m) s.height_error_m = std::abs(s.estimate_m.z() - s.truth_m->z());
  }
}

// The channel's snapshot PEB at the true position from the simulated paths' SINRs.
std::optional<double> SnapshotBound(const VariantContext& vc, const SourceStep& step) {
  if (step.paths.empty() || !step.truth_m.front()) return std::nullopt;
  std::vector<eval::RangeInformation> information;
  for (const auto& anchor_paths : step.paths) {
    for (const auto& truth : anchor_paths) {
      information.push_back({vc.channel_vas[truth.va_id].position_m, truth.sinr});
    }
  }
  return eval::PositionErrorBound(step.truth_m.front()->head<2>(), information, vc.sigma1_m);
}

void FinishHealth(const geometry::FloorPlan& plan, const eval::DivergenceRule& rule, RunRecord& record) {
  RunHealth& h = record.health;
  std::vector<double> sigmas;
  for (const auto& agent : record.agents) {
    for (const auto& s : agent.steps) sigmas.push_back(std::sqrt(s.covariance_m2.trace()));
  }
  if (!sigmas.empty()) {
    const double smallest = *std::min_element(sigmas.begin(), sigmas.end());
    const double largest = *std::max_element(sigmas.begin(), sigmas.end());
    h.covariance_growth = smallest > 0.0 ? largest / smallest : 1.0;
  }
  // Drift, told from the run itself (no truth needed): the filter's own uncertainty at the end
  // exceeds the distance the divergence rule calls diverged, or the estimate sits outside the
  // walls at the end, or most epochs found no measurement to use.
  std::vector<std::string> reasons;
  bool uncertain = false, outside = false;
  for (const auto& agent : record.agents) {
    if (agent.steps.empty()) continue;
    const auto& last = agent.steps.back();
    uncertain = uncertain || std::sqrt(last.covariance_m2.trace()) > rule.threshold_m;
    const Vec2 p = last.estimate_m.head<2>();
    outside = outside || (!plan.walls().empty() && (!plan.Encloses(p) || plan.InsideObstacle(p)));
  }
  if (uncertain) reasons.push_back(fmt::format("position uncertainty above {:g} m at the end", rule.threshold_m));
  if (outside) reasons.push_back("estimate outside the floor plan at the end");
  if (h.steps > h.deferred_steps && 2 * h.steps_without_association > h.steps - h.deferred_steps) reasons.push_back("no measurement used at most epochs");
  if (!h.started) reasons.push_back("never started: no epoch let the estimator start itself");
  h.drifted = !reasons.empty();
  for (std::size_t i = 0; i < reasons.size(); ++i) h.drift_reason += (i > 0 ? "; " : "") + reasons[i];
}

RunRecord RunOne(const VariantContext& vc, int variant, int group, int run, const std::vector<std::vector<double>>* bound) {
  const Experiment& e = *vc.experiment;
  RunRecord record;
  record.variant = variant;
  record.group = group;
  record.run = run;

  std::unique_ptr<EpochSource> source;
  AnchorChannelSource* anchor_source = nullptr;
  if (e.recording) {
    source = std::make_unique<RecordedSource>(*e.recording, e.epoch_window_s);
  } else if (vc.joint) {
    source = std::make_unique<LinkSource>(*vc.links, run);
  } else if (e.measurement_model == MeasurementModel::kAcoustic) {
    source = std::make_unique<AcousticSource>(e, group, run);
  } else if (e.measurement_model == MeasurementModel::kUwbTdoa) {
    source = std::make_unique<UwbTdoaSource>(e, group, run);
  } else {
    auto s = std::make_unique<AnchorChannelSource>(*vc.anchors, group, run);
    anchor_source = s.get();
    record.offset_m = s->offset_m();
    source = std::move(s);
  }

  const GivenPlan given = MakeGivenPlan(e, RunRng(e.seed, vc.joint ? 0 : group, run).Substream("plan"));
  const methods::World world = MakeWorld(vc, given, group);
  const auto estimator = e.method.create(world);
  for (const auto& name : world.agents) record.agents.push_back({name, {}, false, std::nullopt});

  // The start: the truth (possibly perturbed by the method's own start uncertainty), a given
  // point, or the estimator's own fix from the first epochs (also when the recording's truth is
  // in another frame, align_rigid).
  bool started = false;
  if (e.self_start) {
    // Every start comes from the data.
  } else if (const auto truth = source->TrueStart(); truth && !(e.recording && (e.start_m || e.align_rigid))) {
    std::vector<Vec3> start = *truth;
    const double sigma = e.method.start_sigma_m;
    if (anchor_source != nullptr) {
      core::Rng& init = anchor_source->init_rng();
      const Vec2 error(init.Normal(0.0, sigma), init.Normal(0.0, sigma));
      if (e.perturb_initial_position) start.front().head<2>() += error;
    } else if (e.perturb_initial_position && !e.recording && !vc.joint) {
      // The 3-D sources (acoustic, UWB TDOA): a draw per axis from the run's own start stream;
      // a planar method ignores the height's.
      core::Rng init = RunRng(e.seed, group, run).Substream("init");
      for (int axis = 0; axis < 3; ++axis) start.front()(axis) += init.Normal(0.0, sigma);
    }
    estimator->Initialize({source->start_s(), start});
    started = true;
  } else if (e.start_m) {
    estimator->Initialize({source->start_s(), {*e.start_m}});
    started = true;
  }

  std::set<int> visible_channel_ids;  // map truth: channel VAs seen along the run
  const bool walls = !given.plan.walls().empty();
  int step_index = -1;   // epochs processed
  int epoch_index = -1;  // epochs seen, those used to start included
  while (auto step = source->Next()) {
    record.simulate_s += step->simulate_s;
    ++epoch_index;
    if (!started) {
      const auto t0 = Clock::now();
      started = estimator->InitializeFromEpoch(step->epoch);
      record.estimate_s += Seconds(Clock::now() - t0);
      ++record.health.epochs_before_start;
      continue;  // the epoch that initialises is not processed again
    }
    ++step_index;
    const auto t0 = Clock::now();
    const methods::StepOutput out = estimator->Process(step->epoch);
    std::vector<methods::WallEstimate> wall_estimates;
    if (walls) wall_estimates = estimator->Walls();
    record.estimate_s += Seconds(Clock::now() - t0);

    // Path truth and the estimator's SINR of the same paths (anchor channels).
    std::map<int, std::size_t> path_by_channel_va;
    for (std::size_t a = 0; a < step->paths.size(); ++a) {
      for (const auto& truth : step->paths[a]) {
        path_by_channel_va[truth.va_id] = record.paths.size();
        visible_channel_ids.insert(truth.va_id);
        record.paths.push_back({step_index, static_cast<int>(a), truth.va_id, truth.order, truth.delay_s,
                                truth.amplitude, core::PowerRatioToDb(truth.sinr), std::nullopt});
      }
    }
    for (const int id : step->measured_channel_vas) visible_channel_ids.insert(id);
    for (const auto& estimate : out.sinr_estimates) {
      const auto va = vc.channel_va_by_key.find({estimate.anchor_index, estimate.walls});
      if (va == vc.channel_va_by_key.end()) continue;
      const auto path = path_by_channel_va.find(va->second);
      if (path == path_by_channel_va.end()) continue;  // associated a path the channel does not have now
      // SINR 0 ("zero or complex") is reported at -40 dB so that it stays a finite statistic.
      record.paths[path->second].estimated_sinr_db = core::PowerRatioToDb(std::max(estimate.sinr, 1e-4));
    }
    if (e.recording && step->truth_m.front() && vc.channel_vas.size() > 0) {
      // Recorded data with truth: the true VAs are those of the plan visible from the truth.
      for (std::size_t a = 0; a < e.anchors.size(); ++a) {
        for (const int id : geometry::VisibleVirtualAnchors(vc.channel_vas, static_cast<int>(a), e.plan,
                                                            step->truth_m.front()->head<2>())) {
          visible_channel_ids.insert(id);
        }
      }
    }

    std::optional<WallFrame> frame;
    if (!wall_estimates.empty()) frame = ComputeWallFrame(given.plan, wall_estimates, given.true_offset_m);
    const bool channel_truth = vc.anchors && vc.anchors->synthesizer;  // SINRs exist: CIR or range-level
    const std::optional<double> snapshot = bound == nullptr && channel_truth ? SnapshotBound(vc, *step) : std::nullopt;
    for (std::size_t a = 0; a < record.agents.size(); ++a) {
      TrackStep s;
      s.t_s = step->epoch.t_s;
      s.truth_m = a < step->truth_m.size() ? step->truth_m[a] : std::nullopt;
      s.estimate_m = out.agents[a].position_m;
      s.covariance_m2 = out.agents[a].covariance_m2;
      if (s.truth_m) s.error_m = EstimateError(s.estimate_m, s.covariance_m2, *s.truth_m);
      if (s.truth_m && out.agents[a].covariance_m2(2, 2) != 0.0) {
        s.height_error_m = std::abs(out.agents[a].position_m.z() - s.truth_m->z());
      }
      s.hdop = out.hdop;
      s.vdop = out.vdop;
      if (bound != nullptr) {
        const auto k = static_cast<std::size_t>(epoch_index + 1);
        if (k < bound->size() && a < (*bound)[k].size()) s.bound_m = (*bound)[k][a];
      } else {
        s.bound_m = snapshot;
      }
      if (frame && s.truth_m) {
        const Vec2 difference = s.estimate_m.head<2>() - s.truth_m->head<2>();
        s.relative_error_m = (difference - frame->translation_m).norm();
      }
      s.associations = out.associations;
      s.expected = out.expected;
      s.relocalized = out.relocalized;
      s.fixed = out.fixed;
      if (a == 0) s.los_labels = CountLosLabels(step->epoch, step->direct_stamps, out.los_stamps);
      record.agents[a].steps.push_back(s);
    }
    if (frame && given.biased >= 0) {
      if (!record.walls) record.walls.emplace();
      record.walls->biased_wall_error_m.push_back(frame->wall_error_m[static_cast<std::size_t>(given.biased)]);
    }
    if (frame) {
      if (!record.walls) record.walls.emplace();
      double sum = 0.0;
      for (const double err : frame->wall_error_m) sum += err * err;
      record.walls->rms_error_m = std::sqrt(sum / static_cast<double>(std::max<std::size_t>(1, frame->wall_error_m.size())));
    }

    RunHealth& h = record.health;
    ++h.steps;
    if (out.deferred) {
      ++h.deferred_steps;
    } else if (out.associations == 0) {
      ++h.steps_without_association;
    }
    if (out.relocalized) ++h.lost_track_episodes;
    if (out.rejected_update) ++h.rejected_updates;
    if (out.constrained) ++h.constrained_steps;
    for (const auto& agent : out.agents) {
      const Vec2 p = agent.position_m.head<2>();
      if (!e.plan.walls().empty() && (!e.plan.Encloses(p) || e.plan.InsideObstacle(p))) {
        ++h.steps_outside_plan;
        break;
      }
    }
  }
  record.health.out_of_order_records = source->out_of_order();
  if (e.align_rigid) {
    for (auto& agent : record.agents) AlignToTruth(agent);
  }

  for (auto& agent : record.agents) {
    std::vector<double> errors;
    for (const auto& s : agent.steps) {
      if (s.error_m) errors.push_back(*s.error_m);
    }
    agent.diverged = !errors.empty() && errors.size() == agent.steps.size() && eval::IsDiverged(errors, e.divergence);
    // No position at all is a failure too, when the truth could have judged one.
    if (!started && source->TrueStart()) agent.diverged = true;
  }
  record.health.started = started;
  record.map = estimator->Map();
  if (!record.map.empty() && vc.channel_vas.size() > 0 && (!e.recording || e.recording->has_truth())) {
    record.map_score = EvaluateMap(record.map, vc.channel_vas, visible_channel_ids, e.map_cutoff_m);
  }
  FinishHealth(e.plan, e.divergence, record);
  return record;
}

// The truth of a source that samples a 3-D trajectory (one entry per sample): its start, then
// every sample.
template <class Source>
void TruthOfSamples(const Source& source, methods::BoundInput& truth) {
  truth.t_s.push_back(source.start_s());
  truth.positions_m.push_back(*source.TrueStart());
  for (std::size_t k = 0; k < source.samples().size(); ++k) {
    truth.t_s.push_back(source.samples()[k].t_s);
    truth.positions_m.push_back({source.TruthAt(k)});
  }
}

}  // namespace

Vec2 RunOffset(const RunGrid& grid, int run) {
  const int cells = grid.nx * grid.ny;
  const int k = run % cells;
  const int ix = k % grid.nx;
  const int iy = k / grid.nx;
  return {(ix - 0.5 * (grid.nx - 1)) * grid.spacing_m, (iy - 0.5 * (grid.ny - 1)) * grid.spacing_m};
}

ExperimentResult RunExperiment(std::span<const Variant> variants, const Progress& progress) {
  const auto t_start = Clock::now();
  ExperimentResult result;
  std::vector<VariantContext> contexts(variants.size());
  struct Job {
    int variant = 0;
    int group = 0;
    int run = -1;  // -1: the variant-group's posterior bound
  };
  std::vector<Job> jobs;
  for (std::size_t v = 0; v < variants.size(); ++v) {
    const Experiment& e = variants[v].experiment;
    if (const auto problems = Validate(e); !problems.empty()) {
      throw std::invalid_argument("RunExperiment: " + problems.front());
    }
    VariantContext& vc = contexts[v];
    vc.experiment = &e;
    vc.joint = e.method.joint && !e.recording;
    vc.true_given_plan = TrueGivenWalls(e);
    VariantResult vr;
    if (!e.plan.walls().empty() && !vc.joint) {
      std::vector<Vec2> anchors_m;
      for (const auto& a : e.anchors) anchors_m.push_back(a.position_m.head<2>());
      vc.channel_vas = geometry::VirtualAnchorSet::Generate(anchors_m, e.plan, e.channel_max_order);
      for (const auto& va : vc.channel_vas.all()) vc.channel_va_by_key[{va.anchor_index, va.walls}] = va.id;
      vr.channel_vas = vc.channel_vas;
    }
    if (e.recording) {
      vc.groups = 1;
      vc.group_names = {"recorded"};
    } else if (vc.joint) {
      const GivenPlan given = MakeGivenPlan(e, core::Rng(e.seed));
      methods::World world;
      for (const auto& a : e.anchors) world.anchors.push_back({a.id, a.position_m});
      world.agents = SampleJointTruth(e).names;
      world.floor_plan = given.plan;
      world.channel = e.channel;
      vc.links = std::make_unique<LinkContext>(e, e.method.links(world));
      vc.groups = 1;
      vc.group_names = {"joint"};
    } else {
      vc.anchors = std::make_unique<AnchorChannelContext>(e);
      vc.groups = static_cast<int>(e.trajectories.size());
      for (const auto& t : e.trajectories) vc.group_names.push_back(t.name);
      if (vc.anchors->synthesizer) vc.sigma1_m = vc.anchors->synthesizer->pulse().range_sigma_at_unit_sinr_m(e.channel.medium.speed_mps);
    }
    vr.groups = vc.group_names;
    result.variants.push_back(std::move(vr));
    for (int g = 0; g < vc.groups; ++g) {
      if (!e.recording) jobs.push_back({static_cast<int>(v), g, -1});
      for (int r = 0; r < (e.recording ? 1 : e.runs); ++r) jobs.push_back({static_cast<int>(v), g, r});
    }
  }

  // The bounds first (each on run 0's truth), then the runs, which read them.
  std::map<std::pair<int, int>, std::vector<std::vector<double>>> bounds;
  std::vector<Job> bound_jobs, run_jobs;
  for (const auto& j : jobs) (j.run < 0 ? bound_jobs : run_jobs).push_back(j);
  std::vector<std::vector<std::vector<double>>> bound_results(bound_jobs.size());
  const int total = static_cast<int>(jobs.size());
  int done = 0;
  const auto counted = [&](int, int) {
    if (progress) progress(++done, total);
  };
  RunJobs(
      static_cast<int>(bound_jobs.size()), variants.empty() ? 0 : variants.front().experiment.threads,
      [&](int i) {
        const Job& j = bound_jobs[static_cast<std::size_t>(i)];
        const VariantContext& vc = contexts[static_cast<std::size_t>(j.variant)];
        const Experiment& e = *vc.experiment;
        methods::BoundInput truth;
        truth.true_plan = &e.plan;
        truth.true_known_plan = &vc.true_given_plan;
        if (vc.joint) {
          const JointTruth& jt = vc.links->truth;
          truth.t_s = jt.t_s;
          for (std::size_t n = 0; n < jt.t_s.size(); ++n) {
            std::vector<Vec3> at;
            for (const auto& agent : jt.positions_m) at.push_back(agent[n]);
            truth.positions_m.push_back(at);
          }
        } else if (e.measurement_model == MeasurementModel::kAcoustic) {
          // Run 0's trajectory, hand motion included: one entry per emission.
          TruthOfSamples(AcousticSource(e, j.group, 0), truth);
        } else if (e.measurement_model == MeasurementModel::kUwbTdoa) {
          TruthOfSamples(UwbTdoaSource(e, j.group, 0), truth);
        } else {
          // Run 0's trajectory: the start, then every epoch (the first at the start's time).
          AnchorChannelSource source(*vc.anchors, j.group, 0);
          truth.t_s.push_back(source.start_s());
          truth.positions_m.push_back(*source.TrueStart());
          const TrajectorySpec& t = e.trajectories[static_cast<std::size_t>(j.group)];
          for (const auto& s : geometry::SampleTrajectory(t.waypoints_m, t.speed_mps, t.dt_s, source.offset_m(), t.turn_radius_m, t.stops)) {
            truth.t_s.push_back(s.t_s);
            truth.positions_m.push_back({Vec3(s.position_m.x(), s.position_m.y(), t.height_m)});
          }
        }
        const GivenPlan given = MakeGivenPlan(e, RunRng(e.seed, vc.joint ? 0 : j.group, 0).Substream("plan"));
        const auto estimator = e.method.create(MakeWorld(vc, given, j.group));
        bound_results[static_cast<std::size_t>(i)] = estimator->PosteriorBound(truth);
      },
      counted);
  for (std::size_t i = 0; i < bound_jobs.size(); ++i) {
    if (!bound_results[i].empty()) bounds[{bound_jobs[i].variant, bound_jobs[i].group}] = std::move(bound_results[i]);
  }
  for (std::size_t v = 0; v < variants.size(); ++v) {
    const bool posterior = std::any_of(bounds.begin(), bounds.end(), [&](const auto& b) { return b.first.first == static_cast<int>(v); });
    result.variants[v].bound = variants[v].experiment.recording ? "" : posterior ? "posterior" : (contexts[v].anchors && contexts[v].anchors->synthesizer ? "snapshot" : "");
  }

  result.runs.resize(run_jobs.size());
  RunJobs(
      static_cast<int>(run_jobs.size()), variants.empty() ? 0 : variants.front().experiment.threads,
      [&](int i) {
        const Job& j = run_jobs[static_cast<std::size_t>(i)];
        const auto bound = bounds.find({j.variant, j.group});
        result.runs[static_cast<std::size_t>(i)] = RunOne(contexts[static_cast<std::size_t>(j.variant)], j.variant, j.group,
                                                          j.run, bound == bounds.end() ? nullptr : &bound->second);
      },
      counted);
  result.wall_s = Seconds(Clock::now() - t_start);
  return result;
}

}  // namespace mirage::pipeline
