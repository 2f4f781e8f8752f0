// SPDX-License-Identifier: MIT
#include "mirage/estimation/motion/propagator.h"

#include <cassert>

#include "mirage/estimation/covariance_ops.h"

namespace mirage::estimation {

void Propagate(State& state, double t_s, std::span<const Propagator* const> models) {
  const double dt_s = t_s - state.t_s();
  assert(dt_s >= 0.0);
  for (const Propagator* model : models) model->Apply(state, dt_s);
  CovarianceOps::Stamp(state, t_s);
}

void Propagate(State& state, double t_s, std::initializer_list<const Propagator*> models) {
  Propagate(state, t_s, std::span<const Propagator* const>(models.begin(), models.size()));
}

}  // namespace mirage::estimation
