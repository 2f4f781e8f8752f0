// SPDX-License-Identifier: MIT
// The `measurements` section's readers of the models with their own geometry (io/scenario.cc
// reads the others): the acoustic hall and the UWB TDOA room with its obstacles.
#pragma once

#include "mirage/core/physical_keys.h"
#include "mirage/io/yaml_reader.h"
#include "mirage/pipeline/experiment.h"

namespace mirage::io {

/// `measurements: {model: acoustic, ...}`: the hall's reflectors (the floor plan's walls, floor
/// and ceiling, then the partitions and tables, 3-D), the virtual-sender episodes that name them,
/// the inertial input and the stamp simulator's keys. Needs the medium, the floor plan and the
/// trajectories read.
void ReadAcousticModel(YamlMap& m, pipeline::Experiment& e, const core::PhysicalKeys& keys);

/// `measurements: {model: uwb_tdoa, ...}`: the simulator's keys and the box obstacles whose
/// crossing biases a leg (no trajectory may pass through one). Needs the medium, the floor plan,
/// the anchors, the trajectories and the run grid read.
void ReadUwbTdoaModel(YamlMap& m, pipeline::Experiment& e, const core::PhysicalKeys& keys);

}  // namespace mirage::io
