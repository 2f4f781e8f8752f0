// SPDX-License-Identifier: MIT
#include "mirage/methods/acoustic/acoustic_estimator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>

#include <Eigen/Cholesky>

#include "mirage/estimation/gates/chi2.h"
#include "mirage/estimation/meas/toa.h"
#include "mirage/estimation/robust/hampel.h"
#include "mirage/estimation/solvers/toa_nlls.h"
#include "mirage/methods/acoustic/path_association.h"

namespace mirage::methods::acoustic {

std::vector<ChosenStamp> ApplyTdoaBound(std::vector<ChosenStamp> chosen, std::span<const Anchor> receivers,
                                        double margin_m) {
  while (chosen.size() > 1) {
    std::vector<int> violations(chosen.size(), 0);
    int worst_count = 0;
    for (std::size_t i = 0; i < chosen.size(); ++i) {
      for (std::size_t j = i + 1; j < chosen.size(); ++j) {
        const double baseline_m = (receivers[static_cast<std::size_t>(chosen[i].receiver)].position_m -
                                   receivers[static_cast<std::size_t>(chosen[j].receiver)].position_m)
                                      .norm();
        if (std::abs(chosen[i].z_m - chosen[j].z_m) > baseline_m + margin_m) {
          worst_count = std::max({worst_count, ++violations[i], ++violations[j]});
        }
      }
    }
    if (worst_count == 0) break;
    // The stamp in most violations; among equals the latest (an echo or a delayed direct path
    // arrives late, never early).
    std::size_t worst = chosen.size();
    for (std::size_t i = 0; i < chosen.size(); ++i) {
      if (violations[i] != worst_count) continue;
      if (worst == chosen.size() || chosen[i].z_m > chosen[worst].z_m) worst = i;
    }
    chosen.erase(chosen.begin() + static_cast<long>(worst));
  }
  return chosen;
}

AcousticEstimator::AcousticEstimator(const AcousticOptions& options, const World& world)
    : options_(options), world_(world), rng_(1) {
  if (const auto problems = Validate(options_); !problems.empty()) throw std::invalid_argument("acoustic: " + problems.front());
  if (world_.anchors.size() < 3) throw std::invalid_argument("acoustic: at least 3 microphones are needed");
  c_mps_ = world_.channel.medium.speed_mps;
  height_m_ = world_.agent_height_m.value_or(0.0);
  for (const auto& anchor : world_.anchors) mics_m_.push_back(anchor.position_m);
  // The combinatorial method's sigma and TDOA bound are the method's own.
  los_ = options_.los;
  los_.range_sigma_m = options_.range_sigma_m;
  los_.tdoa_bound = options_.tdoa_bound_gate;
  los_.tdoa_bound_sigmas = options_.tdoa_bound_sigmas;
  if (options_.virtual_sender_false_alarm > 0.0) {
    virtual_sender_chi2_ = estimation::Chi2Quantile(1.0 - options_.virtual_sender_false_alarm, 2);
  }
  const auto& plan = world_.floor_plan;
  if (options_.estimator == "ground_echo") {
    ground_echo_.emplace(mics_m_, plan.floor_z_m(), c_mps_, options_.range_sigma_m, options_.emission_interval_s,
                         options_.clock_drift_ppm, options_.ground_echo,
                         std::isfinite(plan.ceiling_z_m()) ? std::optional<double>(plan.ceiling_z_m()) : std::nullopt);
  }
  if (options_.echo_order > 0 && !plan.walls().empty() && std::isfinite(plan.ceiling_z_m())) {
    reflectors_ = geometry::ReflectorsFromPlan(plan);
  }
  // The start's search (multipath_fix.h) with the filters' noise, echoes and association model.
  start_search_.range_sigma_m = options_.range_sigma_m;
  start_search_.echo_order = reflectors_.empty() ? 0 : options_.echo_order;
  start_search_.detection_probability = options_.detection_probability;
  start_search_.clutter_density_per_m = options_.clutter_density_per_m;
  start_search_.irls = options_.irls;
  start_search_.irls.robust = true;  // the search's refinement is robust whatever the filter's update
}

Vec3 AcousticEstimator::PositionOf(const Eigen::VectorXd& x) const {
  if (planar()) return {x(0), x(1), height_m_};
  return x.head<3>();
}

double AcousticEstimator::TdoaBoundMargin() const {
  return options_.tdoa_bound_sigmas * std::sqrt(2.0) * options_.range_sigma_m;
}

std::vector<ChosenStamp> AcousticEstimator::EarliestStamps(const StampsByReceiver& stamps) const {
  std::vector<ChosenStamp> earliest;
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    if (!stamps[i].empty()) earliest.push_back({static_cast<int>(i), *std::min_element(stamps[i].begin(), stamps[i].end())});
  }
  if (options_.tdoa_bound_gate) earliest = ApplyTdoaBound(std::move(earliest), world_.anchors, TdoaBoundMargin());
  return earliest;
}

AgentEstimate AcousticEstimator::Estimate() const {
  AgentEstimate out;
  const int d = dim();
  out.position_m = Position();
  out.covariance_m2.topLeftCorner(d, d) = P_.topLeftCorner(d, d);
  return out;
}

