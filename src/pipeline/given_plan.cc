// SPDX-License-Identifier: MIT
#include "mirage/pipeline/given_plan.h"

#include "mirage/geometry/image_source.h"

namespace mirage::pipeline {

GivenPlan MakeGivenPlan(const Experiment& e, core::Rng rng) {
  GivenPlan out;
  std::vector<geometry::Wall> walls;
  const auto& truth = e.plan.walls();
  for (std::size_t s = 0; s < truth.size(); ++s) {
    // One draw per statement: the order of a constructor's arguments is unspecified (g++ draws
    // the last first, clang the first), so the plan would differ between compilers. y first: the
    // order the published numbers were drawn in.
    const double unit_y = rng.Uniform(-0.5, 0.5);
    const double unit_x = rng.Uniform(-0.5, 0.5);
    const Vec2 unit(unit_x, unit_y);
    if (!e.in_plan[s]) continue;
    Vec2 shift = e.plan_error.wall_shift_m * unit;
    const Vec2 n = geometry::WallNormal(truth[s]);
    if (e.plan_error.bias_m != 0.0 && static_cast<int>(s) == e.plan_error.biased_wall) {
      shift += e.plan_error.bias_m * n;
      out.biased = static_cast<int>(walls.size());
    }
    geometry::Wall w = truth[s];
    w.start_m += shift;
    w.end_m += shift;
    walls.push_back(w);
    out.true_index.push_back(static_cast<int>(s));
    out.true_offset_m.push_back(-n.dot(shift));
  }
  out.plan = geometry::FloorPlan(std::move(walls), e.plan.obstacles(), e.plan.floor_z_m(), e.plan.ceiling_z_m());
  return out;
}

geometry::FloorPlan TrueGivenWalls(const Experiment& e) {
  std::vector<geometry::Wall> walls;
  for (std::size_t s = 0; s < e.plan.walls().size(); ++s) {
    if (e.in_plan[s]) walls.push_back(e.plan.walls()[s]);
  }
  return geometry::FloorPlan(std::move(walls), e.plan.obstacles(), e.plan.floor_z_m(), e.plan.ceiling_z_m());
}

}  // namespace mirage::pipeline
