// SPDX-License-Identifier: MIT
// Constant-velocity motion model of a 2-D agent (Lafer 2014 Eq. 3.13-3.16). The thesis leaves
// Q unspecified [GAP]; we use the discrete white-noise-acceleration form
//   Q = sigma_a^2 [[dt^4/4 I, dt^3/2 I], [dt^3/2 I, dt^2 I]],
// i.e. an acceleration that is constant over one step and white between steps, which scales
// correctly when dt varies (recorded data).
#pragma once

#include <string>
#include <vector>

#include "mirage/estimation/state.h"

namespace mirage::estimation {

/// Parameters of the constant-velocity model.
struct ConstantVelocityOptions {
  /// Standard deviation of the acceleration sigma_a (m/s^2), > 0. 1 m/s^2, a walking person's
  /// typical acceleration; a 90 degree corner at 0.5 m/s (a 0.7 m/s change within one 0.1 s step)
  /// is a 7-sigma event that the measurements, not the model, have to absorb. In the seminar room
  /// 2 m/s^2 diverges more often (docs/methods/mint.md, ablations).
  double accel_sigma_mps2 = 1.0;
};

/// Problems with the options, empty if valid.
std::vector<std::string> Validate(const ConstantVelocityOptions& options);

/// Moves the agent's position and velocity blocks (which must be adjacent, position first) to
/// t_s, propagating the covariance of the whole state. dt = t_s - state.t_s() must be >= 0.
void PropagateConstantVelocity(State& state, int agent, double t_s, const ConstantVelocityOptions& options);

/// The same for agents 0 .. agents-1 of a multi-agent state, all over the same dt. (Calling
/// PropagateConstantVelocity per agent would move only the first: it stamps the state with t_s.)
void PropagateConstantVelocityAll(State& state, int agents, double t_s, const ConstantVelocityOptions& options);

}  // namespace mirage::estimation