void AcousticEstimator::Start(const Vec3& position_m, double position_sigma_m,
                              const std::optional<Eigen::Matrix4d>& fix_covariance) {
  const int d = dim();
  const int n = 2 * d + 2 + (options_.inertial ? 2 : 0);
  x_ = Eigen::VectorXd::Zero(n);
  x_.head(d) = position_m.head(d);
  P_ = Eigen::MatrixXd::Zero(n, n);
  P_.topLeftCorner(d, d).diagonal().setConstant(position_sigma_m * position_sigma_m);
  P_.block(d, d, d, d).diagonal().setConstant(options_.initial_velocity_sigma_mps * options_.initial_velocity_sigma_mps);
  // b is set by the first emission: its variance covers the position's effect on the ranges
  // plus the stamps' noise.
  P_(2 * d, 2 * d) = position_sigma_m * position_sigma_m + options_.range_sigma_m * options_.range_sigma_m;
  if (fix_covariance) {
    // A fix of the first emission (multipath_fix.h): its position, b and their correlation.
    P_.topLeftCorner(d, d) = fix_covariance->topLeftCorner(d, d);
    P_.block(0, 2 * d, d, 1) = fix_covariance->block(0, 3, d, 1);
    P_.block(2 * d, 0, 1, d) = fix_covariance->block(3, 0, 1, d);
    P_(2 * d, 2 * d) = (*fix_covariance)(3, 3);
  }
  const double iota_sigma_m = c_mps_ * options_.emission_interval_s * options_.clock_drift_ppm * 1e-6;
  P_(2 * d + 1, 2 * d + 1) = std::max(iota_sigma_m * iota_sigma_m, 1e-12);
  if (options_.inertial) {
    // The clone starts as a copy of the position (fully correlated with it).
    x_.segment<2>(clone_offset()) = x_.head<2>();
    P_.block(clone_offset(), 0, 2, n) = P_.block(0, 0, 2, n);
    P_.block(0, clone_offset(), n, 2) = P_.block(0, 0, n, 2);
    P_.block<2, 2>(clone_offset(), clone_offset()) = P_.topLeftCorner<2, 2>();
  }
  started_ = true;
  have_emission_ = false;
  confirmed_ = false;
  coasting_ = false;
  first_search_s_.reset();
  search_whole_plan_ = false;
  // The dead reckoning's heading is taken again from this track's velocity (after a restart the
  // old one came from a track that ran away, and the samples while lost were not integrated).
  pdr_.reset();
  pdr_started_ = false;
}

void AcousticEstimator::Initialize(const Prior& prior) {
  Start(prior.positions_m.front(), options_.initial_position_sigma_m);
  last_ = Estimate();
}

bool AcousticEstimator::InitializeFromEpoch(const core::Epoch& epoch) {
  // The snapshot estimators need no start: the first epoch with a fix is their start.
  if (!filter()) return Process(epoch).fixed;
  // The filters: a fix from all the stamps anywhere the sender may be.
  return StartFromStamps(epoch, SearchRegion(false)) == StartOutcome::kStarted;
}

MultipathSearchRegion AcousticEstimator::SearchRegion(bool around_prior, double elapsed_s) const {
  // Horizontally: the floor plan's bounds; without one, the microphones' footprint (ceiling
  // microphones cover the area they serve); around the prior, its 3 sigma box inside them.
  Vec2 lo = mics_m_.front().head<2>(), hi = lo;
  for (const auto& m : mics_m_) {
    lo = lo.cwiseMin(m.head<2>());
    hi = hi.cwiseMax(m.head<2>());
  }
  const bool plan = !world_.floor_plan.walls().empty();
  if (plan) std::tie(lo, hi) = world_.floor_plan.Bounds();
  MultipathSearchRegion region;
  region.plan = &world_.floor_plan;
  region.lo_m.head<2>() = lo;
  region.hi_m.head<2>() = hi;
  if (around_prior) {  // the state exists: the filter has started at its prior
    // The prior moved on by the motion model over the time the start has waited (elapsed_s):
    // the velocity's spread widens the box, so a sender that walks on while the start waits
    // stays inside it.
    const int d = dim();
    const Eigen::VectorXd centre_m = x_.head(d) + x_.segment(d, d) * elapsed_s;
    const Eigen::VectorXd sigma_m =
        (P_.diagonal().head(d) + P_.diagonal().segment(d, d) * elapsed_s * elapsed_s).cwiseSqrt();
    region.lo_m.head(d) = centre_m - 3.0 * sigma_m;
    region.hi_m.head(d) = centre_m + 3.0 * sigma_m;
    if (plan) {
      region.lo_m.head<2>() = region.lo_m.head<2>().cwiseMax(lo);
      region.hi_m.head<2>() = region.hi_m.head<2>().cwiseMin(hi);
    }
  }
  if (planar()) {
    region.lo_m.z() = region.hi_m.z() = height_m_;
    return region;
  }
  // In height: between the floor and the highest a sender is carried, below the ceiling (the
  // whole of it when the prior's box leaves nothing).
  const double floor_z_m = world_.floor_plan.floor_z_m();
  const double top_m = HighestSender_m();
  region.lo_m.z() = around_prior ? std::clamp(region.lo_m.z(), floor_z_m, top_m) : floor_z_m;
  region.hi_m.z() = around_prior ? std::clamp(region.hi_m.z(), floor_z_m, top_m) : top_m;
  if (!(region.hi_m.z() > region.lo_m.z())) {
    region.lo_m.z() = floor_z_m;
    region.hi_m.z() = top_m;
  }
  return region;
}

