// SPDX-License-Identifier: MIT
#include "mirage/geometry/image_path.h"

#include <algorithm>
#include <cassert>
#include <stdexcept>
#include <string>

#include "mirage/geometry/segment.h"

namespace mirage::geometry {
namespace {

struct Line {
  Vec2 normal;      // n_s = U e_s
  double c = 0.0;   // n_s^T x = c on the wall
};

Line WallLine(const Wall& wall) {
  const Vec2 n = WallNormal(wall);
  return {n, n.dot(wall.start_m)};
}

Vec2 Mirror(const Line& line, const Vec2& x) { return x - 2.0 * (line.normal.dot(x) - line.c) * line.normal; }

// A_s^T v = A_s v (A_s is symmetric): the reflection of a direction.
Vec2 Reflect(const Line& line, const Vec2& v) { return v - 2.0 * line.normal.dot(v) * line.normal; }

constexpr int kMaxOrder = 3;

}  // namespace

Vec2 WallNormal(const Wall& wall) {
  const Vec2 e = (wall.end_m - wall.start_m).normalized();
  return Vec2(-e.y(), e.x());
}

ImagePath ComputeImagePath(const FloorPlan& plan, std::span<const int> walls, const Vec2& tx_m, const Vec2& rx_m) {
  const auto& all = plan.walls();
  std::vector<Line> lines;
  lines.reserve(walls.size());
  Vec2 image = tx_m;
  for (const int w : walls) {
    assert(w >= 0 && static_cast<std::size_t>(w) < all.size());
    lines.push_back(WallLine(all[static_cast<std::size_t>(w)]));
    image = Mirror(lines.back(), image);
  }
  ImagePath path;
  path.image_m = image;
  const Vec2 diff = rx_m - image;
  path.length_m = diff.norm();
  // At zero length (rx on the image, only possible for order 0 with tx == rx) the direction is
  // undefined; the derivatives are left zero.
  const Vec2 u = path.length_m > 1e-12 ? Vec2(diff / path.length_m) : Vec2(Vec2::Zero());
  path.d_rx = u;
  // Walk back from the last wall: v = Psi_i^T u, starting with Psi_I = I; after all walls
  // v = Phi^T u.
  path.d_offset.assign(walls.size(), 0.0);
  Vec2 v = u;
  for (std::size_t i = walls.size(); i-- > 0;) {
    // d image / d c_i = Psi_i 2 n_i, so d length / d c_i = -u^T Psi_i 2 n_i = -2 n_i^T (Psi_i^T u).
    path.d_offset[i] = -2.0 * lines[i].normal.dot(v);
    v = Reflect(lines[i], v);
  }
  path.d_tx = -v;
  return path;
}

std::optional<std::vector<Vec2>> TraceImagePath(const FloorPlan& plan, std::span<const int> walls, const Vec2& tx_m,
                                                const Vec2& rx_m) {
  const auto& all = plan.walls();
  const std::size_t order = walls.size();
  if (order == 0 && (tx_m - rx_m).norm() < 1e-9) return std::nullopt;  // no LOS to oneself
  // The images of the transmitter after 0 .. I reflections.
  std::vector<Vec2> images{tx_m};
  for (const int w : walls) images.push_back(Mirror(WallLine(all[static_cast<std::size_t>(w)]), images.back()));
  // Back-trace from the receiver: the leg towards image i hits wall i at the reflection point.
  std::vector<Vec2> vertices(order + 2);
  vertices[order + 1] = rx_m;
  Vec2 from = rx_m;
  for (std::size_t i = order; i-- > 0;) {
    const Wall& wall = all[static_cast<std::size_t>(walls[i])];
    const auto crossing = CrossSegments(from, images[i + 1], wall.start_m, wall.end_m);
    // The image must lie behind the wall as seen from the previous vertex (t in (0, 1)), and
    // the reflection point on the finite segment.
    if (!crossing || crossing->t <= 1e-9 || crossing->t >= 1.0 - 1e-12) return std::nullopt;
    from = from + crossing->t * (images[i + 1] - from);
    vertices[i + 1] = from;
  }
  vertices[0] = tx_m;
  // Occlusion: no leg crosses another wall (the walls it starts or ends on are skipped) or an
  // obstacle.
  for (std::size_t k = 0; k <= order; ++k) {
    const int skip_a = k == 0 ? -1 : walls[k - 1];
    const int skip_b = k == order ? -1 : walls[k];
    if (!plan.IsLegClear(vertices[k], vertices[k + 1], skip_a, skip_b)) return std::nullopt;
  }
  return vertices;
}

std::vector<WallSequence> VisibleImagePaths(const FloorPlan& plan, const Vec2& tx_m, const Vec2& rx_m, int max_order) {
  if (max_order < 0 || max_order > kMaxOrder) {
    throw std::invalid_argument("VisibleImagePaths: max_order must be in 0.." + std::to_string(kMaxOrder) + ", got " +
                                std::to_string(max_order));
  }
  std::vector<WallSequence> out;
  const int count = static_cast<int>(plan.walls().size());
  WallSequence current;
  // Depth-first over sequences without immediate repeats, emitted order by order.
  for (int order = 0; order <= max_order; ++order) {
    current.assign(static_cast<std::size_t>(order), 0);
    const auto emit = [&](const auto& self, int depth) -> void {
      if (depth == order) {
        if (TraceImagePath(plan, current, tx_m, rx_m)) out.push_back(current);
        return;
      }
      for (int w = 0; w < count; ++w) {
        if (depth > 0 && current[static_cast<std::size_t>(depth - 1)] == w) continue;
        current[static_cast<std::size_t>(depth)] = w;
        self(self, depth + 1);
      }
    };
    emit(emit, 0);
  }
  return out;
}

WallSequence Reversed(const WallSequence& walls) { return WallSequence(walls.rbegin(), walls.rend()); }

}  // namespace mirage::geometry
