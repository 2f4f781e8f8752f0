// SPDX-License-Identifier: MIT
// Measurement records: one plain struct per kind of measurement, each stamped with its time t_s
// (seconds from the start of the recording) and the id of its sensor or link (string ids, as in
// the CSV files, plus the index the source resolved them to, so estimators never look strings
// up in their hot path). The simulators, the file readers and the live service produce them; an
// estimator sees them grouped into epochs (epoch.h) and runs unchanged on all sources
// (ROADMAP.md "Architecture"). A new sensor adds one record here and one registered reader.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mirage/core/types.h"

namespace mirage::core {

/// A sampled complex-baseband channel impulse response.
struct Cir {
  /// Delay of samples[0] relative to the transmit time (s).
  double start_s = 0.0;
  /// Sample period T_s (s).
  double sample_period_s = 0.0;
  /// Complex baseband samples; sample n is at delay start_s + n * sample_period_s.
  std::vector<Complex> samples;
};

/// The CIR of one link (an anchor-agent channel, an agent's own channel, the channel between two
/// agents) at one time.
struct CirRecord {
  double t_s = 0.0;         ///< time of the measurement (s)
  std::string link_id;      ///< e.g. "A1", "self 1", "rel 1-2"
  int link_index = 0;       ///< the link's index in the source's link list
  Cir cir;
};

/// One unlabeled range measurement, e.g. one extracted multipath component.
struct RangeMeasurement {
  /// Range, i.e. propagation delay times the signal speed (m).
  double range_m = 0.0;
  /// Magnitude of the estimated complex amplitude |alpha| (linear, the CIR's unit), if known.
  std::optional<double> amplitude;
};

/// All unlabeled ranges measured to one anchor at one time: the extracted multipath components
/// of its channel, or the reply of a ranging system; clutter and missed detections are possible.
struct RangeSet {
  double t_s = 0.0;         ///< time of the measurement (s)
  std::string anchor_id;    ///< the anchor's id ("A1")
  int anchor_index = 0;     ///< index of the anchor in the scenario's anchor list
  std::vector<RangeMeasurement> ranges;  ///< in any order
};

/// Times of arrival at one receiver (a microphone) in the receivers' common time base.
struct ToaStamps {
  double t_s = 0.0;          ///< time of the record (s), e.g. the first stamp's
  std::string receiver_id;
  int receiver_index = 0;
  std::vector<double> toa_s;  ///< arrival times (s), unlabeled: direct path, echoes, false alarms
  /// The emission these stamps belong to, where the system knows it (an ID symbol).
  std::optional<std::int64_t> emission_sequence;
  /// The emission's time in the receivers' time base (s), where the system knows it (a sender
  /// synchronised with the receivers, or a reference system such as motion capture).
  std::optional<double> emission_s;
};

/// One time difference of arrival between two receivers (UWB TDOA anchors, microphones), as a
/// distance: tdoa_m = |p - a_j| - |p - a_i| for the sender at p (the convention of tdoa.csv and of
/// Bitcraze's Loco Positioning TDOA: positive when the sender is nearer to a_i).
struct TdoaMeasurement {
  double t_s = 0.0;  ///< time of the measurement (s)
  std::string id_i;
  std::string id_j;
  int index_i = 0;   ///< index of receiver i in the scenario's receiver list
  int index_j = 0;
  double tdoa_m = 0.0;  ///< |p - a_j| - |p - a_i| (m)
};

/// One two-way-ranging exchange (symmetric double-sided TWR) between two devices, as the raw
/// device timestamps in integer ticks of each device's own clock: the initiator's poll tx,
/// response rx and final tx, and the responder's poll rx, response tx and final rx.
struct TwrExchange {
  double t_s = 0.0;
  std::string initiator_id;
  std::string responder_id;
  int initiator_index = 0;
  int responder_index = 0;
  std::array<std::int64_t, 3> initiator_ticks{};  ///< poll tx, response rx, final tx
  std::array<std::int64_t, 3> responder_ticks{};  ///< poll rx, response tx, final rx
  double tick_s = 0.0;  ///< nominal tick period (s), e.g. 1 / (499.2 MHz * 128) for DW1000
};

/// One inertial sample: specific force and angular rate in the sensor frame.
struct ImuSample {
  double t_s = 0.0;
  std::string sensor_id;
  int sensor_index = 0;
  Vec3 accel_mps2 = Vec3::Zero();  ///< specific force (m/s^2)
  Vec3 gyro_radps = Vec3::Zero();  ///< angular rate (rad/s)
};

/// A horizontal displacement of an agent from its own dead reckoning between two times (a phone's
/// pedestrian dead reckoning, wheel odometry), in the world frame, with its covariance: the
/// loosely coupled inertial input of Bordoy 2020 Eq. 5.35-5.39.
struct PositionIncrement {
  double t_s = 0.0;       ///< end of the interval (s)
  std::string sensor_id;
  int sensor_index = 0;
  double t_from_s = 0.0;  ///< start of the interval (s)
  Vec2 delta_m = Vec2::Zero();
  Eigen::Matrix2d covariance_m2 = Eigen::Matrix2d::Zero();
};

/// True if one of `ranges` lies within tolerance_m (exclusive) of expected_m: the match test of
/// the relocalization scores (MINT's grid search, SLAM's track-loss recovery).
inline bool HasRangeNear(std::span<const RangeMeasurement> ranges, double expected_m, double tolerance_m) {
  return std::any_of(ranges.begin(), ranges.end(),
                     [&](const RangeMeasurement& r) { return std::abs(r.range_m - expected_m) < tolerance_m; });
}

}  // namespace mirage::core
