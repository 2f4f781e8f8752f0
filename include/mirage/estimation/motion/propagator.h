// SPDX-License-Identifier: MIT
// Process models behind one interface: each moves the blocks it owns (mean and covariance) over
// a time step; Propagate() runs a list of them over the same dt and then stamps the state with
// the new time, so that several models (an agent's constant velocity and a map's random walk)
// share one step without each seeing a different dt.
#pragma once

#include <initializer_list>
#include <span>

#include "mirage/estimation/state.h"

namespace mirage::estimation {

/// A process model.
class Propagator {
 public:
  virtual ~Propagator() = default;
  /// Moves the blocks this model owns over dt_s >= 0 seconds; does not change the state's time.
  virtual void Apply(State& state, double dt_s) const = 0;
};

/// Moves `state` to t_s (>= state.t_s()): every model over dt = t_s - state.t_s(), in order, then
/// the state's time becomes t_s.
void Propagate(State& state, double t_s, std::span<const Propagator* const> models);
/// The same for a fixed list of models.
void Propagate(State& state, double t_s, std::initializer_list<const Propagator*> models);

}  // namespace mirage::estimation