AcousticEstimator::StartOutcome AcousticEstimator::StartFromStamps(const core::Epoch& epoch,
                                                                   const MultipathSearchRegion& region) {
  const MultipathFix fix = FixFromAllStamps(reflectors_, mics_m_, Stamps(epoch, epoch.t_s), region, start_search_);
  if (!fix.found) {
    pending_start_.reset();
    return StartOutcome::kNoFix;
  }
  // One emission's best explanation can be a wrong position whose chance coincidences outweigh
  // the sender's (dense echoes near a corner); two emissions agree only at the sender. The start
  // waits for the next emission's fix, which must follow the first: their emission times an
  // integer number of intervals apart (the clock drift and the offsets' sigmas as tolerance), and
  // the positions no farther apart than the velocity prior's 3 sigma over that time plus 3 sigma
  // of the fixes.
  const PendingStart current{epoch.t_s + fix.offset_m / c_mps_, fix};
  if (!pending_start_ || !Follows(*pending_start_, current)) {
    pending_start_ = current;
    return StartOutcome::kPending;
  }
  const PendingStart first = *pending_start_;
  pending_start_.reset();
  Start(fix.position_m, options_.initial_position_sigma_m, fix.covariance);
  // The velocity's mean from the two fixes (its sigma stays the prior's).
  x_.segment(dim(), dim()) = (fix.position_m - first.fix.position_m).head(dim()) / (current.emission_s - first.emission_s);
  t_ref_s_ = current.emission_s;  // b = 0 at this emission
  have_emission_ = true;
  (void)Increment(epoch);  // starts the dead reckoning's interval
  return StartOutcome::kStarted;
}

bool AcousticEstimator::Follows(const PendingStart& first, const PendingStart& second) const {
  const double elapsed_s = second.emission_s - first.emission_s;
  const double intervals = std::round(elapsed_s / options_.emission_interval_s);
  if (intervals < 1.0) return false;
  const double offset_var_m2 = first.fix.covariance(3, 3) + second.fix.covariance(3, 3) +
                               2.0 * std::pow(c_mps_ * options_.emission_jitter_s, 2);
  const double timing_tolerance_s =
      3.0 * std::sqrt(offset_var_m2) / c_mps_ + intervals * options_.emission_interval_s * options_.clock_drift_ppm * 1e-6;
  if (std::abs(elapsed_s - intervals * options_.emission_interval_s) > timing_tolerance_s) return false;
  const int d = dim();
  const double position_var_m2 = first.fix.covariance.topLeftCorner(d, d).trace() + second.fix.covariance.topLeftCorner(d, d).trace();
  const double reach_m = 3.0 * options_.initial_velocity_sigma_mps * elapsed_s + 3.0 * std::sqrt(position_var_m2);
  return (second.fix.position_m - first.fix.position_m).head(d).norm() <= reach_m;
}

std::vector<std::vector<double>> AcousticEstimator::PosteriorBound(const BoundInput& truth) const {
  if (!filter() || options_.inertial || truth.positions_m.empty()) return {};
  const int d = dim();
  AcousticOptions plain = options_;
  plain.estimator = "ekf";  // every row at its true noise: weights 1
  AcousticEstimator model(plain, world_);
  model.Initialize({truth.t_s.front(), {truth.positions_m.front().front()}});
  std::vector<std::vector<double>> bound;
  for (std::size_t k = 0; k < truth.positions_m.size(); ++k) {
    if (k > 1) {  // the first emission sets b; the filter predicts from the second on
      const double intervals = std::round((truth.t_s[k] - truth.t_s[k - 1]) / options_.emission_interval_s);
      model.Predict(std::max(1, static_cast<int>(intervals)));
    }
    if (k > 0) {
      // The filter's own update linearised at the truth, every predicted path of every
      // microphone a row (its stamp at the prediction: the innovations do not enter P).
      model.x_.head(d) = truth.positions_m[k].front().head(d);
      const Vec3 sender_m = model.Position();
      std::vector<Row> rows;
      for (std::size_t i = 0; i < mics_m_.size(); ++i) {
        for (const auto& path : PredictPaths(reflectors_, sender_m, mics_m_[i], model.x_(2 * d), options_.echo_order)) {
          rows.push_back({static_cast<int>(i), path.predicted_m, path});
        }
      }
      if (const auto update = model.UpdateWithRows(rows, std::nullopt, model.x_)) model.P_ = update->P;
    }
    bound.push_back({std::sqrt(model.P_.topLeftCorner(d, d).trace())});
  }
  return bound;
}

StampsByReceiver AcousticEstimator::Stamps(const core::Epoch& epoch, double t_ref_s) const {
  StampsByReceiver out(world_.anchors.size());
  for (const auto& record : epoch.toas) {
    auto& list = out.at(static_cast<std::size_t>(record.receiver_index));
    for (const double toa_s : record.toa_s) list.push_back(c_mps_ * (toa_s - t_ref_s));
  }
  return out;
}

std::optional<double> AcousticEstimator::ImpliedEmission(const core::Epoch& epoch, const Vec3& position_m) const {
  std::vector<double> emissions_s;
  for (const auto& record : epoch.toas) {
    if (record.toa_s.empty()) continue;
    const double first_s = *std::min_element(record.toa_s.begin(), record.toa_s.end());
    const Vec3& mic = world_.anchors.at(static_cast<std::size_t>(record.receiver_index)).position_m;
    emissions_s.push_back(first_s - (position_m - mic).norm() / c_mps_);
  }
  if (emissions_s.empty()) return std::nullopt;
  return estimation::Median(emissions_s);
}

