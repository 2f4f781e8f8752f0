// SPDX-License-Identifier: MIT
#include "mirage/methods/coop/coop_tracker.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "mirage/estimation/covariance_ops.h"
#include "mirage/estimation/gates/chi2_gate.h"
#include "mirage/estimation/meas/image_path_range.h"
#include "mirage/estimation/motion/constant_velocity.h"
#include "mirage/estimation/range_association.h"

namespace mirage::methods::coop {
namespace {

using estimation::BlockKey;
namespace blocks = estimation::blocks;

// The wall moved by `offset_m` along its normal (geometry::WallNormal), so that
// d length / d offset is ImagePath::d_offset.
geometry::Wall Shifted(const geometry::Wall& wall, double offset_m) {
  const Vec2 n = geometry::WallNormal(wall);
  geometry::Wall out = wall;
  out.start_m += offset_m * n;
  out.end_m += offset_m * n;
  return out;
}

}  // namespace

estimation::RangeVarianceOptions CoopOptions::DefaultVariance() {
  estimation::RangeVarianceOptions v;
  v.window_min_m = 0.1;   // half the window: samples of one place are correlated
  v.window_max_m = 0.2;   // Sec. IV-B: "within a distance (along the agent track) of 0.2 m"
  v.min_samples = 5;      // 8 steps fill 0.2 m at 2.5 cm per step
  v.default_sigma_m = 0.07;  // R_0 (Sec. IV-B)
  v.min_sigma_m = 0.005;  // a LOS at 25 dB SINR has a 3.5 mm CRLB at T_p = 0.5 ns
  v.overlap_distance_m = 0.0;  // overlapping expected paths are pruned before (Sec. IV-B)
  return v;
}

const core::OptionsDescriptor<CoopOptions>& CoopOptionsDescriptor() {
  using core::ValueRange;
  using O = CoopOptions;
  static const auto descriptor = [] {
    const ValueRange self_gate_range = ValueRange::NonNegative();
    const ValueRange spacing_range = ValueRange::Closed(0.0, 0.5);
    core::OptionsDescriptor<O> d("methods::coop::CoopOptions");
    d.Number(&O::agent_sigma_m, {.key = "agent_sigma_m",
                                 .unit = "m",
                                 .range = ValueRange::Positive(),
                                 .doc = "Initial position standard deviation sigma_agent. 0.03 m (Kulmer Sec. IV-B)."});
    d.Number(&O::velocity_sigma_mps,
             {.key = "velocity_sigma_mps",
              .unit = "m/s",
              .range = ValueRange::Positive(),
              .doc = "Initial velocity standard deviation; the agents start at rest (not stated in the paper). 0.025 "
                     "m/s = v_max at one step per second."});
    d.Number(&O::wall_sigma_m,
             {.key = "wall_sigma_m",
              .unit = "m",
              .range = ValueRange::LeftOpen(0.0, 1.0),
              .doc = "Initial standard deviation sigma_seg of each wall's normal offset. 3 mm; the paper also shows 1 "
                     "and 10 mm: larger adapts faster, smaller is more robust."});
    d.Boolean(&O::wall_update, {.key = "wall_update",
                                .doc = "Walls in the state (\"w su\"); false keeps them fixed at the provided plan "
                                       "(\"w/o su\")."});
    d.Number(&O::max_speed_mps,
             {.key = "max_speed_mps",
              .unit = "m/s",
              .range = ValueRange::Positive(),
              .doc = "Maximum speed v_max; the white-acceleration std is v_max / (3 dt). 0.025 m per "
                     "1 s step (Kulmer Sec. IV-B)."});
    d.Integer(&O::max_order, {.key = "max_order",
                              .range = ValueRange::Closed(1.0, 2.0),
                              .doc = "Highest reflection order of the expected paths. 2, as in the paper."});
    d.Number(&O::cutoff_m, {.key = "cutoff_m",
                            .unit = "m",
                            .range = ValueRange::NonNegative(),
                            .doc = "Association cut-off d_c; 0 means c T_p of the pulse (Kulmer Sec. IV-B)."});
    d.Number(&O::extraction_factor, {.key = "extraction_factor",
                                     .range = ValueRange::Closed(1.0, 100.0),
                                     .doc = "Components extracted per link = round(factor |K|), |K| the paths expected "
                                            "on the link. 1.5 (Kulmer Sec. IV-B)."});
    d.Number(&O::self_gate_m, {.key = "self_gate_m",
                               .unit = "m",
                               .range = self_gate_range,
                               .doc = "Extracted self-link ranges shorter than this are the antenna coupling and are "
                                      "dropped; it must exceed antenna_spacing_m, where the coupling arrives. 0.3 m."});
    d.Number(&O::innovation_gate_sigma,
             {.key = "innovation_gate_sigma",
              .range = ValueRange::Closed(0.0, 100.0),
              .doc = "Drop an associated range whose innovation exceeds this many standard deviations of its predicted "
                     "innovation; 0 = off (the paper relies on d_c alone). 3, our addition."});
    d.Section(&O::variance,
              {.key = "variance",
               .doc = "SINR and range variance per MPC (Kulmer Sec. III-C), with the cooperative defaults of "
                      "CoopOptions::DefaultVariance() instead of Lafer's: a window of 0.1-0.2 m of track, 5 samples, "
                      "R_0 = 0.07 m, a 5 mm floor, no overlap distance."},
              estimation::RangeVarianceOptionsDescriptor());
    d.Boolean(&O::anchor_links,
              {.key = "anchor_links",
               .doc = "Every agent also measures the channel from the world's first anchor (the anchor variants of "
                      "Kulmer Sec. IV-D); off: the paper's anchorless case."});
    d.Number(&O::antenna_spacing_m,
             {.key = "antenna_spacing_m",
              .unit = "m",
              .range = spacing_range,
              .doc = "Distance between an agent's transmit and receive antennas, side by side along x. 5 cm, as on the "
                     "paper's measurement trolley."});
    d.Check("self_gate_m > antenna_spacing_m when antenna_spacing_m > 0", [=](const O& o) -> std::vector<std::string> {
      if (!(o.antenna_spacing_m > 0.0) || o.self_gate_m > o.antenna_spacing_m ||
          !self_gate_range.Contains(o.self_gate_m) || !spacing_range.Contains(o.antenna_spacing_m)) {
        return {};
      }
      return {"self_gate_m: " + core::FormatNumber(o.self_gate_m) + " m must exceed antenna_spacing_m (" +
              core::FormatNumber(o.antenna_spacing_m) + " m), where the TX-RX coupling of a self link arrives"};
    });
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const CoopOptions& options) { return CoopOptionsDescriptor().Validate(options); }

estimation::ConstantVelocityOptions CoopMotion(const CoopOptions& options, double dt_s) {
  estimation::ConstantVelocityOptions cv;
  cv.accel_sigma_mps2 = options.max_speed_mps / (3.0 * (dt_s > 0.0 ? dt_s : 1.0));
  return cv;
}

CoopTracker::CoopTracker(const CoopOptions& options, geometry::FloorPlan provided_plan, std::vector<Link> links,
                         AntennaLayout antennas, std::optional<Vec2> anchor_m, const PulseFacts& pulse)
    : options_(options),
      provided_plan_(std::move(provided_plan)),
      links_(std::move(links)),
      antennas_(antennas),
      anchor_m_(anchor_m.value_or(Vec2::Zero())),
      cutoff_m_(options.cutoff_m > 0.0 ? options.cutoff_m : pulse.medium.speed_mps * pulse.duration_s),
      variance_(options.variance, pulse.range_sigma_at_unit_sinr_m) {
  if (!(pulse.duration_s > 0.0) || !(pulse.range_sigma_at_unit_sinr_m > 0.0)) {
    throw std::invalid_argument("CoopTracker: the pulse duration and CRLB scale must be > 0");
  }
  if (const auto problems = Validate(options_); !problems.empty()) {
    throw std::invalid_argument("CoopTracker: " + problems.front());
  }
  for (const auto& link : links_) {
    agents_ = std::max(agents_, std::max(link.tx_agent, link.rx_agent) + 1);
    if (link.kind == LinkKind::kAnchor && !anchor_m) throw std::invalid_argument("CoopTracker: anchor link without anchor");
  }
}

void CoopTracker::Initialize(std::span<const Vec2> positions_m, double t_s) {
  if (static_cast<int>(positions_m.size()) != agents_) {
    throw std::invalid_argument(fmt::format("CoopTracker: {} start positions for {} agents", positions_m.size(), agents_));
  }
  estimation::StateLayout layout;
  for (int m = 0; m < agents_; ++m) {
    layout.Append(blocks::kPosition, m);
    layout.Append(blocks::kVelocity, m);
  }
  const int walls = static_cast<int>(provided_plan_.walls().size());
  if (options_.wall_update) {
    for (int s = 0; s < walls; ++s) layout.Append(blocks::kWallOffset, s);
  }
  const int n = layout.dimension();
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd variance = Eigen::VectorXd::Zero(n);
  for (int m = 0; m < agents_; ++m) {
    const int p = layout.At(BlockKey(blocks::kPosition, m)).offset;
    const int v = layout.At(BlockKey(blocks::kVelocity, m)).offset;
    mean.segment<2>(p) = positions_m[static_cast<std::size_t>(m)];
    variance.segment<2>(p).setConstant(options_.agent_sigma_m * options_.agent_sigma_m);
    variance.segment<2>(v).setConstant(options_.velocity_sigma_mps * options_.velocity_sigma_mps);
  }
  if (options_.wall_update) {
    const int w = layout.At(BlockKey(blocks::kWallOffset, 0)).offset;
    variance.segment(w, walls).setConstant(options_.wall_sigma_m * options_.wall_sigma_m);
  }
  // Sec. IV-B: no initial cross-covariances.
  state_ = estimation::State(std::move(layout), std::move(mean), variance.asDiagonal(), t_s);
  variance_.Reset();
  history_ids_.clear();
}

Vec2 CoopTracker::Position(int agent) const { return state_.Mean(BlockKey(blocks::kPosition, agent)); }

Eigen::Matrix2d CoopTracker::PositionCovariance(int agent) const {
  return state_.Covariance(BlockKey(blocks::kPosition, agent));
}

double CoopTracker::WallOffset(int wall) const {
  if (!options_.wall_update) return 0.0;
  return state_.mean()(state_.layout().At(BlockKey(blocks::kWallOffset, wall)).offset);
}

double CoopTracker::WallOffsetSigma(int wall) const {
  if (!options_.wall_update) return 0.0;
  const int i = state_.layout().At(BlockKey(blocks::kWallOffset, wall)).offset;
  return std::sqrt(state_.covariance()(i, i));
}

geometry::FloorPlan CoopTracker::CurrentPlan() const {
  if (!options_.wall_update) return provided_plan_;
  std::vector<geometry::Wall> walls;
  walls.reserve(provided_plan_.walls().size());
  for (std::size_t s = 0; s < provided_plan_.walls().size(); ++s) {
    walls.push_back(Shifted(provided_plan_.walls()[s], WallOffset(static_cast<int>(s))));
  }
  return geometry::FloorPlan(std::move(walls), provided_plan_.obstacles());
}

std::vector<Vec2> CoopTracker::Positions() const {
  std::vector<Vec2> out;
  for (int m = 0; m < agents_; ++m) out.push_back(Position(m));
  return out;
}

int CoopTracker::HistoryId(int link, const geometry::WallSequence& walls) {
  const auto [it, inserted] = history_ids_.try_emplace({link, walls}, static_cast<int>(history_ids_.size()));
  return it->second;
}

Vec2 CoopTracker::WindowPoint(const Link& link, std::span<const Vec2> agents_m) const {
  const Vec2& rx = agents_m[static_cast<std::size_t>(link.rx_agent)];
  if (link.kind != LinkKind::kRelative) return rx;
  return 0.5 * (rx + agents_m[static_cast<std::size_t>(link.tx_agent)]);
}

std::vector<ExpectedPath> CoopTracker::ExpectedPaths(int link_index, std::span<const Vec2> agents_m,
                                                     const geometry::FloorPlan& plan, int* visible) {
  const Link& link = links_[static_cast<std::size_t>(link_index)];
  const std::vector<Vec2> agents(agents_m.begin(), agents_m.end());
  const LinkEnds ends = AntennaPositions(link, agents, anchor_m_, antennas_);
  std::vector<ExpectedPath> paths;
  for (auto& walls : geometry::VisibleImagePaths(plan, ends.tx_m, ends.rx_m, options_.max_order)) {
    // A self link's "line of sight" is the antenna coupling, not a measurement of anything.
    if (link.kind == LinkKind::kSelf && walls.empty()) continue;
    ExpectedPath path;
    path.path = geometry::ComputeImagePath(plan, walls, ends.tx_m, ends.rx_m);
    path.walls = std::move(walls);
    paths.push_back(std::move(path));
  }
  if (visible != nullptr) *visible = static_cast<int>(paths.size());
  // Sec. IV-B: pairs of expected paths closer than d_c cannot be told apart; drop both.
  std::vector<bool> ambiguous(paths.size(), false);
  for (std::size_t i = 0; i < paths.size(); ++i) {
    for (std::size_t j = i + 1; j < paths.size(); ++j) {
      if (std::abs(paths[i].range_m() - paths[j].range_m()) < cutoff_m_) ambiguous[i] = ambiguous[j] = true;
    }
  }
  std::vector<ExpectedPath> kept;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    if (ambiguous[i]) continue;
    paths[i].history = HistoryId(link_index, paths[i].walls);
    kept.push_back(std::move(paths[i]));
  }
  return kept;
}

estimation::MeasurementRow CoopTracker::JacobianRow(const Link& link, const ExpectedPath& expected, double variance_m2) const {
  const auto position = [&](int agent) -> std::optional<estimation::Block> {
    return state_.layout().At(BlockKey(blocks::kPosition, agent));
  };
  // Eq. (13), (14), (17): the antennas move with their agents (an anchor link's transmitter is
  // fixed); with the wall update, each wall of the path has its offset in the state.
  const std::optional<estimation::Block> tx = link.kind == LinkKind::kAnchor ? std::nullopt : position(link.tx_agent);
  const std::optional<estimation::Block> rx = position(link.rx_agent);
  std::array<std::optional<estimation::Block>, estimation::MeasurementRow::kMaxBlocks> walls{};
  std::size_t wall_count = 0;
  if (options_.wall_update) {
    for (const int w : expected.walls) walls[wall_count++] = state_.layout().At(BlockKey(blocks::kWallOffset, w));
  }
  return estimation::ImagePathRangeRow(expected.path, tx, rx, std::span(walls.data(), wall_count), variance_m2);
}

CoopStepInfo CoopTracker::Step(double t_s, std::span<const LinkSignal* const> signals) {
  if (signals.size() != links_.size()) {
    throw std::invalid_argument(fmt::format("CoopTracker::Step: {} signals for {} links", signals.size(), links_.size()));
  }
  // Prediction (Eq. 5, 16): constant velocity per agent with sigma_a = v_max / (3 dt) (Sec. IV-B);
  // walls static without process noise.
  const estimation::ConstantVelocity motion(CoopMotion(options_, t_s - state_.t_s()), 2, agents_);
  estimation::Propagate(state_, t_s, {&motion});

  const geometry::FloorPlan plan = CurrentPlan();
  const std::vector<Vec2> predicted = Positions();

  CoopStepInfo info;
  info.links.resize(links_.size());
  std::vector<estimation::MeasurementRow> rows;
  std::vector<double> innovations;
  std::vector<std::vector<ExpectedPath>> expected(links_.size());
  for (std::size_t l = 0; l < links_.size(); ++l) {
    const Link& link = links_[l];
    LinkStepInfo& li = info.links[l];
    expected[l] = ExpectedPaths(static_cast<int>(l), predicted, plan, &li.visible);
    const auto& paths = expected[l];
    li.expected = static_cast<int>(paths.size());
    if (paths.empty()) continue;
    // Eq. (6)-(7): round(1.5 |K|) components; a self link spends one more on the coupling.
    const int count = static_cast<int>(std::lround(options_.extraction_factor * static_cast<double>(paths.size()))) +
                      (link.kind == LinkKind::kSelf ? 1 : 0);
    std::vector<double> ranges;
    for (const double range_m : signals[l]->Ranges(count)) {
      if (link.kind == LinkKind::kSelf && range_m < options_.self_gate_m) continue;
      ranges.push_back(range_m);
    }
    li.extracted = static_cast<int>(ranges.size());
    if (ranges.empty()) continue;
    // Sec. III-B3: Hungarian assignment on min(|d_hat - d|, d_c); pairs at the cut-off are not
    // associations.
    std::vector<double> expected_m;
    for (const auto& path : paths) expected_m.push_back(path.range_m());
    const std::vector<int> assignment = estimation::AssociateRanges(expected_m, ranges, cutoff_m_);
    for (std::size_t k = 0; k < paths.size(); ++k) {
      const int z = assignment[k];
      if (z < 0) continue;
      const double nu = ranges[static_cast<std::size_t>(z)] - paths[k].range_m();
      const double r_m2 = options_.variance.enabled
                              ? variance_.Variance(paths[k].history, true).variance_m2
                              : options_.variance.default_sigma_m * options_.variance.default_sigma_m;
      const estimation::MeasurementRow row = JacobianRow(link, paths[k], r_m2);
      // Our addition (docs/methods/coop.md): a row whose innovation is implausible under its
      // predicted innovation variance h P h^T + r is a wrong association (a diffuse or
      // unmodelled peak within d_c) and is dropped before it corrupts the state.
      const double gate = options_.innovation_gate_sigma * options_.innovation_gate_sigma;
      if (options_.innovation_gate_sigma > 0.0 &&
          !estimation::InsideChi2Gate(nu, estimation::InnovationVariance(state_, row), gate)) {
        ++li.gated;
        continue;
      }
      rows.push_back(row);
      innovations.push_back(nu);
      ++li.associated;
    }
  }

  // One stacked update of all links (Algorithm 1), the standard covariance form.
  if (!rows.empty()) {
    estimation::UpdateOptions update;
    update.form = estimation::CovarianceForm::kStandard;
    info.update = estimation::Update(state_, rows, innovations, update);
  } else {
    info.update.rejection = estimation::UpdateRejection::kNoMeasurements;
  }

  // Sec. III-C: the amplitude of every expected path at its delay at the updated state, projected
  // from the received signal, feeds the SINR estimate of the next steps.
  const geometry::FloorPlan posterior_plan = CurrentPlan();
  const std::vector<Vec2> posterior = Positions();
  for (std::size_t l = 0; l < links_.size(); ++l) {
    const LinkEnds ends = AntennaPositions(links_[l], posterior, anchor_m_, antennas_);
    const Vec2 window_point = WindowPoint(links_[l], posterior);
    for (const auto& path : expected[l]) {
      const double length_m = geometry::ComputeImagePath(posterior_plan, path.walls, ends.tx_m, ends.rx_m).length_m;
      variance_.AddSample(path.history, window_point, signals[l]->AmplitudeAt(length_m));
    }
  }
  return info;
}

}  // namespace mirage::methods::coop
