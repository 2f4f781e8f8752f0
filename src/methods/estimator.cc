// SPDX-License-Identifier: MIT
#include "mirage/methods/estimator.h"

namespace mirage::methods {

bool Estimator::InitializeFromEpoch(const core::Epoch& /*epoch*/) { return false; }

std::vector<std::vector<double>> Estimator::PosteriorBound(const BoundInput& /*truth*/) const { return {}; }

}  // namespace mirage::methods