void AcousticEstimator::Predict(int intervals) {
  const int d = dim();
  const int n = static_cast<int>(x_.size());
  if (options_.inertial) {
    // The clone takes the last emission's horizontal position (a copy: T x, T P T^T).
    Eigen::MatrixXd T = Eigen::MatrixXd::Identity(n, n);
    T.block<2, 2>(clone_offset(), clone_offset()).setZero();
    T.block<2, 2>(clone_offset(), 0).setIdentity();
    x_ = T * x_;
    P_ = T * P_ * T.transpose();
  }
  const double dt_s = intervals * options_.emission_interval_s;
  Eigen::MatrixXd F = Eigen::MatrixXd::Identity(n, n);
  F.block(0, d, d, d).diagonal().setConstant(dt_s);
  F(2 * d, 2 * d + 1) = intervals;  // b gains iota per interval
  Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(n, n);
  // G Q G^T of Eq. 5.33-5.34: a constant acceleration over the step, white between steps.
  const double qa = options_.motion.accel_sigma_mps2 * options_.motion.accel_sigma_mps2;
  Q.topLeftCorner(d, d).diagonal().setConstant(qa * std::pow(dt_s, 4) / 4.0);
  Q.block(0, d, d, d).diagonal().setConstant(qa * std::pow(dt_s, 3) / 2.0);
  Q.block(d, 0, d, d).diagonal().setConstant(qa * std::pow(dt_s, 3) / 2.0);
  Q.block(d, d, d, d).diagonal().setConstant(qa * dt_s * dt_s);
  const double jitter_m = c_mps_ * options_.emission_jitter_s;
  Q(2 * d, 2 * d) = intervals * jitter_m * jitter_m;
  x_ = F * x_;
  P_ = F * P_ * F.transpose() + Q;
  t_ref_s_ += intervals * options_.emission_interval_s;
}

std::optional<core::PositionIncrement> AcousticEstimator::Increment(const core::Epoch& epoch) {
  if (!options_.inertial) return std::nullopt;
  if (!epoch.increments.empty()) {
    // Dead-reckoning records: their sum over the epoch (one per emission in simulations).
    core::PositionIncrement sum = epoch.increments.front();
    for (std::size_t i = 1; i < epoch.increments.size(); ++i) {
      sum.delta_m += epoch.increments[i].delta_m;
      sum.covariance_m2 += epoch.increments[i].covariance_m2;
      sum.t_s = epoch.increments[i].t_s;
    }
    return sum;
  }
  if (epoch.imus.empty()) return std::nullopt;
  if (!pdr_started_) {
    // The phone's heading in the hall's frame is unknown to the IMU (no magnetometer indoors,
    // Sec. 5.2): take it from the track's velocity once that is well determined.
    const int d = dim();
    const Vec2 v = x_.segment<2>(d);
    const double sv = std::sqrt(P_.block<2, 2>(d, d).trace());
    if (v.norm() < options_.initial_velocity_sigma_mps || sv > v.norm() / 3.0) return std::nullopt;
    pdr_.emplace(options_.pdr);
    pdr_->Reset(epoch.imus.front().t_s, std::atan2(v.y(), v.x()), sv / v.norm());
    pdr_started_ = true;
  }
  for (const auto& sample : epoch.imus) pdr_->Add(sample);
  const auto increment = pdr_->TakeIncrement();
  core::PositionIncrement out;
  out.t_s = increment.t_to_s;
  out.t_from_s = increment.t_from_s;
  out.delta_m = increment.delta_m;
  out.covariance_m2 = increment.covariance_m2;
  return out;
}

std::vector<AcousticEstimator::Row> AcousticEstimator::AssociateRows(const StampsByReceiver& stamps,
                                                                      const Eigen::VectorXd& x_lin,
                                                                      const Eigen::MatrixXd& P_lin, int echo_order) const {
  const int d = dim();
  const Vec3 sender_m = PositionOf(x_lin);
  const double r_m2 = options_.range_sigma_m * options_.range_sigma_m;
  // Per microphone its predicted paths (direct, and echoes to echo_order) and the stamps paired
  // with them (path_association.h).
  std::vector<Row> echo_rows;
  std::vector<ChosenStamp> direct;
  std::vector<PredictedPath> direct_paths(stamps.size());
  const PathStateLayout layout{.position_columns = d, .offset_column = 2 * d};
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    if (stamps[i].empty()) continue;
    for (const auto& a : AssociateMicrophone(reflectors_, sender_m, world_.anchors[i].position_m, x_lin(2 * d), echo_order,
                                             stamps[i], P_lin, layout, r_m2, options_.detection_probability,
                                             options_.clutter_density_per_m)) {
      const double z_m = stamps[i][static_cast<std::size_t>(a.stamp)];
      if (options_.gate_chi2 > 0.0) {
        const double nu = z_m - a.path.predicted_m;
        if (nu * nu > options_.gate_chi2 * a.innovation_var_m2) continue;
      }
      if (a.path.order == 0) {
        direct.push_back({static_cast<int>(i), z_m});
        direct_paths[i] = a.path;
      } else {
        echo_rows.push_back({static_cast<int>(i), z_m, a.path});
      }
    }
  }
  if (options_.tdoa_bound_gate) {
    // The bound holds between direct paths only.
    direct = ApplyTdoaBound(std::move(direct), world_.anchors, TdoaBoundMargin());
  }
  std::vector<Row> rows;
  for (const auto& c : direct) rows.push_back({c.receiver, c.z_m, direct_paths[static_cast<std::size_t>(c.receiver)]});
  rows.insert(rows.end(), echo_rows.begin(), echo_rows.end());
  return rows;
}

