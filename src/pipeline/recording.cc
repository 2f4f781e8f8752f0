// SPDX-License-Identifier: MIT
#include "mirage/pipeline/recording.h"

#include <algorithm>

namespace mirage::pipeline {

std::optional<Vec3> Recording::TruthAt(double t_s) const {
  if (truth.empty() || t_s < truth.front().t_s || t_s > truth.back().t_s) return std::nullopt;
  const auto after = std::lower_bound(truth.begin(), truth.end(), t_s,
                                      [](const TruthSample& s, double t) { return s.t_s < t; });
  if (after->t_s == t_s || after == truth.begin()) return after->position_m;
  const auto before = after - 1;
  const double w = (t_s - before->t_s) / (after->t_s - before->t_s);
  return before->position_m + w * (after->position_m - before->position_m);
}

}  // namespace mirage::pipeline
