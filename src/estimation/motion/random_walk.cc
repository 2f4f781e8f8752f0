// SPDX-License-Identifier: MIT
#include "mirage/estimation/motion/random_walk.h"

#include <Eigen/Core>

#include "mirage/estimation/covariance_ops.h"

namespace mirage::estimation {

RandomWalk::RandomWalk(double sigma_per_sqrt_s, std::vector<BlockKey> blocks)
    : sigma_per_sqrt_s_(sigma_per_sqrt_s), blocks_(std::move(blocks)) {}

void RandomWalk::Apply(State& state, double dt_s) const {
  const double q = sigma_per_sqrt_s_;
  if (q <= 0.0 || dt_s <= 0.0) return;
  for (const BlockKey& key : blocks_) {
    const int k = state.layout().At(key).size;
    const Eigen::MatrixXd Q = Eigen::MatrixXd::Identity(k, k) * q * q * dt_s;
    CovarianceOps::PropagateBlock(state, key, Eigen::MatrixXd::Identity(k, k), Q);
  }
}

}  // namespace mirage::estimation
