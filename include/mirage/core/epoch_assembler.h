// SPDX-License-Identifier: MIT
// Groups a time-ordered stream of records into epochs by the epoch rule (epoch.h): a record
// within window_s of the open epoch's first record joins it; a later one closes it and opens the
// next. A record older than the open epoch's first record (a late packet of a live stream, a
// merged file running behind) is out of order: it is counted, so that the run's health reports
// it, and not handed to the estimator (which has already moved past its time).
#pragma once

#include <algorithm>
#include <optional>
#include <utility>
#include <vector>

#include "mirage/core/epoch.h"

namespace mirage::core {

class EpochAssembler {
 public:
  /// @param window_s the epoch window (s), >= 0; 0 groups records with equal time stamps.
  explicit EpochAssembler(double window_s = 0.0) : window_s_(window_s) {}

  /// Adds one record (any kind of records.h). Returns the epoch it closed, if it opened a new one.
  template <typename Record>
  std::optional<Epoch> Add(Record record) {
    const double t_s = record.t_s;
    if (open_ && t_s < open_->t_s) {
      ++out_of_order_;
      return std::nullopt;
    }
    std::optional<Epoch> closed;
    if (open_ && t_s > open_->t_s + window_s_) closed = std::exchange(open_, std::nullopt);
    if (!open_) {
      open_.emplace();
      open_->t_s = t_s;
    }
    Insert(Slot(*open_, record), std::move(record));
    return closed;
  }

  /// The epoch still open at the end of the stream, if any.
  std::optional<Epoch> Flush() { return std::exchange(open_, std::nullopt); }

  /// Records dropped because they arrived older than the epoch being built.
  [[nodiscard]] int out_of_order() const { return out_of_order_; }

 private:
  static std::vector<RangeSet>& Slot(Epoch& e, const RangeSet&) { return e.range_sets; }
  static std::vector<CirRecord>& Slot(Epoch& e, const CirRecord&) { return e.cirs; }
  static std::vector<ToaStamps>& Slot(Epoch& e, const ToaStamps&) { return e.toas; }
  static std::vector<TwrExchange>& Slot(Epoch& e, const TwrExchange&) { return e.twrs; }
  static std::vector<ImuSample>& Slot(Epoch& e, const ImuSample&) { return e.imus; }
  static std::vector<PositionIncrement>& Slot(Epoch& e, const PositionIncrement&) { return e.increments; }
  static std::vector<TdoaMeasurement>& Slot(Epoch& e, const TdoaMeasurement&) { return e.tdoas; }

  // Keeps each kind in time order (records inside one window may arrive shuffled); equal times
  // keep their arrival order.
  template <typename Record>
  static void Insert(std::vector<Record>& slot, Record record) {
    const auto at = std::upper_bound(slot.begin(), slot.end(), record.t_s,
                                     [](double t_s, const Record& r) { return t_s < r.t_s; });
    slot.insert(at, std::move(record));
  }

  double window_s_;
  std::optional<Epoch> open_;
  int out_of_order_ = 0;
};

}  // namespace mirage::core
