// SPDX-License-Identifier: MIT
#include "mirage/estimation/motion/constant_velocity.h"

#include <cassert>
#include <cmath>

#include "mirage/estimation/covariance_ops.h"

namespace mirage::estimation {

std::vector<std::string> Validate(const ConstantVelocityOptions& options) {
  std::vector<std::string> problems;
  if (!(options.accel_sigma_mps2 > 0.0) || !std::isfinite(options.accel_sigma_mps2)) {
    problems.push_back("accel_sigma_mps2 must be > 0 m/s^2");
  }
  return problems;
}

namespace {

// Eq. (3.16) for one agent over dt, stamping the state with t_s.
void Propagate(State& state, int agent, double dt, double t_s, const ConstantVelocityOptions& options) {
  const Block position = state.layout().At({BlockKind::kPosition, agent});
  assert(state.layout().At({BlockKind::kVelocity, agent}).offset == position.offset + 2);
  assert(dt >= 0.0);
  Eigen::Matrix4d F = Eigen::Matrix4d::Identity();
  F(0, 2) = dt;
  F(1, 3) = dt;
  const double q = options.accel_sigma_mps2 * options.accel_sigma_mps2;
  const double dt2 = dt * dt;
  Eigen::Matrix4d Q = Eigen::Matrix4d::Zero();
  for (int axis = 0; axis < 2; ++axis) {
    Q(axis, axis) = q * dt2 * dt2 / 4.0;
    Q(axis, axis + 2) = Q(axis + 2, axis) = q * dt2 * dt / 2.0;
    Q(axis + 2, axis + 2) = q * dt2;
  }
  CovarianceOps::PropagateBlock(state, position.offset, F, Q, t_s);
}

}  // namespace

void PropagateConstantVelocity(State& state, int agent, double t_s, const ConstantVelocityOptions& options) {
  Propagate(state, agent, t_s - state.t_s(), t_s, options);
}

void PropagateConstantVelocityAll(State& state, int agents, double t_s, const ConstantVelocityOptions& options) {
  // dt is taken once: the first agent's propagation already stamps the state with t_s.
  const double dt = t_s - state.t_s();
  for (int m = 0; m < agents; ++m) Propagate(state, m, dt, t_s, options);
}

}  // namespace mirage::estimation
