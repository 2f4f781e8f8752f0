// SPDX-License-Identifier: MIT
// Test helper for the NEES consistency tests: truth drawn from a filter's own motion model (the
// prior and the discrete white-noise-acceleration constant-velocity model of
// estimation/motion/constant_velocity.h), the time-and-run average of the whole state's NEES and
// its chi-square interval.
#pragma once

#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "mirage/core/rng.h"
#include "mirage/core/types.h"
#include "mirage/estimation/gates/chi2.h"
#include "rng_vectors.h"

namespace mirage::methods::testing {

/// What a planar constant-velocity filter assumes about its agent.
struct CvModel {
  double position_sigma_m = 0.1;    ///< prior std of each coordinate around the start (m)
  double velocity_sigma_mps = 0.1;  ///< prior std of each velocity component, mean 0 (m/s)
  double accel_sigma_mps2 = 0.1;    ///< sigma_a of the white acceleration (m/s^2)
  double dt_s = 0.1;                ///< step time (s)
};

/// A drawn trajectory: position and velocity at steps 0 .. steps.
struct CvTrack {
  std::vector<Vec2> position_m;
  std::vector<Vec2> velocity_mps;
};

/// The truth at steps 0 .. steps (step 0: the start, drawn from the prior around start_m, at a
/// velocity drawn from the prior around 0). The acceleration is constant over a step and white
/// between steps, so position and velocity noise are correlated exactly as in
/// Q = sigma_a^2 [[dt^4/4, dt^3/2], [dt^3/2, dt^2]]. A trajectory with a point outside `inside` is
/// drawn again (the filters need the room's geometry, which a model without walls does not know).
inline CvTrack DrawCvTrajectory(const CvModel& model, const Vec2& start_m, int steps, core::Rng& rng,
                                const std::function<bool(const Vec2&)>& inside) {
  const auto normal2 = [&](double sigma) { return Vec2(sigma * mirage::testing::NormalVec2(rng)); };
  const double dt = model.dt_s;
  for (;;) {
    CvTrack track{{start_m + normal2(model.position_sigma_m)}, {normal2(model.velocity_sigma_mps)}};
    bool kept = inside(track.position_m.back());
    for (int k = 1; k <= steps && kept; ++k) {
      const Vec2 accel_mps2 = normal2(model.accel_sigma_mps2);
      track.position_m.push_back(track.position_m.back() + track.velocity_mps.back() * dt + 0.5 * dt * dt * accel_mps2);
      track.velocity_mps.push_back(track.velocity_mps.back() + dt * accel_mps2);
      kept = inside(track.position_m.back());
    }
    if (kept) return track;
  }
}

/// The NEES e^T P^-1 e of whole filter states (every block of the layout) over the steps of
/// many independent runs, each of the same number of steps. The state's dimension may change
/// within a run (SLAM adds a VA at its first range).
class StateNees {
 public:
  /// One step: the state's mean minus the truth, in the layout's tangent order, and P.
  void Add(const Eigen::VectorXd& error, const Eigen::MatrixXd& covariance) {
    sum_ += error.dot(covariance.ldlt().solve(error));
    dimension_sum_ += static_cast<double>(error.size());
    ++count_;
  }
  /// Closes a run (Add's steps since the last call).
  void EndRun() { ++runs_; }
  [[nodiscard]] double mean() const { return count_ > 0 ? sum_ / count_ : 0.0; }
  /// The state's mean dimension over the steps added.
  [[nodiscard]] double mean_dimension() const { return count_ > 0 ? dimension_sum_ / count_ : 0.0; }
  [[nodiscard]] int runs() const { return runs_; }
  [[nodiscard]] int count() const { return count_; }

 private:
  double sum_ = 0.0;
  double dimension_sum_ = 0.0;
  int count_ = 0;
  int runs_ = 0;
};

/// The 99 % interval of mean() / mean_dimension() for a consistent filter (Bar-Shalom, Li and
/// Kirubarajan 2001, Sec. 5.4.2, the NEES test over N independent runs): the time-average T_r of
/// run r's NEES has mean nbar_r (its mean dimension) and, as an average of K chi^2(n_k) that may
/// be correlated, a standard deviation of at most the average of their standard deviations,
/// sqrt(2 n_k), so var T_r <= 2 nbar_r (Jensen). The runs are independent, so sum_r T_r has mean
/// D = sum_r nbar_r and variance <= 2 D: that of chi^2(D). The interval
/// [Chi2Quantile(0.005, D), Chi2Quantile(0.995, D)] / D is thus a conservative 99 % interval; the
/// within-run correlation only narrows the true spread.
struct NeesInterval {
  double lower = 0.0;
  double upper = 0.0;
};
inline NeesInterval Chi2Interval99(const StateNees& nees) {
  const int dof = static_cast<int>(std::lround(nees.mean_dimension() * nees.runs()));
  const double d = static_cast<double>(dof);
  return {estimation::Chi2Quantile(0.005, dof) / d, estimation::Chi2Quantile(0.995, dof) / d};
}

/// Whether the NEES per dimension lies in its 99 % interval; prints both for the record.
inline bool InChi2Interval99(const StateNees& nees, const char* what) {
  const NeesInterval interval = Chi2Interval99(nees);
  const double ratio = nees.mean() / nees.mean_dimension();
  std::printf("%s: mean NEES %.3f of mean dimension %.2f (%d runs, %d steps): ratio %.4f, 99%% interval [%.4f, %.4f]\n",
              what, nees.mean(), nees.mean_dimension(), nees.runs(), nees.count(), ratio, interval.lower,
              interval.upper);
  return ratio > interval.lower && ratio < interval.upper;
}

}  // namespace mirage::methods::testing
