// SPDX-License-Identifier: MIT
#include "mirage/pipeline/experiment_config.h"

namespace mirage::pipeline {

Vec2 RunOffset(const RunGrid& grid, int run) {
  const int cells = grid.nx * grid.ny;
  const int k = run % cells;
  const int ix = k % grid.nx;
  const int iy = k / grid.nx;
  return {(ix - 0.5 * (grid.nx - 1)) * grid.spacing_m, (iy - 0.5 * (grid.ny - 1)) * grid.spacing_m};
}

}  // namespace mirage::pipeline
