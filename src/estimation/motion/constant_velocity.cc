// SPDX-License-Identifier: MIT
#include "mirage/estimation/motion/constant_velocity.h"

#include <cassert>

#include <Eigen/Core>

#include "mirage/estimation/covariance_ops.h"
#include "mirage/estimation/state.h"

namespace mirage::estimation {

const core::OptionsDescriptor<ConstantVelocityOptions>& ConstantVelocityOptionsDescriptor() {
  static const auto descriptor = [] {
    core::OptionsDescriptor<ConstantVelocityOptions> d("estimation::ConstantVelocityOptions");
    d.Number(&ConstantVelocityOptions::accel_sigma_mps2,
             {.key = "accel_sigma_mps2",
              .unit = "m/s^2",
              .range = core::ValueRange::Positive(),
              .doc = "Standard deviation of the white acceleration of the constant-velocity model. 1 m/s^2 is a "
                     "walking person's typical acceleration. Derived: a walker's velocity changes by about its speed "
                     "within one gait cycle of about 0.5 s (a turn, a stop), so sigma_a = speed / 0.5 s.",
              .derived = core::DerivedDefault{.formula = "speed_mps / 0.5 s",
                                              .needs = {core::PhysicalKey::kSpeed},
                                              .compute = [](const core::PhysicalKeys& k) { return *k.speed_mps / 0.5; }}});
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const ConstantVelocityOptions& options) {
  return ConstantVelocityOptionsDescriptor().Validate(options);
}

ConstantVelocity::ConstantVelocity(const ConstantVelocityOptions& options, int dimension, int agents)
    : options_(options), dimension_(dimension) {
  assert((dimension == 2 || dimension == 3) && agents >= 0);
  for (int m = 0; m < agents; ++m) agents_.push_back(m);
}

ConstantVelocity::ConstantVelocity(const ConstantVelocityOptions& options, int dimension, std::vector<int> agents)
    : options_(options), dimension_(dimension), agents_(std::move(agents)) {
  assert(dimension == 2 || dimension == 3);
}

void ConstantVelocity::Apply(State& state, double dt) const {
  assert(dt >= 0.0);
  const int d = dimension_;
  const BlockType& position_type = d == 2 ? blocks::kPosition : blocks::kPosition3;
  [[maybe_unused]] const BlockType& velocity_type = d == 2 ? blocks::kVelocity : blocks::kVelocity3;
  // Eq. (3.16): F = [[I, dt I], [0, I]] and the white-acceleration Q, per axis.
  Eigen::MatrixXd F = Eigen::MatrixXd::Identity(2 * d, 2 * d);
  Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(2 * d, 2 * d);
  const double q = options_.accel_sigma_mps2 * options_.accel_sigma_mps2;
  const double dt2 = dt * dt;
  for (int axis = 0; axis < d; ++axis) {
    F(axis, axis + d) = dt;
    Q(axis, axis) = q * dt2 * dt2 / 4.0;
    Q(axis, axis + d) = Q(axis + d, axis) = q * dt2 * dt / 2.0;
    Q(axis + d, axis + d) = q * dt2;
  }
  for (const int m : agents_) {
    const BlockKey position(position_type, m);
    assert(state.layout().At(BlockKey(velocity_type, m)).offset == state.layout().At(position).offset + d);
    CovarianceOps::PropagateBlock(state, position, F, Q);
  }
}

State StartAtRest(int dimension, double t_s, const Vec3& position_m, const Eigen::Matrix3d& position_covariance_m2,
                  double velocity_sigma_mps) {
  assert(dimension == 2 || dimension == 3);
  const int d = dimension;
  StateLayout layout;
  layout.Append(d == 2 ? blocks::kPosition : blocks::kPosition3, 0);
  layout.Append(d == 2 ? blocks::kVelocity : blocks::kVelocity3, 0);
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(2 * d);
  mean.head(d) = position_m.head(d);
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(2 * d, 2 * d);
  P.topLeftCorner(d, d) = position_covariance_m2.topLeftCorner(d, d);
  P.bottomRightCorner(d, d) = velocity_sigma_mps * velocity_sigma_mps * Eigen::MatrixXd::Identity(d, d);
  return State(layout, mean, P, t_s);
}

}  // namespace mirage::estimation
