// SPDX-License-Identifier: MIT
// A walker's speed limit as a state inequality constraint |v| <= v_max, enforced by estimate
// projection (D. Simon and T. L. Chia, "Kalman filtering with state equality constraints", IEEE
// Trans. AES 38(1), 2002; D. Simon, "Kalman filtering with state constraints: a survey of linear
// and nonlinear algorithms", IET Control Theory Appl. 4(8), 2010: an active inequality constraint
// is projected on like an equality). The constant-velocity model (Lafer Eq. 3.16) has no bound on
// the speed: a track that follows clutter can build up a velocity no walker has, and its
// predictions then run away faster than any measurement can pull them back.
//
// Choices (not in the papers): the projection with weight W = I, i.e. the velocity mean is
// scaled back onto the disc |v| <= v_max and nothing else changes. The maximum-probability
// projection (W = P^-1) would also move the position and the map through their correlation with
// the velocity, by a correction no measurement asked for. The covariance is kept: the disc is
// convex and holds the true velocity of a walker within the limit, so the projection does not
// make the velocity error larger, and the kept covariance errs on the cautious side.
#pragma once

#include "mirage/estimation/state.h"

namespace mirage::estimation {

/// Scales the velocity mean of `agent` onto |v| = max_speed_mps when it is faster; returns
/// whether it did. max_speed_mps <= 0 disables the limit (returns false).
bool LimitSpeed(State& state, int agent, double max_speed_mps);

}  // namespace mirage::estimation
