// SPDX-License-Identifier: MIT
// 2-D segment primitives: intersection of two segments, of a segment and a circle, of two
// circles, mirroring a point at a line. Tolerances are explicit parameters of the callers that need them.
#pragma once

#include <array>
#include <optional>

#include "mirage/core/types.h"

namespace mirage::geometry {

/// Where two segments p->q and a->b cross: p + t (q - p) = a + s (b - a).
struct SegmentCrossing {
  double t = 0.0;  ///< parameter along p->q, in [0, 1]
  double s = 0.0;  ///< parameter along a->b, in [0, 1]
};

/// Crossing of segment p->q with segment a->b, if they intersect (end points included).
/// Parallel and collinear segments are reported as not crossing.
std::optional<SegmentCrossing> CrossSegments(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b);

/// True if segment p->q passes through the open disc of the given centre and radius (m).
bool SegmentHitsCircle(const Vec2& p, const Vec2& q, const Vec2& center_m, double radius_m);

/// The two intersections of the circles (c1, r1) and (c2, r2), mirror images of each other at
/// the line c1-c2 (equal where the circles touch); std::nullopt if they do not meet, the centres
/// coincide (within 1 nm) or the input is not finite.
std::optional<std::array<Vec2, 2>> IntersectCircles(const Vec2& c1, double r1, const Vec2& c2, double r2);

/// Unit normal of the line through a and b (a != b): the direction a -> b turned by +90 degrees.
Vec2 LineNormal(const Vec2& a, const Vec2& b);

/// Mirror image of point x at the line through point_m with unit normal n:
/// x - 2 ((x - point_m)^T n) n. The one mirror formula of mirage (image_source.h).
Vec2 MirrorAtLine(const Vec2& x, const Vec2& point_m, const Vec2& n);

/// Mirror image of point x at the infinite line through a and b (a != b).
Vec2 MirrorPoint(const Vec2& x, const Vec2& a, const Vec2& b);

/// Signed distance (m) of x from the line through a and b, positive on the left of a->b.
double SignedDistanceToLine(const Vec2& x, const Vec2& a, const Vec2& b);

/// Distance (m) from x to the segment a->b.
double DistanceToSegment(const Vec2& x, const Vec2& a, const Vec2& b);

}  // namespace mirage::geometry
