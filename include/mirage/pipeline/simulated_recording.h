// SPDX-License-Identifier: MIT
// One simulated run as a recording (anchors and ranges, or microphones and arrival-time stamps;
// truth), as `mirage simulate` writes it: exactly the range sets or stamps the runner's estimator
// sees in that run, so that replaying the files gives the same track.
#pragma once

#include "mirage/pipeline/experiment.h"
#include "mirage/pipeline/recording.h"

namespace mirage::pipeline {

/// Run `run` of trajectory `trajectory` of a range-set simulation (CIRs with extraction,
/// range-level or ranging). Epochs without any range of any anchor cannot be written to
/// ranges.csv and are left out; the truth keeps every epoch.
/// For an acoustic simulation (MeasurementModel::kAcoustic) the recording has the stamps of every
/// emission (one step per emission, the epoch's time and records), without the inertial records
/// (the caller refuses scenarios that have them); an emission without any stamp is left out.
Recording SimulateRecording(const Experiment& experiment, int trajectory, int run);

}  // namespace mirage::pipeline
