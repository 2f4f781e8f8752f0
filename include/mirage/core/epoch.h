// SPDX-License-Identifier: MIT
// An epoch: the records one estimator step sees together. The epoch rule: records whose times
// lie within the source's epoch window of the epoch's first record belong to it (window 0:
// records with the same time stamp, as a simulator or a CSV file with one row per anchor and
// time writes them). Inside an epoch each record keeps its own t_s, so an event-driven
// estimator can still propagate to every record's time before its update.
#pragma once

#include <vector>

#include "mirage/core/records.h"

namespace mirage::core {

/// The records of one estimator step, by kind, each kind in time order.
struct Epoch {
  double t_s = 0.0;  ///< the time of the epoch's first record (s)
  std::vector<RangeSet> range_sets;
  std::vector<CirRecord> cirs;
  std::vector<ToaStamps> toas;
  std::vector<TwrExchange> twrs;
  std::vector<ImuSample> imus;
  std::vector<PositionIncrement> increments;
  std::vector<TdoaMeasurement> tdoas;

  /// Number of records of all kinds.
  [[nodiscard]] std::size_t size() const {
    return range_sets.size() + cirs.size() + toas.size() + twrs.size() + imus.size() + increments.size() +
           tdoas.size();
  }
  [[nodiscard]] bool empty() const { return size() == 0; }
};

}  // namespace mirage::core
