// SPDX-License-Identifier: MIT
#include "mirage/methods/tdoa_ekf/tdoa_ekf.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "mirage/core/derived_defaults.h"
#include "mirage/estimation/ekf_update.h"
#include "mirage/estimation/gates/chi2_gate.h"
#include "mirage/estimation/gates/tdoa_bound.h"
#include "mirage/estimation/init/tdoa_position_fix.h"
#include "mirage/estimation/meas/tdoa.h"
#include "mirage/estimation/motion/propagator.h"

namespace mirage::methods::tdoa_ekf {
namespace {

namespace blocks = estimation::blocks;

/// Standard deviations by which a difference may exceed its anchors' baseline.
constexpr double kBaselineSigmas = 3.0;
/// Rows of a window: more than the state's 6 unknowns, so that the rows can outvote the prior.
constexpr std::size_t kMinWindowRows = 7;

}  // namespace

const core::OptionsDescriptor<TdoaEkfOptions>& TdoaEkfOptionsDescriptor() {
  using core::ValueRange;
  using O = TdoaEkfOptions;
  static const auto descriptor = [] {
    core::OptionsDescriptor<O> d("methods::tdoa_ekf::TdoaEkfOptions");
    d.Choice(&O::update,
             {.key = "update",
              .doc = "rekf: the robust EKF (Hampel IRLS over the prior and the rows, Bordoy Sec. 5.2); gated_ekf: "
                     "an EKF that drops a difference outside the chi-square gate; ekf: every difference enters."},
             {"rekf", "gated_ekf", "ekf"});
    d.Number(&O::tdoa_sigma_m, {.key = "tdoa_sigma_m",
                                .unit = "m",
                                .range = ValueRange::Above(0.0),
                                .doc = "Standard deviation of one reported difference. 0.15 m (Loco Positioning "
                                       "TDOA3); derived from the scenario's noise.",
                                .derived = core::RangeSigmas(1.0)});
    d.Boolean(&O::baseline_gate, {.key = "baseline_gate",
                                  .doc = "Drop a difference larger in magnitude than its anchors' baseline plus 3 "
                                         "tdoa_sigma_m: no true difference exceeds the baseline (triangle "
                                         "inequality)."});
    d.Number(&O::gate_chi2, {.key = "gate_chi2",
                             .range = ValueRange::Above(0.0),
                             .doc = "gated_ekf: chi-square gate on one difference's innovation (1 degree of "
                                    "freedom). 9 = 3 sigma of h P h^T + R."});
    d.Section(&O::irls, {.key = "irls", .doc = "The rekf update's reweighting."}, estimation::IrlsOptionsDescriptor());
    d.Number(&O::initial_position_sigma_m,
             {.key = "initial_position_sigma_m",
              .unit = "m",
              .range = ValueRange::Above(0.0),
              .doc = "Position standard deviation of a given start point. 0.5 m: a start known to the room's scale. A "
                     "self-initialised start uses its fix's covariance instead."});
    d.Number(&O::initial_velocity_sigma_mps, {.key = "initial_velocity_sigma_mps",
                                              .unit = "m/s",
                                              .range = ValueRange::Above(0.0),
                                              .doc = "Velocity standard deviation at the start. 1 m/s; derived: the "
                                                     "agent's speed in an unknown direction.",
                                              .derived = core::SpeedTimes(1.0)});
    d.Number(&O::window_s, {.key = "window_s",
                                 .unit = "s",
                                 .range = ValueRange::Above(0.0),
                                 .doc = "The differences of this long a window are solved together: by the rekf "
                                        "update (more rows than unknowns) and by the self-initialisation. 0.1 s; "
                                        "derived: the time in which the agent moves one standard deviation of a "
                                        "difference (at most 1 s).",
                                 .derived = core::RangeSigmaWalkingTime(1.0)});
    d.Section(&O::motion, {.key = "motion", .doc = "Constant-velocity motion model of the agent."},
              estimation::ConstantVelocityOptionsDescriptor());
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const TdoaEkfOptions& options) { return TdoaEkfOptionsDescriptor().Validate(options); }

TdoaEkf::TdoaEkf(const TdoaEkfOptions& options, const World& world)
    : options_(options), world_(world), motion_(options.motion, 3, 1) {
  if (const auto problems = Validate(options_); !problems.empty()) throw std::invalid_argument("tdoa_ekf: " + problems.front());
  if (world_.anchors.size() < 4) throw std::invalid_argument("tdoa_ekf: a 3-D position from differences needs at least 4 anchors");
}

void TdoaEkf::Start(double t_s, const Vec3& position_m, const Eigen::Matrix3d& position_covariance_m2) {
  state_ = estimation::StartAtRest(3, t_s, position_m, position_covariance_m2, options_.initial_velocity_sigma_mps);
  init_rows_.clear();
  pending_.clear();
}

void TdoaEkf::Initialize(const Prior& prior) {
  const double sp = options_.initial_position_sigma_m;
  Start(prior.t_s, prior.positions_m.front(), sp * sp * Eigen::Matrix3d::Identity());
}

bool TdoaEkf::Usable(const core::TdoaMeasurement& m) const {
  const auto n = static_cast<int>(world_.anchors.size());
  // Valid indices are the source's contract (the readers check ids against the anchors).
  assert(m.index_i >= 0 && m.index_i < n && m.index_j >= 0 && m.index_j < n);
  if (m.index_i < 0 || m.index_i >= n || m.index_j < 0 || m.index_j >= n || m.index_i == m.index_j) return false;
  if (!std::isfinite(m.t_s) || !std::isfinite(m.tdoa_m)) return false;
  return !options_.baseline_gate ||
         estimation::InsideTdoaBound(m.tdoa_m, world_.anchors[static_cast<std::size_t>(m.index_i)].position_m,
                                     world_.anchors[static_cast<std::size_t>(m.index_j)].position_m,
                                     kBaselineSigmas * options_.tdoa_sigma_m);
}

bool TdoaEkf::InitializeFromEpoch(const core::Epoch& epoch) {
  for (const auto& m : epoch.tdoas) {
    if (Usable(m)) init_rows_.push_back(m);
  }
  if (init_rows_.empty()) return false;
  while (init_rows_.front().t_s < init_rows_.back().t_s - options_.window_s) init_rows_.pop_front();
  // A full window, as the robust update uses: the first rows that happen to agree are too few
  // to expose a mirror image or an outlier.
  if (init_rows_.back().t_s - init_rows_.front().t_s < options_.window_s * (1.0 - 1e-9) ||
      init_rows_.size() < kMinWindowRows) {
    return false;
  }
  std::vector<estimation::TdoaRow> rows;
  for (const auto& m : init_rows_) {
    rows.push_back({world_.anchors[static_cast<std::size_t>(m.index_i)].position_m,
                    world_.anchors[static_cast<std::size_t>(m.index_j)].position_m, m.index_i, m.index_j, m.tdoa_m});
  }
  const auto fix = estimation::FixPositionFromTdoas(rows, options_.tdoa_sigma_m);
  if (!fix || !Plausible(fix->fix)) return false;
  Start(init_rows_.back().t_s, fix->fix.position_m, fix->fix.covariance_m2);
  return true;
}

bool TdoaEkf::Plausible(const estimation::PositionFix& fix) const {
  // A start less certain than the anchors' own spread tells nothing about where the tag is (the
  // direction along the normal of nearly coplanar anchors, seen from few rows).
  Vec3 centroid_m = Vec3::Zero();
  for (const auto& a : world_.anchors) centroid_m += a.position_m;
  centroid_m /= static_cast<double>(world_.anchors.size());
  double spread_m2 = 0.0;
  for (const auto& a : world_.anchors) spread_m2 += (a.position_m - centroid_m).squaredNorm();
  spread_m2 /= static_cast<double>(world_.anchors.size());
  const double largest_m2 = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(fix.covariance_m2).eigenvalues()(2);
  if (!(largest_m2 <= spread_m2)) return false;
  // Inside the given floor plan and between its floor and ceiling, when it has them.
  const geometry::FloorPlan& plan = world_.floor_plan;
  if (!plan.walls().empty() && !plan.Encloses(fix.position_m.head<2>())) return false;
  return fix.position_m.z() >= plan.floor_z_m() && fix.position_m.z() <= plan.ceiling_z_m();
}

TdoaEkf::Stack TdoaEkf::Linearize(const estimation::State& state, const std::vector<core::TdoaMeasurement>& tdoas) const {
  const estimation::Block position = state.layout().At(estimation::BlockKey(blocks::kPosition3, 0));
  const estimation::Block velocity = state.layout().At(estimation::BlockKey(blocks::kVelocity3, 0));
  const Vec3 p = state.mean().segment<3>(position.mean_offset);
  const Vec3 v = state.mean().segment<3>(velocity.mean_offset);
  Stack s;
  std::vector<Eigen::RowVector3d> rows;
  std::vector<double> dt_s;
  std::vector<double> innovations;
  for (std::size_t k = 0; k < tdoas.size(); ++k) {
    const auto& m = tdoas[k];
    if (!Usable(m)) {
      ++s.out_of_bound;
      continue;
    }
    // A row of another time than the state's sees the agent where the constant-velocity model
    // puts it then: p + v (t - t_state), so its Jacobian has d (t - t_state) in the velocity
    // columns.
    const double offset_s = m.t_s - state.t_s();
    const auto pred = estimation::PredictTdoa(p + offset_s * v, world_.anchors[static_cast<std::size_t>(m.index_i)].position_m,
                                              world_.anchors[static_cast<std::size_t>(m.index_j)].position_m);
    if (!pred) {  // the agent sits on an anchor: the direction is undefined
      ++s.out_of_bound;
      continue;
    }
    rows.push_back(pred->d_sender.transpose());
    dt_s.push_back(offset_s);
    innovations.push_back(m.tdoa_m - pred->predicted_m);
    s.kept.push_back(static_cast<int>(k));
  }
  s.H = Eigen::MatrixXd::Zero(static_cast<long>(rows.size()), state.dimension());
  s.innovation_m = Eigen::VectorXd::Zero(static_cast<long>(rows.size()));
  s.variance_m2 = Eigen::VectorXd::Zero(static_cast<long>(rows.size()));
  // A row at another time than the state's is predicted by the motion model over the offset, and
  // the model's own uncertainty over it adds to the row's noise: the position variance of the
  // white-acceleration model, sigma_a^2 dt^4 / 4 per axis (motion/constant_velocity.h), seen
  // along the row's gradient. Rows of one window share that process noise; it is small against
  // the noise within a window (0.1 s at 3 m/s^2: 0.15 mm^2 against 0.0225 m^2) and large after
  // a dropout, where it lets an old row weigh little.
  const double q = options_.motion.accel_sigma_mps2 * options_.motion.accel_sigma_mps2;
  const double sigma2 = options_.tdoa_sigma_m * options_.tdoa_sigma_m;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const double dt2 = dt_s[r] * dt_s[r];
    s.variance_m2(static_cast<long>(r)) = sigma2 + q * dt2 * dt2 / 4.0 * rows[r].squaredNorm();
    s.H.block<1, 3>(static_cast<long>(r), position.offset) = rows[r];
    s.H.block<1, 3>(static_cast<long>(r), velocity.offset) = dt_s[r] * rows[r];
    s.innovation_m(static_cast<long>(r)) = innovations[r];
  }
  return s;
}

TdoaUpdateCounts TdoaEkf::Update(const std::vector<core::TdoaMeasurement>& tdoas) {
  TdoaUpdateCounts counts;
  Stack s = Linearize(state_, tdoas);
  counts.rejected = s.out_of_bound;
  if (options_.update == "gated_ekf") {
    // Keep the rows whose innovation lies inside the gate on its own h P h^T + R.
    std::vector<long> inside;
    for (long r = 0; r < s.H.rows(); ++r) {
      const double s_m2 = (s.H.row(r) * state_.covariance() * s.H.row(r).transpose())(0) + s.variance_m2(r);
      if (estimation::InsideChi2Gate(s.innovation_m(r), s_m2, options_.gate_chi2)) inside.push_back(r);
    }
    counts.rejected += static_cast<int>(s.H.rows()) - static_cast<int>(inside.size());
    s.H = s.H(inside, Eigen::all).eval();
    s.innovation_m = s.innovation_m(inside).eval();
    s.variance_m2 = s.variance_m2(inside).eval();
  }
  const long m = s.H.rows();
  if (m == 0) return counts;
  const Eigen::MatrixXd R = s.variance_m2.asDiagonal();
  if (options_.update == "rekf") {
    const auto result = estimation::IrlsUpdate(state_.covariance(), s.H, s.innovation_m, R, options_.irls);
    if (!result) {
      counts.rejected += static_cast<int>(m);
      counts.failed = true;
      return counts;
    }
    const int n = state_.dimension();
    for (long r = 0; r < m; ++r) (result->weights(n + r) > 0.0 ? counts.used : counts.rejected) += 1;
    state_ = estimation::State(state_.layout(), state_.mean() + result->dx, result->P, state_.t_s());
    return counts;
  }
  if (estimation::EkfUpdate(state_, s.H, s.innovation_m, R).applied) {
    counts.used += static_cast<int>(m);
  } else {
    counts.rejected += static_cast<int>(m);
    counts.failed = true;
  }
  return counts;
}

AgentEstimate TdoaEkf::Estimate() const {
  AgentEstimate out;
  out.position_m = state_.mean().head<3>();
  out.covariance_m2 = state_.covariance().topLeftCorner<3, 3>();
  return out;
}

StepOutput TdoaEkf::Process(const core::Epoch& epoch) {
  StepOutput out;
  if (options_.update == "rekf") {
    // The robust update needs more rows than the state has unknowns, or the prior always
    // outvotes a lone row (a wrong prediction could never lose): the rows of window_s are
    // collected and update together at the latest one's time.
    // A window closes when its rows span window_s and outnumber the unknowns.
    for (const auto& m : epoch.tdoas) {
      if (std::isfinite(m.t_s)) pending_.push_back(m);
    }
    if (pending_.size() >= kMinWindowRows &&
        pending_.back().t_s - pending_.front().t_s >= options_.window_s * (1.0 - 1e-9)) {
      estimation::Propagate(state_, std::max(pending_.back().t_s, state_.t_s()), {&motion_});
      const TdoaUpdateCounts counts = Update(pending_);
      out.associations += counts.used;
      out.expected += counts.used + counts.rejected;
      out.rejected_update = counts.failed;
      pending_.clear();
    } else {
      out.deferred = true;
    }
    estimation::Propagate(state_, std::max(epoch.t_s, state_.t_s()), {&motion_});
    out.agents.push_back(Estimate());
    return out;
  }
  // Event-driven: the differences are in time order; those of one time stamp update together.
  std::size_t next = 0;
  while (next < epoch.tdoas.size()) {
    const double t_s = epoch.tdoas[next].t_s;
    std::vector<core::TdoaMeasurement> group;
    for (; next < epoch.tdoas.size() && epoch.tdoas[next].t_s == t_s; ++next) group.push_back(epoch.tdoas[next]);
    if (!std::isfinite(t_s)) {  // a row without a time: it cannot be placed (never equal: skip it alone)
      ++next;
      out.expected += 1;
      continue;
    }
    estimation::Propagate(state_, std::max(t_s, state_.t_s()), {&motion_});
    const TdoaUpdateCounts counts = Update(group);
    out.associations += counts.used;
    out.expected += counts.used + counts.rejected;
    out.rejected_update = out.rejected_update || counts.failed;
  }
  estimation::Propagate(state_, std::max(epoch.t_s, state_.t_s()), {&motion_});
  out.agents.push_back(Estimate());
  return out;
}

}  // namespace mirage::methods::tdoa_ekf
