// SPDX-License-Identifier: MIT
#include "mirage/estimation/motion/speed_limit.h"

#include <Eigen/Core>

namespace mirage::estimation {

bool LimitSpeed(State& state, int agent, double max_speed_mps) {
  if (!(max_speed_mps > 0.0)) return false;
  const BlockKey velocity(blocks::kVelocity, agent);
  // Read in place: this runs at every step, and State::Mean would copy into a heap vector.
  const Eigen::Vector2d v_mps = state.mean().segment<2>(state.layout().At(velocity).mean_offset);
  const double speed_mps = v_mps.norm();
  if (!(speed_mps > max_speed_mps)) return false;
  state.SetMean(velocity, v_mps * (max_speed_mps / speed_mps));
  return true;
}

}  // namespace mirage::estimation
