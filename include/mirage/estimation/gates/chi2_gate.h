// SPDX-License-Identifier: MIT
// Chi-square (Mahalanobis) gate of a scalar innovation: nu is accepted when nu^2 <= gamma * S,
// with S the innovation variance. gamma = 9 accepts 99.7 % of consistent innovations (3 sigma).
#pragma once

namespace mirage::estimation {

/// True if the innovation nu (any unit) passes the gate of threshold gamma (>= 0; 0 disables the
/// gate) given the innovation variance s (unit^2, > 0).
inline bool InsideChi2Gate(double nu, double s, double gamma) { return gamma <= 0.0 || nu * nu <= gamma * s; }

}  // namespace mirage::estimation
