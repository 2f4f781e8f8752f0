// SPDX-License-Identifier: MIT
// Short names for the Eigen and complex types used across mirage.
#pragma once

#include <complex>

#include <Eigen/Core>

namespace mirage {

/// 2-D vector, metres unless its name says otherwise.
using Vec2 = Eigen::Vector2d;
/// 3-D vector, metres unless its name says otherwise; z is up.
using Vec3 = Eigen::Vector3d;
/// Complex double, as used for baseband samples and path amplitudes.
using Complex = std::complex<double>;

}  // namespace mirage
