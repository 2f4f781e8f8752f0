// SPDX-License-Identifier: MIT
// Constant-velocity motion model of an agent in the plane or in 3-D (Lafer 2014 Eq. 3.13-3.16).
// The thesis leaves Q unspecified [GAP]; we use the discrete white-noise-acceleration form
//   Q = sigma_a^2 [[dt^4/4 I, dt^3/2 I], [dt^3/2 I, dt^2 I]],
// i.e. an acceleration that is constant over one step and white between steps, which scales
// correctly when dt varies (recorded data).
#pragma once

#include <string>
#include <vector>

#include "mirage/core/options_descriptor.h"
#include "mirage/core/types.h"
#include "mirage/estimation/motion/propagator.h"
#include "mirage/estimation/state.h"

namespace mirage::estimation {

/// Parameters of the constant-velocity model.
struct ConstantVelocityOptions {
  /// Standard deviation of the acceleration sigma_a (m/s^2), in [1e-9, 1e9]. 1 m/s^2, a walking
  /// person's typical acceleration. A scenario that states the walker's speed derives it as
  /// speed / 0.5 s: the velocity changes by about the speed within one gait cycle (a turn, a
  /// stop), which gives the same 1 m/s^2 at the seminar room's 0.5 m/s. A 90 degree corner turned
  /// instantly (a 0.7 m/s change within one 0.1 s step at 0.5 m/s) is still a 7-sigma event that
  /// the measurements, not the model, have to absorb (docs/methods/mint.md, ablations).
  double accel_sigma_mps2 = 1.0;
};

/// The options' descriptor (keys, units, ranges, docs; core/options_descriptor.h).
const core::OptionsDescriptor<ConstantVelocityOptions>& ConstantVelocityOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const ConstantVelocityOptions& options);

/// The constant-velocity model of agents 0 .. agents-1, whose position and velocity blocks are
/// adjacent (position first): blocks::kPosition / kVelocity in the plane (dimension 2) or
/// blocks::kPosition3 / kVelocity3 in 3-D (dimension 3).
class ConstantVelocity final : public Propagator {
 public:
  /// The model of agents 0 .. agents-1 in `dimension` (2 or 3) dimensions.
  ConstantVelocity(const ConstantVelocityOptions& options, int dimension = 2, int agents = 1);
  /// The model of the listed agents only.
  ConstantVelocity(const ConstantVelocityOptions& options, int dimension, std::vector<int> agents);
  void Apply(State& state, double dt_s) const override;

 private:
  ConstantVelocityOptions options_;
  int dimension_;
  std::vector<int> agents_;
};

/// The state of agent 0 of a constant-velocity model in `dimension` (2 or 3) dimensions at rest
/// at t_s: its position block (mean position_m's first `dimension` coordinates, covariance the
/// top-left block of position_covariance_m2) then its velocity block (mean 0, variance
/// velocity_sigma_mps^2 per axis), uncorrelated.
State StartAtRest(int dimension, double t_s, const Vec3& position_m, const Eigen::Matrix3d& position_covariance_m2,
                  double velocity_sigma_mps);

}  // namespace mirage::estimation
