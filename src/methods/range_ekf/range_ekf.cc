// SPDX-License-Identifier: MIT
#include "mirage/methods/range_ekf/range_ekf.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Cholesky>

#include "mirage/core/derived_defaults.h"
#include "mirage/estimation/ekf_update.h"
#include "mirage/estimation/gates/chi2.h"
#include "mirage/estimation/gates/chi2_gate.h"
#include "mirage/estimation/init/robust_position_fix.h"
#include "mirage/estimation/meas/range_to_point.h"

namespace mirage::methods::range_ekf {
namespace {

namespace blocks = estimation::blocks;

const estimation::BlockType& PositionType(bool planar) { return planar ? blocks::kPosition : blocks::kPosition3; }

}  // namespace

const core::OptionsDescriptor<RangeEkfOptions>& RangeEkfOptionsDescriptor() {
  using core::ValueRange;
  using O = RangeEkfOptions;
  static const auto descriptor = [] {
    core::OptionsDescriptor<O> d("methods::range_ekf::RangeEkfOptions");
    d.Choice(&O::mode,
             {.key = "mode",
              .doc = "3d: position and velocity in 3-D (anchors not coplanar, or coplanar with the agent below them); "
                     "planar: x, y at the world's known agent height (a tag worn at a fixed height), which makes the "
                     "height error zero."},
             {"3d", "planar"});
    d.Number(&O::range_sigma_m, {.key = "range_sigma_m",
                                 .unit = "m",
                                 .range = ValueRange::Above(0.0),
                                 .doc = "Range standard deviation. 0.1 m, typical of UWB two-way ranging; derived "
                                        "from the scenario's range noise.",
                                 .derived = core::RangeSigmas(1.0)});
    d.Number(&O::gate_chi2, {.key = "gate_chi2",
                             .range = ValueRange::AtLeast(0.0),
                             .doc = "Chi-square gate on one range's innovation (1 degree of freedom); 0 = off. 9 = 3 "
                                    "sigma of the innovation variance, 99.7 % of consistent ranges."});
    d.Number(&O::initial_position_sigma_m,
             {.key = "initial_position_sigma_m",
              .unit = "m",
              .range = ValueRange::Above(0.0),
              .doc = "Position standard deviation of a given start point. 0.5 m: a start known to the room's scale. A "
                     "self-initialised start uses its fix's covariance instead."});
    d.Number(&O::initial_velocity_sigma_mps, {.key = "initial_velocity_sigma_mps",
                                              .unit = "m/s",
                                              .range = ValueRange::Above(0.0),
                                              .doc = "Velocity standard deviation at the start, at rest. 1 m/s; "
                                                     "derived: the walker's speed in an unknown direction.",
                                              .derived = core::SpeedTimes(1.0)});
    d.Section(&O::motion, {.key = "motion", .doc = "Constant-velocity motion model of the agent."},
              estimation::ConstantVelocityOptionsDescriptor());
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const RangeEkfOptions& options) {
  return RangeEkfOptionsDescriptor().Validate(options);
}

RangeEkf::RangeEkf(const RangeEkfOptions& options, const World& world)
    : options_(options), world_(world), motion_(options.motion, options.mode == "planar" ? 2 : 3, 1) {
  if (const auto problems = Validate(options_); !problems.empty()) throw std::invalid_argument("range_ekf: " + problems.front());
  if (world_.anchors.empty()) throw std::invalid_argument("range_ekf: the scenario has no anchors");
}

double RangeEkf::AgentHeight() const { return world_.agent_height_m.value_or(0.0); }

void RangeEkf::Start(double t_s, const Vec3& position_m, const Eigen::Matrix3d& position_covariance_m2) {
  state_ = estimation::StartAtRest(planar() ? 2 : 3, t_s, position_m, position_covariance_m2, options_.initial_velocity_sigma_mps);
}

void RangeEkf::Initialize(const Prior& prior) {
  const double sp = options_.initial_position_sigma_m;
  Start(prior.t_s, prior.positions_m.front(), sp * sp * Eigen::Matrix3d::Identity());
}

std::optional<estimation::RobustPositionFix> RangeEkf::Fix(std::span<const core::RangeSet> sets) const {
  std::vector<estimation::AnchorCandidates> candidates;
  for (const auto& set : sets) {
    if (set.ranges.empty()) continue;
    auto& candidate = candidates.emplace_back();
    candidate.anchor_m = world_.anchors.at(static_cast<std::size_t>(set.anchor_index)).position_m;
    for (const auto& range : set.ranges) candidate.ranges_m.push_back(range.range_m);
  }
  // The gate of the fix's single residuals is the filter's own gate; with the gate off, 3 sigma.
  const double gate_chi2 = options_.gate_chi2 > 0.0 ? options_.gate_chi2 : 9.0;
  return estimation::FixPositionRobust(candidates, planar() ? std::optional(AgentHeight()) : std::nullopt,
                                       options_.range_sigma_m, gate_chi2);
}

bool RangeEkf::InitializeFromEpoch(const core::Epoch& epoch) {
  const auto fix = Fix(epoch.range_sets);
  if (!fix) return false;
  Start(epoch.t_s, fix->fix.position_m, fix->fix.covariance_m2);
  return true;
}

bool RangeEkf::Reacquire(std::span<const core::RangeSet> sets, int explained_by_track) {
  if (options_.gate_chi2 == 0.0) return false;  // nothing is ever gated out
  const auto robust = Fix(sets);
  // The fix counts only when every one of its ranges passed the gate and there were more of
  // them than unknowns, so that a wrong range would have shown in the residuals.
  if (!robust || !robust->redundant) return false;
  // It must explain more anchors than the track does: an anchor whose only range is a false peak
  // (its true one missed) is gated out by a track that is fine, and a fix that explains no more
  // anchors than the track is no evidence against it.
  if (robust->anchors_used <= explained_by_track) return false;
  const estimation::PositionFix& fix = robust->fix;
  const int d = planar() ? 2 : 3;
  // The track is lost when the prediction lies outside the fix's confidence region, combined
  // with its own, at the gate's tail probability carried to the position's dimension.
  const estimation::BlockKey position(PositionType(planar()), 0);
  const Eigen::VectorXd difference_m = state_.Mean(position) - fix.position_m.head(d);
  const Eigen::MatrixXd combined_m2 = state_.Covariance(position) + fix.covariance_m2.topLeftCorner(d, d);
  const double distance2 = difference_m.dot(combined_m2.ldlt().solve(difference_m));
  if (!(distance2 > estimation::Chi2ThresholdLike1Dof(options_.gate_chi2, d))) return false;
  Start(sets.front().t_s, fix.position_m, fix.covariance_m2);
  return true;
}

std::optional<estimation::MeasurementRow> RangeEkf::AnchorRow(const estimation::State& state, int anchor_index) const {
  const estimation::Block position = state.layout().At(estimation::BlockKey(PositionType(planar()), 0));
  return estimation::RangeToPointRow(state, position, world_.anchors.at(static_cast<std::size_t>(anchor_index)).position_m,
                                     AgentHeight(), options_.range_sigma_m * options_.range_sigma_m);
}

AgentEstimate RangeEkf::Estimate() const {
  const int d = planar() ? 2 : 3;
  const estimation::Block position = state_.layout().At(estimation::BlockKey(PositionType(planar()), 0));
  AgentEstimate out;
  out.position_m.head(d) = state_.mean().segment(position.mean_offset, d);
  if (planar()) out.position_m.z() = AgentHeight();
  out.covariance_m2.topLeftCorner(d, d) = state_.covariance().block(position.offset, position.offset, d, d);
  return out;
}

StepOutput RangeEkf::Process(const core::Epoch& epoch) {
  StepOutput out;
  // Event-driven: the range sets are in time order; those with one time stamp update together.
  std::size_t next = 0;
  while (next < epoch.range_sets.size()) {
    const double t_s = epoch.range_sets[next].t_s;
    estimation::Propagate(state_, std::max(t_s, state_.t_s()), {&motion_});
    std::vector<estimation::MeasurementRow> rows;
    std::vector<double> innovations;
    const std::size_t first = next;
    int gated_out = 0;
    for (; next < epoch.range_sets.size() && epoch.range_sets[next].t_s == t_s; ++next) {
      const core::RangeSet& set = epoch.range_sets[next];
      const auto row = AnchorRow(state_, set.anchor_index);
      if (!row) continue;
      // The anchor's range nearest to the prediction in innovation variances, if inside the gate.
      const double s_m2 = estimation::InnovationVariance(state_, *row);
      double best_nis = std::numeric_limits<double>::infinity();
      double best_nu = 0.0;
      for (const auto& r : set.ranges) {
        const double nu = r.range_m - row->predicted;
        if (nu * nu / s_m2 < best_nis) {
          best_nis = nu * nu / s_m2;
          best_nu = nu;
        }
      }
      if (!std::isfinite(best_nis) || !estimation::InsideChi2Gate(best_nu, s_m2, options_.gate_chi2)) {
        ++gated_out;
        continue;
      }
      rows.push_back(*row);
      innovations.push_back(best_nu);
    }
    // A range outside the gate is either a bad range or a sign that the track is lost; the
    // epoch's own fix tells which.
    if (gated_out > 0 && Reacquire(std::span(epoch.range_sets).subspan(first, next - first), static_cast<int>(rows.size()))) {
      out.relocalized = true;
      continue;
    }
    if (!rows.empty()) {
      const auto update = estimation::Update(state_, rows, innovations);
      if (update.applied) out.associations += static_cast<int>(rows.size());
      out.rejected_update = out.rejected_update || update.rejection == estimation::UpdateRejection::kNotPositiveDefinite;
    }
  }
  if (epoch.range_sets.empty()) estimation::Propagate(state_, std::max(epoch.t_s, state_.t_s()), {&motion_});
  out.agents.push_back(Estimate());
  return out;
}

std::vector<std::vector<double>> RangeEkf::PosteriorBound(const BoundInput& truth) const {
  if (truth.positions_m.empty()) return {};
  const int d = planar() ? 2 : 3;
  // The same start as a run with a known start point: the truth with the initial covariance.
  RangeEkf model(options_, world_);
  model.Initialize({truth.t_s.front(), {truth.positions_m.front().front()}});
  estimation::State state = model.state_;
  const estimation::Block position = state.layout().At(estimation::BlockKey(PositionType(planar()), 0));
  std::vector<std::vector<double>> bound;
  for (std::size_t k = 0; k < truth.positions_m.size(); ++k) {
    if (k > 0) {
      estimation::Propagate(state, truth.t_s[k], {&motion_});
      // Linearise at the truth: the bound's Fisher information is evaluated on the true path.
      Eigen::VectorXd at_truth = state.Mean(position.key);
      at_truth = truth.positions_m[k].front().head(d);
      state.SetMean(position.key, at_truth);
      std::vector<estimation::MeasurementRow> rows;
      for (std::size_t i = 0; i < world_.anchors.size(); ++i) {
        if (auto row = AnchorRow(state, static_cast<int>(i))) rows.push_back(*row);
      }
      const std::vector<double> zero(rows.size(), 0.0);
      estimation::Update(state, rows, zero);
    }
    bound.push_back({std::sqrt(state.Covariance(position.key).trace())});
  }
  return bound;
}

}  // namespace mirage::methods::range_ekf
