// SPDX-License-Identifier: MIT
#include "mirage/pipeline/los_labels.h"

#include <algorithm>

namespace mirage::pipeline {

std::optional<LosLabelCount> CountLosLabels(const core::Epoch& epoch, const std::vector<std::vector<bool>>& direct_stamps,
                                            const std::vector<int>& los_stamps) {
  const std::size_t n = epoch.toas.size();
  // Nothing labelled or no truth (also an epoch without stamp records, as on UWB sources): no count.
  if (los_stamps.empty() || direct_stamps.empty()) return std::nullopt;
  if (direct_stamps.size() != n || los_stamps.size() != n) return std::nullopt;
  LosLabelCount count;
  for (std::size_t r = 0; r < n; ++r) {
    const std::vector<bool>& direct = direct_stamps[r];
    if (direct.size() != epoch.toas[r].toa_s.size()) return std::nullopt;
    const int labelled = los_stamps[r];
    if (labelled >= static_cast<int>(direct.size())) return std::nullopt;
    const bool has_direct = std::find(direct.begin(), direct.end(), true) != direct.end();
    if (labelled >= 0 && direct[static_cast<std::size_t>(labelled)]) {
      ++count.true_positives;
    } else {
      if (labelled >= 0) ++count.false_positives;
      if (has_direct) ++count.false_negatives;
    }
  }
  return count;
}

}  // namespace mirage::pipeline
