// SPDX-License-Identifier: MIT
#include "mirage/geometry/segment.h"

#include <algorithm>
#include <cmath>

namespace mirage::geometry {
namespace {
double Cross(const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); }
}  // namespace

std::optional<SegmentCrossing> CrossSegments(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b) {
  const Vec2 r = q - p;
  const Vec2 s = b - a;
  const double denom = Cross(r, s);
  // Relative parallelism threshold: sin(angle) below 1e-12 (squared, to avoid two square roots
  // in the hottest loop of the visibility test).
  if (denom * denom <= 1e-24 * r.squaredNorm() * s.squaredNorm()) return std::nullopt;
  const Vec2 ap = a - p;
  const double t = Cross(ap, s) / denom;
  const double u = Cross(ap, r) / denom;
  if (t < 0.0 || t > 1.0 || u < 0.0 || u > 1.0) return std::nullopt;
  return SegmentCrossing{t, u};
}

bool SegmentHitsCircle(const Vec2& p, const Vec2& q, const Vec2& center_m, double radius_m) {
  return DistanceToSegment(center_m, p, q) < radius_m;
}

std::optional<std::array<Vec2, 2>> IntersectCircles(const Vec2& c1, double r1, const Vec2& c2, double r2) {
  const Vec2 d = c2 - c1;
  const double l = d.norm();
  if (!std::isfinite(l) || !std::isfinite(r1) || !std::isfinite(r2)) return std::nullopt;
  if (l < 1e-9 || r1 + r2 < l || std::abs(r1 - r2) > l) return std::nullopt;
  const Vec2 u = d / l;
  // Distance from c1 along u to the chord, and the half chord.
  const double a = (l * l + r1 * r1 - r2 * r2) / (2.0 * l);
  const double h = std::sqrt(std::max(0.0, r1 * r1 - a * a));
  const Vec2 mid = c1 + a * u;
  const Vec2 n(-u.y(), u.x());
  return std::array<Vec2, 2>{mid + h * n, mid - h * n};
}

Vec2 LineNormal(const Vec2& a, const Vec2& b) {
  const Vec2 d = (b - a).normalized();
  return Vec2(-d.y(), d.x());
}

Vec2 MirrorAtLine(const Vec2& x, const Vec2& point_m, const Vec2& n) { return x - 2.0 * (x - point_m).dot(n) * n; }

Vec2 MirrorPoint(const Vec2& x, const Vec2& a, const Vec2& b) { return MirrorAtLine(x, a, LineNormal(a, b)); }

double SignedDistanceToLine(const Vec2& x, const Vec2& a, const Vec2& b) {
  const Vec2 d = (b - a).normalized();
  return Cross(d, x - a);
}

double DistanceToSegment(const Vec2& x, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 == 0.0) return (x - a).norm();
  const double t = std::clamp((x - a).dot(ab) / len2, 0.0, 1.0);
  return (x - (a + t * ab)).norm();
}

}  // namespace mirage::geometry
