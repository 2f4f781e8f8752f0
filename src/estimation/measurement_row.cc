// SPDX-License-Identifier: MIT
#include "mirage/estimation/measurement_row.h"

namespace mirage::estimation {

double InnovationVariance(const State& state, const MeasurementRow& row) {
  const auto& P = state.covariance();
  double s = row.variance;
  for (int a = 0; a < row.block_count; ++a) {
    const auto ia = static_cast<std::size_t>(a);
    for (int i = 0; i < row.sizes[ia]; ++i) {
      for (int b = 0; b < row.block_count; ++b) {
        const auto ib = static_cast<std::size_t>(b);
        for (int j = 0; j < row.sizes[ib]; ++j) {
          s += row.jacobians[ia](i) * P(row.offsets[ia] + i, row.offsets[ib] + j) * row.jacobians[ib](j);
        }
      }
    }
  }
  return s;
}

}  // namespace mirage::estimation
