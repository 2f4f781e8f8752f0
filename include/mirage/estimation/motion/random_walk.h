// SPDX-License-Identifier: MIT
// Random-walk process model of static-but-drifting blocks (a map feature, a bias): the mean stays,
// each block's covariance grows by sigma^2 dt I, i.e. white noise of spectral density sigma^2
// integrated over the step.
#pragma once

#include <vector>

#include "mirage/estimation/motion/propagator.h"

namespace mirage::estimation {

/// A random walk of the given Euclidean blocks.
class RandomWalk final : public Propagator {
 public:
  /// @param sigma_per_sqrt_s the walk's standard deviation after one second (unit/sqrt(s)), >= 0.
  /// @param blocks           the blocks that walk (they must be in the state when it is applied).
  RandomWalk(double sigma_per_sqrt_s, std::vector<BlockKey> blocks);
  void Apply(State& state, double dt_s) const override;

 private:
  double sigma_per_sqrt_s_;
  std::vector<BlockKey> blocks_;
};

}  // namespace mirage::estimation