double AcousticEstimator::HighestSender_m() const {
  return std::min(world_.floor_plan.ceiling_z_m(), world_.floor_plan.floor_z_m() + options_.ground_echo.max_sender_height_m);
}

bool AcousticEstimator::Outside(const Eigen::VectorXd& x, const Eigen::MatrixXd& P) const {
  const geometry::FloorPlan& plan = world_.floor_plan;
  if (plan.walls().empty()) return false;
  const int d = dim();
  const Vec3 p = PositionOf(x);
  // 3 sigma of the position in every direction: the track stays while its centre or a corner or
  // edge midpoint of that box lies inside the plan (a track near a wall, a noisy update).
  const Eigen::VectorXd sigma_m = P.diagonal().head(d).cwiseSqrt();
  bool enclosed = plan.Encloses(p.head<2>());
  for (int dx = -1; dx <= 1 && !enclosed; ++dx) {
    for (int dy = -1; dy <= 1 && !enclosed; ++dy) {
      enclosed = plan.Encloses(p.head<2>() + 3.0 * Vec2(dx * sigma_m(0), dy * sigma_m(1)));
    }
  }
  if (!enclosed) return true;
  if (d == 3) {
    // The heights the start searches.
    const double margin_z_m = 3.0 * sigma_m(2);
    return p.z() < plan.floor_z_m() - margin_z_m || p.z() > HighestSender_m() + margin_z_m;
  }
  return false;
}

std::vector<AcousticEstimator::Row> AcousticEstimator::FirstArrivalRows(const StampsByReceiver& stamps,
                                                                         const Eigen::VectorXd& x_lin) const {
  const int d = dim();
  const Vec3 sender_m = PositionOf(x_lin);
  std::vector<Row> rows;
  for (const auto& c : EarliestStamps(stamps)) {
    const auto paths = PredictPaths({}, sender_m, world_.anchors[static_cast<std::size_t>(c.receiver)].position_m, x_lin(2 * d), 0);
    if (!paths.empty()) rows.push_back({c.receiver, c.z_m, paths.front()});
  }
  return rows;
}

std::optional<estimation::IrlsResult> AcousticEstimator::UpdateWithRows(const std::vector<Row>& rows,
                                                                       const std::optional<core::PositionIncrement>& increment,
                                                                       const Eigen::VectorXd& x_lin, bool robust) const {
  const int d = dim();
  const int n = static_cast<int>(x_.size());
  const long m = static_cast<long>(rows.size()) + (increment ? 2 : 0);
  if (m == 0) return std::nullopt;
  // The rows z = |path| + b linearised at x_lin, d z / d S = the path's d_sender, d z / d b = 1,
  // as innovations against the prediction x_: y = z - h(x_lin) + H (x_lin - x_) (iterated EKF).
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(m, n);
  Eigen::VectorXd innovation = Eigen::VectorXd::Zero(m);
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(m, m);
  long r = 0;
  for (const auto& row : rows) {
    H.row(r).head(d) = row.path.d_sender.head(d).transpose();
    H(r, 2 * d) = 1.0;
    innovation(r) = row.z_m - row.path.predicted_m;
    R(r, r) = options_.range_sigma_m * options_.range_sigma_m;
    ++r;
  }
  if (increment) {
    // S_xy - S_prev = delta (Eq. 5.38-5.39 on the clone); linear.
    H.block(r, 0, 2, 2).setIdentity();
    H.block(r, clone_offset(), 2, 2) = -Eigen::Matrix2d::Identity();
    innovation.segment<2>(r) = increment->delta_m - (x_lin.head<2>() - x_lin.segment<2>(clone_offset()));
    // A floor keeps R positive definite for an increment of zero length and zero covariance.
    R.block<2, 2>(r, r) = increment->covariance_m2 + 1e-6 * Eigen::Matrix2d::Identity();
  }
  innovation += H * (x_lin - x_);
  estimation::IrlsOptions irls = options_.irls;
  irls.robust = robust && options_.estimator == "rekf";
  return estimation::IrlsUpdate(P_, H, innovation, R, irls);
}

AcousticEstimator::VirtualSenderCheck AcousticEstimator::CheckVirtualSender(const std::vector<Row>& rows,
                                                                          const core::PositionIncrement& increment,
                                                                          const estimation::IrlsResult& update) const {
  const int d = dim();
  VirtualSenderCheck out;
  const Eigen::VectorXd& dx = update.dx;
  // The update's position against the dead reckoning from the last emission's posterior (the
  // clone as predicted, not as the update moved it): S - (S_prev + delta) with covariance
  // P_prev + Q_delta (Eq. 5.38-5.39 as a test).
  const Vec2 miss_m = increment.delta_m - ((x_ + dx).head<2>() - x_.segment<2>(clone_offset()));
  const Eigen::Matrix2d cov_m2 = increment.covariance_m2 + P_.block<2, 2>(clone_offset(), clone_offset()) +
                                 1e-6 * Eigen::Matrix2d::Identity();
  out.breaks_dead_reckoning = miss_m.dot(cov_m2.ldlt().solve(miss_m)) > virtual_sender_chi2_;
  // "Most" stamps: more than half, and more than the unknowns (position and b) so that their
  // agreement is evidence.
  if (static_cast<int>(rows.size()) < d + 2) return out;
  const auto most = [&](int count) { return 2 * count > static_cast<int>(rows.size()) && count >= d + 2; };
  out.prediction_exact = most(CountExplained(rows));
  out.update_exact = most(CountExplained(rows, &dx));
  return out;
}

