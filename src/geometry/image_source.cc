// SPDX-License-Identifier: MIT
#include "mirage/geometry/image_source.h"

#include <array>
#include <cassert>
#include <cmath>

#include "mirage/geometry/segment.h"

namespace mirage::geometry {
namespace {

using Vec2Chain = std::array<Vec2, kMaxImageOrder + 2>;

const Wall& WallOf(const FloorPlan& plan, SurfaceId wall) {
  assert(wall >= 0 && static_cast<std::size_t>(wall) < plan.walls().size());
  return plan.walls()[static_cast<std::size_t>(wall)];
}

bool Collinear(const Wall& a, const Wall& b) {
  return std::abs(SignedDistanceToLine(b.start_m, a.start_m, a.end_m)) < kOnLineTolerance_m &&
         std::abs(SignedDistanceToLine(b.end_m, a.start_m, a.end_m)) < kOnLineTolerance_m;
}

// The first half of the trace: the reflection points, back from the receiver. vertices[k] (k =
// 1..I) is the reflection on walls[I - k]; with kFractions, fractions[k] is the t at which it
// splits the leg from vertices[k - 1] towards its image (a template parameter, not a run-time
// one, so that the planar trace, the hot loop of MINT and SLAM, carries no 3-D bookkeeping). All
// wall crossings come before any occlusion test because they are cheap and reject most sequences.
template <bool kFractions>
bool ReflectionPoints(const FloorPlan& plan, std::span<const SurfaceId> walls, std::span<const Vec2> images_m,
                      const Vec2& rx_m, std::span<Vec2> vertices_m, double* fractions) {
  const std::size_t order = walls.size();
  assert(order <= static_cast<std::size_t>(kMaxImageOrder));
  assert(images_m.size() == order + 1 && vertices_m.size() == order + 2);
  vertices_m[0] = rx_m;
  for (std::size_t k = 1; k <= order; ++k) {
    const std::size_t i = order - k;  // the wall met k-th counted from the receiver
    const Wall& wall = WallOf(plan, walls[i]);
    const Vec2& from = vertices_m[k - 1];
    const Vec2& image = images_m[i + 1];
    const auto crossing = CrossSegments(from, image, wall.start_m, wall.end_m);
    if (!crossing || crossing->t <= kLegFractionTolerance || crossing->t >= 1.0 - kLegFractionTolerance) return false;
    vertices_m[k] = from + crossing->t * (image - from);
    if constexpr (kFractions) fractions[k] = crossing->t;
  }
  vertices_m[order + 1] = images_m[0];
  return true;
}

// The second half: no leg crosses a wall other than the ones it starts or ends on, or an obstacle.
bool LegsClear(const FloorPlan& plan, std::span<const SurfaceId> walls, std::span<const Vec2> vertices_m) {
  const std::size_t order = walls.size();
  for (std::size_t k = 0; k <= order; ++k) {
    const int skip_a = k == 0 ? -1 : walls[order - k];
    const int skip_b = k == order ? -1 : walls[order - k - 1];
    if (!plan.IsLegClear(vertices_m[k], vertices_m[k + 1], skip_a, skip_b)) return false;
  }
  return true;
}

// v -> Phi^T v, writing d length / d c_i = -2 n_i^T Psi_i^T v into d_offset: the walk back from
// the last wall (Psi_I = I). d image / d c_i = Psi_i 2 n_i, so d length / d c_i = -u^T Psi_i 2 n_i.
Vec2 BackPropagate(std::span<const Vec2> normals, const Vec2& u, std::vector<double>& d_offset) {
  d_offset.assign(normals.size(), 0.0);
  Vec2 v = u;
  for (std::size_t i = normals.size(); i-- > 0;) {
    const Vec2& n = normals[i];
    d_offset[i] = -2.0 * n.dot(v);
    v = v - 2.0 * n.dot(v) * n;  // A_s^T v = A_s v: the reflection of a direction
  }
  return v;
}

// The planar image of tx after the walls, with the walls' normals for BackPropagate.
Vec2 ImageWithNormals(const FloorPlan& plan, std::span<const SurfaceId> walls, const Vec2& tx_m,
                      std::array<Vec2, kMaxImageOrder>& normals) {
  assert(walls.size() <= static_cast<std::size_t>(kMaxImageOrder));
  Vec2 image = tx_m;
  for (std::size_t i = 0; i < walls.size(); ++i) {
    const Wall& wall = WallOf(plan, walls[i]);
    normals[i] = WallNormal(wall);
    image = MirrorAtLine(image, wall.start_m, normals[i]);
  }
  return image;
}

// The image chain of tx with the generation rules applied; false if a mirror breaks them.
bool RealizableChain(const FloorPlan& plan, std::span<const SurfaceId> walls, const Vec2& tx_m,
                     std::span<Vec2> images_m) {
  images_m[0] = tx_m;
  for (std::size_t k = 0; k < walls.size(); ++k) {
    if (!CanMirror(plan, k == 0 ? -1 : walls[k - 1], walls[k], images_m[k])) return false;
    images_m[k + 1] = MirrorAtWall(WallOf(plan, walls[k]), images_m[k]);
  }
  return true;
}

// Depth-first over the sequences the generation rules allow, extending each image chain by one
// wall; `exists(walls, images)` decides whether a sequence's path exists. Emitted order by order,
// each order in lexicographic wall order (the depth-first visiting order).
template <typename Exists>
std::vector<WallSequence> Enumerate(const FloorPlan& plan, const Vec2& tx_m, int max_order, const Exists& exists) {
  assert(max_order >= 0 && max_order <= kMaxImageOrder);
  std::vector<std::vector<WallSequence>> by_order(static_cast<std::size_t>(max_order) + 1);
  const int count = static_cast<int>(plan.walls().size());
  WallSequence current;
  std::array<Vec2, kMaxImageOrder + 1> images;
  images[0] = tx_m;
  const auto visit = [&](const auto& self, int depth) -> void {
    const auto d = static_cast<std::size_t>(depth);
    if (exists(std::span<const SurfaceId>(current), std::span<const Vec2>(images.data(), d + 1))) {
      by_order[d].push_back(current);
    }
    if (depth == max_order) return;
    for (int w = 0; w < count; ++w) {
      if (!CanMirror(plan, depth == 0 ? -1 : current.back(), w, images[d])) continue;
      images[d + 1] = MirrorAtWall(WallOf(plan, w), images[d]);
      current.push_back(w);
      self(self, depth + 1);
      current.pop_back();
    }
  };
  visit(visit, 0);
  std::vector<WallSequence> out;
  for (auto& sequences : by_order) {
    for (auto& s : sequences) out.push_back(std::move(s));
  }
  return out;
}

Vec3 WithHeight(const Vec2& xy_m, double z_m) { return Vec3(xy_m.x(), xy_m.y(), z_m); }

}  // namespace

Vec2 WallNormal(const Wall& wall) { return LineNormal(wall.start_m, wall.end_m); }

Vec2 MirrorAtWall(const Wall& wall, const Vec2& point_m) {
  return MirrorAtLine(point_m, wall.start_m, WallNormal(wall));
}

Vec3 MirrorAtWall(const Wall& wall, const Vec3& point_m) {
  return WithHeight(MirrorAtWall(wall, Vec2(point_m.head<2>())), point_m.z());
}

bool CanMirror(const FloorPlan& plan, SurfaceId previous_wall, SurfaceId wall, const Vec2& image_m) {
  const Wall& w = WallOf(plan, wall);
  if (previous_wall >= 0 && (wall == previous_wall || Collinear(w, WallOf(plan, previous_wall)))) return false;
  return std::abs(SignedDistanceToLine(image_m, w.start_m, w.end_m)) >= kOnLineTolerance_m;
}

std::vector<Vec2> ImageChain(const FloorPlan& plan, std::span<const SurfaceId> walls, const Vec2& source_m) {
  std::vector<Vec2> images{source_m};
  for (const SurfaceId w : walls) images.push_back(MirrorAtWall(WallOf(plan, w), images.back()));
  return images;
}

std::vector<Vec3> ImageChain(const FloorPlan& plan, std::span<const SurfaceId> walls, const Vec3& source_m) {
  std::vector<Vec3> images{source_m};
  for (const SurfaceId w : walls) images.push_back(MirrorAtWall(WallOf(plan, w), images.back()));
  return images;
}

bool TraceImageChain(const FloorPlan& plan, std::span<const SurfaceId> walls, std::span<const Vec2> images_m,
                     const Vec2& rx_m, std::span<Vec2> vertices_m) {
  if (walls.empty() && (rx_m - images_m[0]).norm() < kOnLineTolerance_m) return false;
  return ReflectionPoints<false>(plan, walls, images_m, rx_m, vertices_m, nullptr) &&
         LegsClear(plan, walls, vertices_m);
}

bool TraceImageChain(const FloorPlan& plan, std::span<const SurfaceId> walls, std::span<const Vec3> images_m,
                     const Vec3& rx_m, std::span<Vec3> vertices_m) {
  const std::size_t order = walls.size();
  assert(order <= static_cast<std::size_t>(kMaxImageOrder));
  assert(images_m.size() == order + 1 && vertices_m.size() == order + 2);
  if (order == 0 && (rx_m - images_m[0]).norm() < kOnLineTolerance_m) return false;
  std::array<Vec2, kMaxImageOrder + 1> images_xy;
  for (std::size_t k = 0; k <= order; ++k) images_xy[k] = images_m[k].head<2>();
  Vec2Chain vertices_xy;
  std::array<double, kMaxImageOrder + 2> fractions{};
  const std::span<Vec2> vertices(vertices_xy.data(), order + 2);
  if (!ReflectionPoints<true>(plan, walls, std::span<const Vec2>(images_xy.data(), order + 1), rx_m.head<2>(), vertices,
                        fractions.data())) {
    return false;
  }
  // The unfolded path is the straight line rx -> (a_I, z_tx): the leg from reflection k - 1
  // towards its image unfolds into the rest of that line, so reflection k lies at the fraction
  // f_k = f_{k-1} + t_k (1 - f_{k-1}) of it, and its height is z_rx + f_k (z_tx - z_rx).
  const double z_rx_m = rx_m.z();
  const double dz_m = images_m[0].z() - z_rx_m;
  double f = 0.0;
  vertices_m[0] = rx_m;
  for (std::size_t k = 1; k <= order; ++k) {
    f += fractions[k] * (1.0 - f);
    const double z_m = z_rx_m + f * dz_m;
    if (z_m < plan.floor_z_m() || z_m > plan.ceiling_z_m()) return false;
    vertices_m[k] = WithHeight(vertices_xy[k], z_m);
  }
  vertices_m[order + 1] = images_m[0];
  return LegsClear(plan, walls, vertices);
}

ImagePath ComputeImagePath(const FloorPlan& plan, std::span<const SurfaceId> walls, const Vec2& tx_m,
                           const Vec2& rx_m) {
  std::array<Vec2, kMaxImageOrder> normals;
  ImagePath path;
  path.image_m = ImageWithNormals(plan, walls, tx_m, normals);
  const Vec2 diff = rx_m - path.image_m;
  path.length_m = diff.norm();
  const Vec2 u = path.length_m > 1e-12 ? Vec2(diff / path.length_m) : Vec2(Vec2::Zero());
  path.d_rx = u;
  path.d_tx = -BackPropagate(std::span<const Vec2>(normals.data(), walls.size()), u, path.d_offset);
  return path;
}

ImagePath3 ComputeImagePath(const FloorPlan& plan, std::span<const SurfaceId> walls, const Vec3& tx_m,
                            const Vec3& rx_m) {
  std::array<Vec2, kMaxImageOrder> normals;
  ImagePath3 path;
  path.image_m = WithHeight(ImageWithNormals(plan, walls, tx_m.head<2>(), normals), tx_m.z());
  const Vec3 diff = rx_m - path.image_m;
  path.length_m = diff.norm();
  const Vec3 u = path.length_m > 1e-12 ? Vec3(diff / path.length_m) : Vec3(Vec3::Zero());
  path.d_rx = u;
  // The walls act on (x, y) only: the planar part of u walks back through them, z passes as is.
  const Vec2 v = BackPropagate(std::span<const Vec2>(normals.data(), walls.size()), u.head<2>(), path.d_offset);
  path.d_tx = -WithHeight(v, u.z());
  return path;
}

std::optional<std::vector<Vec2>> TraceImagePath(const FloorPlan& plan, std::span<const SurfaceId> walls,
                                                const Vec2& tx_m, const Vec2& rx_m) {
  assert(walls.size() <= static_cast<std::size_t>(kMaxImageOrder));
  const std::size_t order = walls.size();
  std::array<Vec2, kMaxImageOrder + 1> images;
  Vec2Chain vertices;
  if (!RealizableChain(plan, walls, tx_m, std::span<Vec2>(images.data(), order + 1)) ||
      !TraceImageChain(plan, walls, std::span<const Vec2>(images.data(), order + 1), rx_m,
                       std::span<Vec2>(vertices.data(), order + 2))) {
    return std::nullopt;
  }
  return std::vector<Vec2>(vertices.rend() - static_cast<std::ptrdiff_t>(order + 2), vertices.rend());
}

std::optional<std::vector<Vec3>> TraceImagePath(const FloorPlan& plan, std::span<const SurfaceId> walls,
                                                const Vec3& tx_m, const Vec3& rx_m) {
  assert(walls.size() <= static_cast<std::size_t>(kMaxImageOrder));
  const std::size_t order = walls.size();
  std::array<Vec2, kMaxImageOrder + 1> images_xy;
  if (!RealizableChain(plan, walls, tx_m.head<2>(), std::span<Vec2>(images_xy.data(), order + 1))) return std::nullopt;
  std::array<Vec3, kMaxImageOrder + 1> images;
  for (std::size_t k = 0; k <= order; ++k) images[k] = WithHeight(images_xy[k], tx_m.z());
  std::array<Vec3, kMaxImageOrder + 2> vertices;
  if (!TraceImageChain(plan, walls, std::span<const Vec3>(images.data(), order + 1), rx_m,
                       std::span<Vec3>(vertices.data(), order + 2))) {
    return std::nullopt;
  }
  return std::vector<Vec3>(vertices.rend() - static_cast<std::ptrdiff_t>(order + 2), vertices.rend());
}

std::vector<WallSequence> VisibleImagePaths(const FloorPlan& plan, const Vec2& tx_m, const Vec2& rx_m, int max_order) {
  Vec2Chain vertices;
  return Enumerate(plan, tx_m, max_order, [&](std::span<const SurfaceId> walls, std::span<const Vec2> images) {
    return TraceImageChain(plan, walls, images, rx_m, std::span<Vec2>(vertices.data(), walls.size() + 2));
  });
}

std::vector<WallSequence> VisibleImagePaths(const FloorPlan& plan, const Vec3& tx_m, const Vec3& rx_m, int max_order) {
  std::array<Vec3, kMaxImageOrder + 1> images3;
  std::array<Vec3, kMaxImageOrder + 2> vertices;
  return Enumerate(plan, tx_m.head<2>(), max_order, [&](std::span<const SurfaceId> walls, std::span<const Vec2> images) {
    for (std::size_t k = 0; k < images.size(); ++k) images3[k] = WithHeight(images[k], tx_m.z());
    return TraceImageChain(plan, walls, std::span<const Vec3>(images3.data(), images.size()), rx_m,
                           std::span<Vec3>(vertices.data(), walls.size() + 2));
  });
}

WallSequence Reversed(const WallSequence& walls) { return WallSequence(walls.rbegin(), walls.rend()); }

}  // namespace mirage::geometry
