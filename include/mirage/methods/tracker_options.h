// SPDX-License-Identifier: MIT
// The descriptor fields MINT and SLAM share (Lafer 2014 Tab. 3.1): the association cut-off, the
// fixed range noise and the initial uncertainty, with the same keys, ranges and meaning in both
// trackers' options structs. The cut-off, the range noise and the initial velocity are derived
// from the scenario's range noise and walking speed when it states them.
#pragma once

#include "mirage/core/derived_defaults.h"
#include "mirage/core/options_descriptor.h"

namespace mirage::methods {

/// Adds cutoff_m, range_sigma_m, initial_position_sigma_m and initial_velocity_sigma_mps of an
/// options struct O that has those double members, each in [1e-9, 1e9].
template <typename O>
void AddTrackerStartFields(core::OptionsDescriptor<O>& d) {
  using core::ValueRange;
  d.Number(&O::cutoff_m,
           {.key = "cutoff_m",
            .unit = "m",
            .range = ValueRange::Positive(),
            .doc = "Cut-off distance d_c of the data association. 0.15 m (Lafer Tab. 3.1). Derived: a measured range "
                   "is off its expected range by the range noise (3 sigma: 99.7 % of a path's ranges) plus the "
                   "prediction's error, up to one step of motion when the walker turns or stops; the thesis's 0.15 "
                   "m is this at 3.3 cm of noise and 5 cm steps.",
            .derived = core::DerivedDefault{
                .formula = "3 * range_sigma_m + speed_mps * dt_s",
                .needs = {core::PhysicalKey::kRangeSigma, core::PhysicalKey::kSpeed, core::PhysicalKey::kStepTime},
                .compute = [](const core::PhysicalKeys& k) { return 3.0 * *k.range_sigma_m + *k.speed_mps * *k.dt_s; }}});
  d.Number(&O::range_sigma_m, {.key = "range_sigma_m",
                               .unit = "m",
                               .range = ValueRange::Positive(),
                               .doc = "Range standard deviation sigma_z used when variance estimation is off. 0.07 m "
                                      "(Lafer Tab. 3.1: sigma_z^2 = 0.0049 m^2); derived: the scenario's range noise.",
                               .derived = core::RangeSigmas(1.0)});
  d.Number(&O::initial_position_sigma_m,
           {.key = "initial_position_sigma_m",
            .unit = "m",
            .range = ValueRange::Positive(),
            .doc = "Standard deviation sigma_i of the initial position. 0.1 m (Lafer Tab. 3.1: 0.01 m^2)."});
  d.Number(&O::initial_velocity_sigma_mps,
           {.key = "initial_velocity_sigma_mps",
            .unit = "m/s",
            .range = ValueRange::Positive(),
            .doc = "Standard deviation of the initial velocity; the filter starts at rest (a gap in the thesis). "
                   "0.5 m/s, the maximum walking speed v_max of Lafer Tab. 3.1; derived: the walker's speed in an "
                   "unknown direction.",
            .derived = core::SpeedTimes(1.0)});
}

}  // namespace mirage::methods