int AcousticEstimator::CountExplained(const std::vector<Row>& rows, const Eigen::VectorXd* dx) const {
  const int d = dim();
  const double gate_m = 3.0 * options_.range_sigma_m;
  int count = 0;
  for (const auto& row : rows) {
    // The path's length after the step dx, to first order about the linearisation point.
    const double moved_m = dx != nullptr ? row.path.d_sender.head(d).dot(dx->head(d)) + (*dx)(2 * d) : 0.0;
    count += std::abs(row.z_m - row.path.predicted_m - moved_m) <= gate_m ? 1 : 0;
  }
  return count;
}

bool AcousticEstimator::DecideCoast(const std::optional<core::PositionIncrement>& increment,
                                    const std::vector<Row>& rows, const estimation::IrlsResult& update, double t_s) {
  if (!increment) return coasting_;  // no dead reckoning to test against: a coast goes on
  const VirtualSenderCheck check = CheckVirtualSender(rows, *increment, update);
  if (coasting_) {
    const bool coast = check.breaks_dead_reckoning || !check.update_exact;
    if (!coast) verified_s_ = t_s;
    return coast;
  }
  if (t_s - verified_s_ > options_.virtual_sender_onset_s + options_.emission_interval_s) confirmed_ = false;
  if (confirmed_ && check.breaks_dead_reckoning && !check.prediction_exact) return true;
  if (check.prediction_exact && !check.breaks_dead_reckoning) {
    confirmed_ = true;  // the stamps and the dead reckoning both agree with the track
    verified_s_ = t_s;
  } else if (check.update_exact) {
    confirmed_ = false;  // a correction
  }
  return false;
}

