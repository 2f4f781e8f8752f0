// SPDX-License-Identifier: MIT
// Random vectors for tests, drawn in one fixed order. The order in which a constructor's
// arguments are evaluated is unspecified in C++ (g++ evaluates them last first, clang first
// first), so `Vec3(rng.Normal(), rng.Normal(), rng.Normal())` is a different vector under each
// compiler, and a test would check different cases in the release and the sanitizer builds.
// These draw the last coordinate first: the order the tests' recorded numbers were drawn in.
#pragma once

#include "mirage/core/rng.h"
#include "mirage/core/types.h"

namespace mirage::testing {

inline Vec3 NormalVec3(core::Rng& rng) {
  const double z = rng.Normal(), y = rng.Normal(), x = rng.Normal();
  return {x, y, z};
}

inline Vec2 NormalVec2(core::Rng& rng) {
  const double y = rng.Normal(), x = rng.Normal();
  return {x, y};
}

/// Each coordinate uniform in [lo, hi].
inline Vec3 UniformVec3(core::Rng& rng, const Vec3& lo, const Vec3& hi) {
  const double z = rng.Uniform(lo.z(), hi.z()), y = rng.Uniform(lo.y(), hi.y()), x = rng.Uniform(lo.x(), hi.x());
  return {x, y, z};
}

inline Vec2 UniformVec2(core::Rng& rng, const Vec2& lo, const Vec2& hi) {
  const double y = rng.Uniform(lo.y(), hi.y()), x = rng.Uniform(lo.x(), hi.x());
  return {x, y};
}

}  // namespace mirage::testing
