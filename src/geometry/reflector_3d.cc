// SPDX-License-Identifier: MIT
#include "mirage/geometry/reflector_3d.h"

#include <array>
#include <cassert>
#include <cmath>
#include <string>
#include <utility>

namespace mirage::geometry {
namespace {

// Tolerances, the same as image_source.h's: a point this close to a plane lies on it (m); a
// crossing must split its segment at a fraction in (kFraction, 1 - kFraction); a crossing this
// far outside a rectangle's edge still hits it (m), so that a leg grazing an edge counts as
// hitting it both when it reflects and when it is blocked.
constexpr double kOnPlane_m = 1e-9;
constexpr double kFraction = 1e-9;
constexpr double kEdge_m = 1e-9;
constexpr int kMaxOrder = 3;

using ImageChain = std::array<Vec3, kMaxOrder + 1>;   // a_0 = tx .. a_I
using VertexChain = std::array<Vec3, kMaxOrder + 2>;  // tx, reflection points, rx

const Reflector3& At(std::span<const Reflector3> reflectors, int index) {
  assert(index >= 0 && static_cast<std::size_t>(index) < reflectors.size());
  return reflectors[static_cast<std::size_t>(index)];
}

// The trace without allocations: images[0..I] and vertices[0..I+1]; false when the path does not
// exist. All reflection points are found before any blocking test, since those are cheap and
// reject most sequences.
bool Trace(std::span<const Reflector3> reflectors, std::span<const int> surfaces, const Vec3& tx_m, const Vec3& rx_m,
           ImageChain& images, VertexChain& vertices) {
  const std::size_t order = surfaces.size();
  assert(order <= static_cast<std::size_t>(kMaxOrder));
  images[0] = tx_m;
  for (std::size_t k = 0; k < order; ++k) {
    if (k > 0 && surfaces[k] == surfaces[k - 1]) return false;
    const Reflector3& r = At(reflectors, surfaces[k]);
    // An image on the plane mirrors to itself: the path would graze the plane.
    if (std::abs((images[k] - r.origin_m).dot(r.normal())) < kOnPlane_m) return false;
    images[k + 1] = MirrorAtPlane(r, images[k]);
  }
  // A receiver on top of the source has no path (as in image_source.h).
  if ((rx_m - images[order]).norm() < kOnPlane_m) return false;
  // Back from the receiver: vertices[order + 1] = rx, then the reflection on s_I, s_{I-1}, ...
  vertices[order + 1] = rx_m;
  for (std::size_t k = order; k >= 1; --k) {
    const Vec3& from = vertices[k + 1];
    const auto t = CrossingFraction(At(reflectors, surfaces[k - 1]), from, images[k]);
    if (!t) return false;
    vertices[k] = from + *t * (images[k] - from);
  }
  vertices[0] = tx_m;
  // Leg k runs from vertices[k] to vertices[k + 1]; it starts on surface k - 1 and ends on k.
  for (std::size_t k = 0; k <= order; ++k) {
    const int skip_a = k == 0 ? -1 : surfaces[k - 1];
    const int skip_b = k == order ? -1 : surfaces[k];
    if (!IsSegmentClear(reflectors, vertices[k], vertices[k + 1], skip_a, skip_b)) return false;
  }
  return true;
}

SpecularPath3 MakePath(std::span<const Reflector3> reflectors, std::span<const int> surfaces, const ImageChain& images,
                       const VertexChain& vertices) {
  const std::size_t order = surfaces.size();
  SpecularPath3 path;
  path.surfaces.assign(surfaces.begin(), surfaces.end());
  path.image_m = images[order];
  path.length_m = (vertices[order + 1] - images[order]).norm();
  path.vertices_m.assign(vertices.begin(), vertices.begin() + static_cast<std::ptrdiff_t>(order + 2));
  for (const int s : surfaces) path.reflection_gain *= At(reflectors, s).reflection_coeff;
  return path;
}

}  // namespace

Reflector3 HorizontalReflector(std::string name, const Vec2& centre_m, double x_half_m, double y_half_m, double z_m,
                               double reflection_coeff) {
  assert(x_half_m > 0.0 && y_half_m > 0.0);
  Reflector3 r;
  r.name = std::move(name);
  r.origin_m = Vec3(centre_m.x(), centre_m.y(), z_m);
  r.u = Vec3::UnitX();
  r.v = Vec3::UnitY();
  r.u_half_m = x_half_m;
  r.v_half_m = y_half_m;
  r.reflection_coeff = reflection_coeff;
  return r;
}

Reflector3 VerticalReflector(std::string name, const Vec2& a_m, const Vec2& b_m, double z0_m, double z1_m,
                             double reflection_coeff) {
  const Vec2 ab = b_m - a_m;
  assert(ab.norm() > 0.0 && z1_m > z0_m);
  const Vec2 mid = 0.5 * (a_m + b_m);
  Reflector3 r;
  r.name = std::move(name);
  r.origin_m = Vec3(mid.x(), mid.y(), 0.5 * (z0_m + z1_m));
  r.u = Vec3(ab.x(), ab.y(), 0.0).normalized();
  r.v = Vec3::UnitZ();
  r.u_half_m = 0.5 * ab.norm();
  r.v_half_m = 0.5 * (z1_m - z0_m);
  r.reflection_coeff = reflection_coeff;
  return r;
}

std::vector<Reflector3> BoxReflectors(const std::string& name, const Vec3& lo_m, const Vec3& hi_m, double reflection_coeff) {
  assert((hi_m - lo_m).minCoeff() > 0.0);
  const Vec2 centre_m = 0.5 * (lo_m + hi_m).head<2>();
  const Vec3 half_m = 0.5 * (hi_m - lo_m);
  const Vec2 a(lo_m.x(), lo_m.y()), b(hi_m.x(), lo_m.y()), c(hi_m.x(), hi_m.y()), d(lo_m.x(), hi_m.y());
  return {HorizontalReflector(name + " bottom", centre_m, half_m.x(), half_m.y(), lo_m.z(), reflection_coeff),
          HorizontalReflector(name + " top", centre_m, half_m.x(), half_m.y(), hi_m.z(), reflection_coeff),
          VerticalReflector(name + " y-", a, b, lo_m.z(), hi_m.z(), reflection_coeff),
          VerticalReflector(name + " x+", b, c, lo_m.z(), hi_m.z(), reflection_coeff),
          VerticalReflector(name + " y+", c, d, lo_m.z(), hi_m.z(), reflection_coeff),
          VerticalReflector(name + " x-", d, a, lo_m.z(), hi_m.z(), reflection_coeff)};
}

std::vector<Reflector3> ShoeboxReflectors(double length_x_m, double length_y_m, double height_m,
                                          double reflection_coeff) {
  const double lx = length_x_m, ly = length_y_m, h = height_m;
  const Vec2 centre(0.5 * lx, 0.5 * ly);
  return {HorizontalReflector("floor", centre, 0.5 * lx, 0.5 * ly, 0.0, reflection_coeff),
          HorizontalReflector("ceiling", centre, 0.5 * lx, 0.5 * ly, h, reflection_coeff),
          VerticalReflector("y=0", Vec2(0, 0), Vec2(lx, 0), 0.0, h, reflection_coeff),
          VerticalReflector("x=max", Vec2(lx, 0), Vec2(lx, ly), 0.0, h, reflection_coeff),
          VerticalReflector("y=max", Vec2(lx, ly), Vec2(0, ly), 0.0, h, reflection_coeff),
          VerticalReflector("x=0", Vec2(0, ly), Vec2(0, 0), 0.0, h, reflection_coeff)};
}

std::vector<Reflector3> ReflectorsFromPlan(const FloorPlan& plan, double ceiling_floor_coeff) {
  assert(std::isfinite(plan.ceiling_z_m()) && "ReflectorsFromPlan needs a plan with a ceiling");
  const double z0 = plan.floor_z_m(), z1 = plan.ceiling_z_m();
  std::vector<Reflector3> out;
  out.reserve(plan.walls().size() + 2);
  for (std::size_t i = 0; i < plan.walls().size(); ++i) {
    const Wall& w = plan.walls()[i];
    std::string name = "W";  // appended, not "W" + ...: GCC 12 warns falsely (-Wrestrict) on that
    name += std::to_string(i + 1);
    out.push_back(VerticalReflector(std::move(name), w.start_m, w.end_m, z0, z1, w.reflection_coeff));
  }
  const auto [lo, hi] = plan.Bounds();
  const Vec2 centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  out.push_back(HorizontalReflector("floor", centre, half.x(), half.y(), z0, ceiling_floor_coeff));
  out.push_back(HorizontalReflector("ceiling", centre, half.x(), half.y(), z1, ceiling_floor_coeff));
  return out;
}

Vec3 MirrorAtPlane(const Reflector3& reflector, const Vec3& point_m) {
  // Eq. (3.34) with the sign made independent of the normal's orientation (digest typo 2).
  const Vec3 n = reflector.normal();
  return point_m - 2.0 * (point_m - reflector.origin_m).dot(n) * n;
}

std::optional<double> CrossingFraction(const Reflector3& reflector, const Vec3& a_m, const Vec3& b_m) {
  const Vec3 n = reflector.normal();
  const double da = (a_m - reflector.origin_m).dot(n);
  const double db = (b_m - reflector.origin_m).dot(n);
  // Both ends on one side (or on the plane): no crossing. This also rejects parallel segments.
  if ((da > 0.0) == (db > 0.0) || da == 0.0 || db == 0.0) return std::nullopt;
  const double t = da / (da - db);
  if (!(t > kFraction && t < 1.0 - kFraction)) return std::nullopt;
  const Vec3 p = a_m + t * (b_m - a_m) - reflector.origin_m;
  if (std::abs(p.dot(reflector.u)) > reflector.u_half_m + kEdge_m) return std::nullopt;
  if (std::abs(p.dot(reflector.v)) > reflector.v_half_m + kEdge_m) return std::nullopt;
  return t;
}

bool IsSegmentClear(std::span<const Reflector3> reflectors, const Vec3& a_m, const Vec3& b_m, int skip_a, int skip_b) {
  for (std::size_t i = 0; i < reflectors.size(); ++i) {
    const int index = static_cast<int>(i);
    if (index == skip_a || index == skip_b || !reflectors[i].blocks) continue;
    if (CrossingFraction(reflectors[i], a_m, b_m)) return false;
  }
  return true;
}

std::optional<SpecularPath3> TraceSpecularPath(std::span<const Reflector3> reflectors, std::span<const int> surfaces,
                                               const Vec3& tx_m, const Vec3& rx_m) {
  if (surfaces.size() > static_cast<std::size_t>(kMaxOrder)) return std::nullopt;
  ImageChain images;
  VertexChain vertices;
  if (!Trace(reflectors, surfaces, tx_m, rx_m, images, vertices)) return std::nullopt;
  return MakePath(reflectors, surfaces, images, vertices);
}

std::vector<SpecularPath3> SpecularPaths3(std::span<const Reflector3> reflectors, const Vec3& tx_m, const Vec3& rx_m,
                                          int max_order) {
  assert(max_order >= 0 && max_order <= kMaxOrder);
  std::vector<SpecularPath3> out;
  ImageChain images;
  VertexChain vertices;
  const int n = static_cast<int>(reflectors.size());
  std::array<int, kMaxOrder> seq{};
  for (int order = 0; order <= max_order; ++order) {
    if (order > 0 && n == 0) break;
    // An odometer over [0, n)^order in lexicographic order; back-to-back repeats are rejected by
    // Trace before any geometry is done.
    seq.fill(0);
    while (true) {
      const std::span<const int> surfaces(seq.data(), static_cast<std::size_t>(order));
      if (Trace(reflectors, surfaces, tx_m, rx_m, images, vertices)) {
        out.push_back(MakePath(reflectors, surfaces, images, vertices));
      }
      int digit = order - 1;
      while (digit >= 0 && ++seq[static_cast<std::size_t>(digit)] == n) seq[static_cast<std::size_t>(digit--)] = 0;
      if (digit < 0) break;
    }
  }
  return out;
}

}  // namespace mirage::geometry