StepOutput AcousticEstimator::Filter(const core::Epoch& epoch) {
  StepOutput out;
  const int d = dim();
  const int n = static_cast<int>(x_.size());
  if (!have_emission_) {
    // The first emission: with b unknown and a prior wider than the echoes' spacing, pairing
    // stamps with paths at the prior mean is a guess. With the echoes predicted, the fix from all
    // stamps inside the prior's 3 sigma box (multipath_fix.h) starts the filter. Without them
    // every echo is a direct path of some other position, and such a search finds those as
    // readily: the thesis's start stands (the prior mean, the emission the earliest stamps imply).
    if (!first_search_s_) first_search_s_ = epoch.t_s;
    const StartOutcome start =
        reflectors_.empty() ? StartOutcome::kNoFix
                            : StartFromStamps(epoch, search_whole_plan_ ? SearchRegion(false)
                                                                        : SearchRegion(true, epoch.t_s - *first_search_s_));
    if (start != StartOutcome::kNoFix || search_whole_plan_) {
      // A lost track waits for a start from the stamps: its state is known to be wrong.
      // Started from the fixes, or waiting for the next emission's to confirm: then the prior
      // stands, which is no fix of this emission.
      out.expected = static_cast<int>(world_.anchors.size());
      out.fixed = start == StartOutcome::kStarted;
      out.agents.push_back(Estimate());
      return out;
    }
    const auto emission_s = ImpliedEmission(epoch, Position());
    if (!emission_s) {
      out.agents.push_back(Estimate());
      return out;
    }
    t_ref_s_ = *emission_s;
    x_(2 * d) = 0.0;
    have_emission_ = true;
    (void)Increment(epoch);  // starts the dead reckoning's interval
  } else {
    // Elapsed intervals (Eq. 3.39) between the last emission and the one these stamps imply.
    const double last_emission_s = t_ref_s_ + x_(2 * d) / c_mps_;
    const auto emission_s = ImpliedEmission(epoch, Position());
    const double t_new_s = emission_s.value_or(epoch.t_s);
    const int intervals = std::max(1, static_cast<int>(std::lround((t_new_s - last_emission_s) / options_.emission_interval_s)));
    Predict(intervals);
  }

  const StampsByReceiver stamps = Stamps(epoch, t_ref_s_);
  const auto increment = have_emission_ ? Increment(epoch) : std::nullopt;
  // Iterated association (an iterated EKF whose data association is redone at each iterate): the
  // first pass pairs each microphone's earliest stamp with its direct path at the prediction
  // (the shortest path arrives first); every later pass pairs the stamps with the direct paths and
  // the echoes at the last pass's estimate, whose covariance makes the gates and the nearest
  // neighbours sharp. A prediction off by a step of unknown velocity is farther from the truth
  // than the echoes are from each other; an estimate is not.
  struct Outcome {
    std::optional<estimation::IrlsResult> update;
    std::vector<Row> rows;  // the update's stamp rows
    bool had_rows = false;
    int explained = 0;  // stamps within 3 sigma of a predicted path at the final estimate
    double prior_d2 = 0.0;  // the estimate's squared Mahalanobis distance from the prediction
  };
  const int passes = reflectors_.empty() ? 1 : 1 + kAssociationPasses;
  Eigen::LLT<Eigen::MatrixXd> prior_llt;
  if (passes > 1) prior_llt.compute(P_);
  const auto run_passes = [&](bool first_arrival) {
    Outcome o;
    Eigen::VectorXd x_lin = x_;
    Eigen::MatrixXd P_lin = P_;
    std::vector<std::pair<int, double>> last_pairs;
    for (int pass = first_arrival ? 0 : 1; pass < passes; ++pass) {
      auto rows = pass == 0 && passes > 1 ? FirstArrivalRows(stamps, x_lin)
                                          : AssociateRows(stamps, x_lin, P_lin, pass == 0 ? 0 : options_.echo_order);
      o.had_rows = o.had_rows || !rows.empty() || increment.has_value();
      std::vector<std::pair<int, double>> pairs;
      for (const auto& row : rows) pairs.emplace_back(row.receiver, row.z_m);
      if (pass > 1 && pairs == last_pairs) break;  // the association settled: the last update stands
      last_pairs = pairs;
      auto candidate = UpdateWithRows(rows, increment, x_lin);
      if (!candidate) break;
      o.update = std::move(candidate);
      o.rows = std::move(rows);
      x_lin = x_ + o.update->dx;
      P_lin = o.update->P;
    }
    if (o.update && passes > 1) {
      o.explained = CountExplained(AssociateRows(stamps, x_lin, P_lin, options_.echo_order));
      o.prior_d2 = o.update->dx.dot(prior_llt.solve(o.update->dx));
    }
    return o;
  };
  // With echoes the association can lock onto a wrong position that a subset of the earliest
  // stamps supports (two blocked microphones among six leave 3 unknowns ambiguous). The passes
  // run a second time from the prediction itself, and the outcome whose estimate explains more
  // stamps (the likelihood of every stamp, not only the earliest) is kept; when both explain as
  // many, the prior decides: the one nearer the prediction (Mahalanobis). The tie is the
  // virtual-sender case of Sec. 5.2: facing a wall, every stamp is that wall's echo, which fits
  // the mirrored sender as direct paths and the true sender as echoes equally well. (A finite
  // trade-off, ln(P_d / (lambda sqrt(2 pi) sigma)) per stamp against half the squared distance,
  // lost more runs in both hold-outs with the derived clutter density: docs/methods/acoustic.md.)
  Outcome outcome = run_passes(true);
  if (passes > 1) {
    Outcome other = run_passes(false);
    const bool better = other.explained > outcome.explained ||
                        (other.explained == outcome.explained && other.prior_d2 < outcome.prior_d2);
    if (other.update && (!outcome.update || better)) outcome = std::move(other);
  }
  // Sec. 5.2's virtual sender, for the thesis's filter (direct paths only) with dead reckoning:
  // facing a wall, every stamp is that wall's echo and fits the sender mirrored behind it as
  // consistently as direct paths fit the sender. Such stamps are correlated outliers, which no
  // per-row weight rejects (ten agreeing stamps outvote the increment's two rows): the event is
  // one of the whole emission. A confirmed track whose update breaks the dead reckoning beyond
  // the chi-square quantile at 1 - virtual_sender_false_alarm while its prediction does not
  // explain the stamps (a mirror never fits the prediction; a dead-reckoning glitch does) coasts
  // on the dead reckoning, its stamps left out, until an update explains most stamps and keeps to
  // the dead reckoning again. Confirmed: its prediction explained most stamps and its update kept
  // to the dead reckoning, with no correction since (an update explaining most stamps its
  // prediction did not) and the stamps unexplained for at most virtual_sender_onset_s plus one
  // interval. An unconfirmed track takes a jump as a correction: there its own past is what is in
  // doubt (after a poor start, measured in docs/results/acoustic.md). With the echoes predicted
  // the same stamps are the wall's echoes of the true sender, and no such event is needed.
  if (passes == 1 && options_.estimator == "rekf" && options_.virtual_sender_false_alarm > 0.0 && outcome.update) {
    const bool coast = DecideCoast(increment, outcome.rows, *outcome.update, epoch.t_s);
    coasting_ = coast;
    if (coast) {
      outcome.rows.clear();
      outcome.had_rows = increment.has_value();
      // The dead reckoning is what the track trusts here: its rows are not reweighted (ten prior
      // rows would outvote the increment's two as the stamps did). Without it, the prediction.
      outcome.update = increment ? UpdateWithRows({}, increment, x_, false) : std::nullopt;
    }
  }
  const auto& update = outcome.update;
  const long stamp_rows = static_cast<long>(outcome.rows.size());
  const bool had_rows = outcome.had_rows;
  if (update) {
    x_ += update->dx;
    P_ = 0.5 * (update->P + update->P.transpose());
    // Rows whose weight stayed positive entered the estimate.
    for (long i = 0; i < stamp_rows; ++i) out.associations += update->weights(n + i) > 0.0 ? 1 : 0;
  } else if (had_rows) {
    out.rejected_update = true;
  }
  out.expected = static_cast<int>(world_.anchors.size());
  out.agents.push_back(Estimate());
  // The track-loss test: a sender is inside the floor plan, between its floor and ceiling; an
  // estimate outside it by more than 3 sigma has lost the sender (a track that paired wrong
  // stamps and ran away with them). The start then searches the whole plan again.
  if (options_.restart_lost_track && passes > 1 && Outside(x_, P_)) {
    have_emission_ = false;
    search_whole_plan_ = true;
    pending_start_.reset();
    first_search_s_.reset();
    out.relocalized = true;
    out.fixed = false;  // the estimate outside the plan is no fix
  }
  return out;
}

