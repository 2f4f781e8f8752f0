// SPDX-License-Identifier: MIT
// Test helper: mirroring in the plane written out from the definition, so that the methods'
// Jacobian tests predict a path's length without the code under test (the image-source engine,
// the VA set). A wall is the line through start -> end; its normal is the direction turned by
// +90 degrees, the side to which a wall offset moves it (Kulmer Eq. 18, U = rotation by pi/2).
#pragma once

#include <span>

#include "mirage/core/types.h"

namespace mirage::methods::testing {

/// A wall's line, moved by offset_m along its normal.
struct MirrorLine {
  Vec2 start_m = Vec2::Zero();
  Vec2 end_m = Vec2::Zero();
  double offset_m = 0.0;
};

/// The unit normal of start -> end turned by +90 degrees: (-e_y, e_x).
inline Vec2 LeftNormal(const Vec2& start_m, const Vec2& end_m) {
  const Vec2 e = (end_m - start_m).normalized();
  return Vec2(-e.y(), e.x());
}

/// x mirrored at the line: x - 2 ((x - q)^T n) n with q a point of the moved line.
inline Vec2 MirrorAt(const MirrorLine& line, const Vec2& x_m) {
  const Vec2 n = LeftNormal(line.start_m, line.end_m);
  const Vec2 q = line.start_m + line.offset_m * n;
  return x_m - 2.0 * (x_m - q).dot(n) * n;
}

/// The image of a source after the lines in the order the signal meets them (the first line is
/// the bounce next to the source).
inline Vec2 ImageOf(const Vec2& source_m, std::span<const MirrorLine> lines) {
  Vec2 image_m = source_m;
  for (const MirrorLine& line : lines) image_m = MirrorAt(line, image_m);
  return image_m;
}

}  // namespace mirage::methods::testing
