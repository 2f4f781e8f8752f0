// SPDX-License-Identifier: MIT
// Innovation-based scaling of a measurement variance: the mean normalised innovation squared
// (NIS, nu^2 / S) of a measurement source's last few updates, used as a factor >= 1 on its
// variance R. A consistent source has E[NIS] = 1 and keeps R; one whose ranges are biased or
// noisier than R says (a path merged with a neighbouring one, a VA between two wall offsets) is
// weighted down by its own excess. The scale-only, inflate-only form of the adaptive R of
// innovation-based adaptive estimation (Mehra 1972, "Approaches to adaptive filtering", IEEE TAC
// 17(5); Mohamed and Schwarz 1999, J. Geodesy 73).
#pragma once

#include <cmath>
#include <cstddef>
#include <deque>
#include <numeric>
#include <stdexcept>
#include <string>

namespace mirage::estimation {

class InnovationScale {
 public:
  /// Fewer innovations than this give no scaling: the mean of NIS over 5 consistent innovations
  /// (chi^2_5 / 5) already exceeds 1.85 one time in ten.
  static constexpr std::size_t kMinInnovations = 5;

  /// @param window the number of most recent innovations averaged (>= 1; 0 disables scaling).
  explicit InnovationScale(std::size_t window = 0) : window_(window) {}

  /// Forgets the recorded innovations (e.g. after a track restart: they were taken along the
  /// lost track).
  void Reset() { nis_.clear(); }

  /// Records the NIS (nu^2 / S, >= 0) of one update. A NaN, infinite or negative NIS (a zero or
  /// negative S upstream) throws std::invalid_argument: kept, it would make the mean NaN, and
  /// Factor() would silently return 1 for the whole window.
  void Add(double nis) {
    if (!std::isfinite(nis) || nis < 0.0) {
      throw std::invalid_argument("InnovationScale::Add: the NIS must be finite and >= 0, got " + std::to_string(nis));
    }
    if (window_ == 0) return;
    nis_.push_back(nis);
    if (nis_.size() > window_) nis_.pop_front();
  }

  /// The factor for the variance of the next update: the mean NIS over the window if it exceeds
  /// 1 and at least kMinInnovations were recorded, else 1.
  [[nodiscard]] double Factor() const {
    if (nis_.size() < kMinInnovations) return 1.0;
    const double mean = std::accumulate(nis_.begin(), nis_.end(), 0.0) / static_cast<double>(nis_.size());
    return mean > 1.0 ? mean : 1.0;
  }

 private:
  std::size_t window_;
  std::deque<double> nis_;
};

}  // namespace mirage::estimation