StepOutput AcousticEstimator::Snapshot(const core::Epoch& epoch) {
  StepOutput out;
  out.expected = static_cast<int>(world_.anchors.size());
  // Each microphone's earliest stamp (the direct path when it was heard), as c (T - t_epoch).
  const StampsByReceiver stamps = Stamps(epoch, epoch.t_s);
  const std::vector<ChosenStamp> chosen = EarliestStamps(stamps);
  const std::size_t unknowns = planar() ? 3 : 4;
  if (chosen.size() < unknowns) {
    out.agents.push_back(last_);  // no fix: the last one stands, the epoch counts as a failure
    out.fixed = false;
    return out;
  }
  std::vector<Vec3> mics;
  std::vector<double> rho_m, sigma_m;
  for (const auto& c : chosen) {
    mics.push_back(world_.anchors[static_cast<std::size_t>(c.receiver)].position_m);
    rho_m.push_back(c.z_m);
    sigma_m.push_back(options_.range_sigma_m);
  }
  // Random starts over the microphones' footprint (the thesis's random initialisation), the
  // emission offset of each start from the median of its implied offsets.
  Vec3 lo = mics.front(), hi = mics.front();
  for (const auto& m : mics) {
    lo = lo.cwiseMin(m);
    hi = hi.cwiseMax(m);
  }
  estimation::NllsOptions nlls;
  if (planar()) nlls.known_height_m = height_m_;
  std::optional<estimation::SolverFix> best;
  for (int k = 0; k < options_.nlls_starts; ++k) {
    // One draw per statement (argument order is unspecified: the starts would differ between
    // compilers); z, y, x: the order the published numbers were drawn in.
    const double z_m = planar() ? height_m_ : rng_.Uniform(0.0, lo.z());
    const double y_m = rng_.Uniform(lo.y(), hi.y());
    const double x_m = rng_.Uniform(lo.x(), hi.x());
    const Vec3 start(x_m, y_m, z_m);
    std::vector<double> implied;
    for (std::size_t i = 0; i < mics.size(); ++i) implied.push_back(rho_m[i] - (start - mics[i]).norm());
    const auto fix = estimation::SolveToaNlls(mics, rho_m, sigma_m, start, estimation::Median(implied), nlls);
    if (!fix.converged || fix.degenerate()) continue;
    if (!best || fix.rms_m < best->rms_m) best = fix;
  }
  if (!best) {
    out.agents.push_back(last_);
    out.fixed = false;
    return out;
  }
  out.associations = static_cast<int>(chosen.size());
  AgentEstimate estimate;
  estimate.position_m = best->position_m;
  if (planar()) estimate.position_m.z() = height_m_;
  const int d = dim();
  estimate.covariance_m2.topLeftCorner(d, d) = best->covariance_m2.topLeftCorner(d, d);
  out.agents.push_back(estimate);
  return out;
}

StepOutput AcousticEstimator::Combinatorial(const core::Epoch& epoch) {
  StepOutput out;
  out.expected = static_cast<int>(world_.anchors.size());
  const auto fix = IdentifyLos(mics_m_, Stamps(epoch, epoch.t_s), height_m_, los_);
  // A fix outside the floor plan's bounds is no fix: the sender is in the room (a far mirror
  // root can gather votes when the voters' rows are nearly parallel).
  bool inside = true;
  if (!world_.floor_plan.walls().empty()) {
    const auto [lo, hi] = world_.floor_plan.Bounds();
    const Vec2 p = fix.position_m.head<2>();
    inside = (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
  }
  // The labels per record: a receiver's stamps are its records' concatenated (Stamps).
  out.los_stamps.assign(epoch.toas.size(), -1);
  if (fix.found && inside) {
    std::vector<int> offset(world_.anchors.size(), 0);
    for (std::size_t r = 0; r < epoch.toas.size(); ++r) {
      const auto m = static_cast<std::size_t>(epoch.toas[r].receiver_index);
      const int index = fix.los_stamp_index.at(m) - offset[m];
      if (index >= 0 && index < static_cast<int>(epoch.toas[r].toa_s.size())) out.los_stamps[r] = index;
      offset[m] += static_cast<int>(epoch.toas[r].toa_s.size());
    }
  }
  if (!fix.found || !inside) {
    out.agents.push_back(last_);  // no fix: the last one stands, the epoch counts as a failure
    out.fixed = false;
    return out;
  }
  out.associations = static_cast<int>(fix.los_receivers.size());
  AgentEstimate estimate;
  estimate.position_m = fix.position_m;
  estimate.covariance_m2.topLeftCorner<2, 2>() = fix.covariance_m2.topLeftCorner<2, 2>();
  out.agents.push_back(estimate);
  return out;
}

StepOutput AcousticEstimator::GroundEcho(const core::Epoch& epoch) {
  StepOutput out;
  out.expected = 2 * static_cast<int>(world_.anchors.size());  // a LOS and a floor echo per microphone
  const GroundEchoFix fix = ground_echo_->Process(epoch);
  if (!fix.found) {
    out.agents.push_back(last_);  // no fix: the last one stands, the epoch counts as a failure
    out.fixed = false;
    return out;
  }
  out.associations = fix.los_rows + fix.echo_rows;
  out.hdop = fix.hdop;
  out.vdop = fix.vdop;
  AgentEstimate estimate;
  estimate.position_m = fix.position_m;
  estimate.covariance_m2 = fix.covariance_m2;
  out.agents.push_back(estimate);
  return out;
}

StepOutput AcousticEstimator::Process(const core::Epoch& epoch) {
  StepOutput out = options_.estimator == "nlls"            ? Snapshot(epoch)
                   : options_.estimator == "combinatorial" ? Combinatorial(epoch)
                   : options_.estimator == "ground_echo"   ? GroundEcho(epoch)
                                                           : Filter(epoch);
  last_ = out.agents.front();
  return out;
}

}  // namespace mirage::methods::acoustic
