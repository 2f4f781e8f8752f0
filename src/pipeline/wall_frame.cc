// SPDX-License-Identifier: MIT
#include "mirage/pipeline/wall_frame.h"

#include <algorithm>

#include <Eigen/Cholesky>

#include "mirage/geometry/image_source.h"

namespace mirage::pipeline {

WallFrame ComputeWallFrame(const geometry::FloorPlan& given, std::span<const methods::WallEstimate> walls,
                           std::span<const double> true_offset_m) {
  WallFrame frame;
  frame.wall_error_m.assign(walls.size(), 0.0);
  const bool estimated = std::any_of(walls.begin(), walls.end(), [](const auto& w) { return w.sigma_m > 0.0; });
  if (!estimated) {
    // Walls fixed at the given plan, which defines the frame: the error is the plan's.
    for (std::size_t s = 0; s < walls.size(); ++s) frame.wall_error_m[s] = -true_offset_m[s];
    return frame;
  }
  Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
  Vec2 b = Vec2::Zero();
  for (std::size_t s = 0; s < walls.size(); ++s) {
    frame.wall_error_m[s] = walls[s].offset_m - true_offset_m[s];
    const Vec2 n = geometry::WallNormal(given.walls()[s]);
    const double sigma = std::max(walls[s].sigma_m, 1e-6);
    A += n * n.transpose() / (sigma * sigma);
    b += n * frame.wall_error_m[s] / (sigma * sigma);
  }
  frame.translation_m = A.ldlt().solve(b);
  for (std::size_t s = 0; s < walls.size(); ++s) {
    frame.wall_error_m[s] -= geometry::WallNormal(given.walls()[s]).dot(frame.translation_m);
  }
  return frame;
}

}  // namespace mirage::pipeline
