// SPDX-License-Identifier: MIT
#include "mirage/methods/coop/coop_estimator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "mirage/channel/link_channel.h"
#include "mirage/estimation/ekf_update.h"
#include "mirage/estimation/motion/constant_velocity.h"
#include "mirage/methods/coop/cir_link_signal.h"

namespace mirage::methods::coop {
namespace {

AntennaLayout Antennas(const CoopOptions& options) { return AntennaLayout{options.antenna_spacing_m}; }

std::optional<Vec2> FirstAnchor(const CoopOptions& options, const World& world) {
  if (!options.anchor_links) return std::nullopt;
  if (world.anchors.empty()) throw std::invalid_argument("coop: anchor_links needs an anchor in the scenario");
  return world.anchors.front().position_m.head<2>();
}

std::vector<Vec2> Planar(const std::vector<Vec3>& positions_m) {
  std::vector<Vec2> out;
  for (const auto& p : positions_m) out.push_back(p.head<2>());
  return out;
}

}  // namespace

std::vector<channel::LinkSpec> CoopLinks(const CoopOptions& options, const World& world) {
  const AntennaLayout antennas = Antennas(options);
  std::vector<channel::LinkSpec> out;
  for (const Link& link : EnumerateLinks(static_cast<int>(world.agents.size()), options.anchor_links)) {
    channel::LinkSpec spec;
    spec.id = link.Name();
    spec.rx = {link.rx_agent, -1, antennas.rx_offset()};
    spec.tx = link.kind == LinkKind::kAnchor ? channel::LinkEnd{-1, 0, Vec2::Zero()}
                                             : channel::LinkEnd{link.tx_agent, -1, antennas.tx_offset()};
    out.push_back(spec);
  }
  return out;
}

CoopEstimator::CoopEstimator(const CoopOptions& options, const World& world)
    : options_(options),
      world_(world),
      links_(EnumerateLinks(static_cast<int>(world.agents.size()), options.anchor_links)),
      synthesizer_(std::make_unique<channel::CirSynthesizer>(world_.channel)),
      extractor_(std::make_unique<dsp::MpcExtractor>(world_.mpc, synthesizer_->pulse(), synthesizer_->sample_count(),
                                                     world_.channel.sample_period_s, world_.channel.medium)),
      tracker_(options_, world_.floor_plan, links_, Antennas(options_), FirstAnchor(options_, world_),
               PulseFactsOf(synthesizer_->pulse(), world_.channel.medium)) {}

void CoopEstimator::Initialize(const Prior& prior) { tracker_.Initialize(Planar(prior.positions_m), prior.t_s); }

StepOutput CoopEstimator::Process(const core::Epoch& epoch) {
  if (epoch.cirs.size() != links_.size()) {
    throw std::invalid_argument("coop: an epoch needs one CIR per link (" + std::to_string(links_.size()) + "), got " +
                                std::to_string(epoch.cirs.size()));
  }
  std::vector<CirLinkSignal> signals;
  signals.reserve(links_.size());
  std::vector<const LinkSignal*> pointers(links_.size(), nullptr);
  for (const auto& record : epoch.cirs) signals.emplace_back(*extractor_, record.cir);
  for (std::size_t i = 0; i < epoch.cirs.size(); ++i) {
    pointers.at(static_cast<std::size_t>(epoch.cirs[i].link_index)) = &signals[i];
  }
  const CoopStepInfo info = tracker_.Step(epoch.t_s, pointers);
  StepOutput out;
  for (int m = 0; m < tracker_.agent_count(); ++m) {
    AgentEstimate agent;
    agent.position_m.head<2>() = tracker_.Position(m);
    agent.position_m.z() = world_.agent_height_m.value_or(0.0);
    agent.covariance_m2.topLeftCorner<2, 2>() = tracker_.PositionCovariance(m);
    out.agents.push_back(agent);
  }
  for (const auto& link : info.links) {
    out.associations += link.associated;
    out.expected += link.expected;
  }
  out.rejected_update = info.update.rejection == estimation::UpdateRejection::kNotPositiveDefinite;
  return out;
}

std::vector<WallEstimate> CoopEstimator::Walls() const {
  std::vector<WallEstimate> out;
  for (int s = 0; s < static_cast<int>(world_.floor_plan.walls().size()); ++s) {
    out.push_back({tracker_.WallOffset(s), tracker_.WallOffsetSigma(s)});
  }
  return out;
}

std::vector<std::vector<double>> CoopEstimator::PosteriorBound(const BoundInput& truth) const {
  if (truth.true_plan == nullptr || truth.true_known_plan == nullptr || truth.positions_m.empty()) return {};
  // The filter's model on the given plan's walls at their true places.
  const geometry::FloorPlan& plan = *truth.true_known_plan;
  CoopTracker model(options_, plan, links_, Antennas(options_), FirstAnchor(options_, world_),
                    PulseFactsOf(synthesizer_->pulse(), world_.channel.medium));
  const int agents = tracker_.agent_count();
  model.Initialize(Planar(truth.positions_m.front()), truth.t_s.front());
  estimation::State state = model.state();
  const double sigma1_m = synthesizer_->pulse().range_sigma_at_unit_sinr_m(world_.channel.medium.speed_mps);
  const auto specs = CoopLinks(options_, world_);
  std::vector<Vec2> anchors_m;
  for (const auto& a : world_.anchors) anchors_m.push_back(a.position_m.head<2>());
  channel::LinkPathOptions link_options;
  link_options.max_order = options_.max_order;
  link_options.carrier_hz = world_.channel.pulse.carrier_hz;
  link_options.speed_mps = world_.channel.medium.speed_mps;
  link_options.min_reference_m = std::max(options_.antenna_spacing_m, 0.1);
  std::vector<std::vector<double>> bound(truth.positions_m.size());
  for (std::size_t k = 0; k < truth.positions_m.size(); ++k) {
    const std::vector<Vec2> at = Planar(truth.positions_m[k]);
    if (k > 0) {
      const estimation::ConstantVelocity motion(CoopMotion(options_, truth.t_s[k] - state.t_s()), 2, agents);
      estimation::Propagate(state, truth.t_s[k], {&motion});
      std::vector<estimation::MeasurementRow> rows;
      for (std::size_t l = 0; l < links_.size(); ++l) {
        const Vec2 tx = channel::EndPosition(specs[l].tx, at, anchors_m);
        const Vec2 rx = channel::EndPosition(specs[l].rx, at, anchors_m);
        // The diffuse multipath is referred to the true channel (all walls, the unmodelled too).
        const double dm_reference_m =
            channel::ComputeLinkPaths(*truth.true_plan, tx, rx, specs[l].self(), link_options).dm_reference_m;
        for (const auto& path : model.ExpectedPaths(static_cast<int>(l), at, plan)) {
          const double length_m = path.range_m();
          double gain = 1.0;
          for (const int s : path.walls) gain *= plan.walls()[static_cast<std::size_t>(s)].reflection_coeff;
          const double sinr = synthesizer_->TrueSinr(Complex(gain / length_m, 0.0), length_m / world_.channel.medium.speed_mps,
                                                     dm_reference_m);
          // The model's layout is the layout of `state` (a copy of its initial state).
          rows.push_back(model.JacobianRow(links_[l], path, sigma1_m * sigma1_m / std::max(sinr, 1e-12)));
        }
      }
      if (!rows.empty()) {
        // Every path measured exactly at its mean: zero innovations, only the covariance moves.
        const std::vector<double> zero(rows.size(), 0.0);
        estimation::Update(state, rows, zero);
      }
    }
    for (int m = 0; m < agents; ++m) {
      bound[k].push_back(std::sqrt(state.Covariance(estimation::BlockKey(estimation::blocks::kPosition, m)).trace()));
    }
  }
  return bound;
}

}  // namespace mirage::methods::coop
