// SPDX-License-Identifier: MIT
// Online SINR and range-variance estimation per multipath-component source, e.g. a virtual
// anchor or one path of a link (Lafer 2014 Sec. 3.6; MINT, SLAM and the cooperative filter use
// it): moment-based SINR from the amplitudes of the MPCs associated to the source over a sliding
// spatial window (Eq. 3.26, 3.27, 3.30), turned into a range variance by the CRLB (Eq. 3.28).
//
// Eq. (3.26) needs m_2 to be the *variance* of Y = |alpha_hat|^2 (digest Sec. 2.9): with
// Y = |a + n|^2, n ~ CN(0, s^2), E[Y] = |a|^2 + s^2 and Var[Y] = s^4 + 2 |a|^2 s^2, so
// K = |a|^2 / s^2 = 1 / (m1 / sqrt(m1^2 - Var) - 1), the Rician K-factor moment estimator.
#pragma once

#include <deque>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "mirage/core/options_descriptor.h"
#include "mirage/core/types.h"

namespace mirage::estimation {

/// Parameters of the variance estimation (defaults from Lafer 2014 Tab. 3.2).
struct RangeVarianceOptions {
  /// Estimate per-VA variances online; when false every range gets range_sigma_m of the tracker.
  bool enabled = true;
  /// Minimum spatial extent d_min of the amplitude window (m), in [1e-6, 1e9]: guards against
  /// correlated samples. 0.9 m (Tab. 3.2).
  double window_min_m = 0.9;
  /// Maximum spatial extent d_max (m), in [1e-6, 1e9] and >= window_min_m: keeps the channel
  /// stationary. 1.0 m.
  double window_max_m = 1.0;
  /// Minimum number of amplitudes N_min in the window, in [3, 1e6]. 15 (Tab. 3.2).
  int min_samples = 15;
  /// Default range standard deviation sigma_VA before any estimate (m), in [1e-9, 1e9]. 0.07 m
  /// (the text; Tab. 3.2 misprints it as 0.07 m^2). Derived from the scenario's range noise when
  /// it states one (the descriptor): ranges without amplitudes keep this for good.
  double default_sigma_m = 0.07;
  /// sigma_VA,max^2 = factor * sigma_VA^2 for SINR estimates of zero or complex, in [1, 1e9]. 10.
  double max_variance_factor = 10.0;
  /// Floor of the standard deviation (m), in [1e-9, 1e9] and <= default_sigma_m [GAP in the
  /// thesis]: Var[Y] -> 0 would give zero variance. 1 cm, about the delay error that model
  /// mismatch leaves at high SINR; with a stated range noise below 1 cm, that noise.
  double min_sigma_m = 0.01;
  /// Two expected ranges closer than this overlap (m), in [0, 1e9]; overlapping samples are
  /// discarded because Eq. (3.25) does not hold for them [GAP: the thesis gives no criterion].
  /// 0.15 m is c * T_p at T_p = 0.5 ns.
  double overlap_distance_m = 0.15;
};

/// The options' descriptor (keys, units, ranges, docs, the window and sigma-floor checks;
/// core/options_descriptor.h).
const core::OptionsDescriptor<RangeVarianceOptions>& RangeVarianceOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const RangeVarianceOptions& options);

/// Moments of Y = |alpha_hat|^2 over a VA's current window (Eq. 3.27).
struct AmplitudeMoments {
  double mean = 0.0;      ///< m1 = E[Y]
  double variance = 0.0;  ///< m2 = Var[Y] (the digest's reading of Eq. 3.26)
  int count = 0;          ///< samples in the window
};

/// The variance used for one VA at one step.
struct RangeVariance {
  double variance_m2 = 0.0;   ///< range variance (m^2)
  /// SINR estimated at this step (linear; 0 for the "zero or complex" case), when the window
  /// allowed an estimate; empty when a fallback was used.
  std::optional<double> sinr;
  /// The window's moments the estimate came from (present exactly when sinr is).
  std::optional<AmplitudeMoments> moments;
};


/// Amplitude history and variance state of all VAs; one instance per tracker.
class RangeVarianceEstimator {
 public:
  /// @param range_sigma_at_unit_sinr_m c / (sqrt(8) pi beta) of the pulse (m), Eq. (3.28).
  RangeVarianceEstimator(const RangeVarianceOptions& options, double range_sigma_at_unit_sinr_m);

  /// Records the amplitude |alpha_hat| of an MPC associated to va_id at the agent's estimated
  /// position (Eq. 3.27, 3.30 use EKF positions online).
  void AddSample(int va_id, const Vec2& agent_m, double amplitude);

  /// Range variance (m^2) for this step. When the VA was associated now and its window holds
  /// enough samples, the Eq. (3.26)/(3.28) estimate; SINR 0 or complex gives sigma_VA,max^2;
  /// otherwise the average of the VA's previous variances, or sigma_VA^2 if there are none.
  RangeVariance Variance(int va_id, bool associated_now);

  /// The variance the VA would get from the fallback rule now: the average of its previous
  /// variances, or sigma_VA^2 (m^2). Records nothing.
  [[nodiscard]] double CurrentVariance(int va_id) const;

  /// The moments of the VA's window as seen from the agent position at_m: the samples within
  /// d_max of at_m, if there are at least N_min of them and the farthest is at least d_min away
  /// (Eq. 3.30 with p_n = at_m). A window left behind (the VA was not associated for a while)
  /// therefore expires instead of describing a place the agent has left.
  [[nodiscard]] std::optional<AmplitudeMoments> Moments(int va_id, const Vec2& at_m) const;

  /// The variance of the VA's most recent moment-based estimate (m^2), or std::nullopt while it
  /// has none (start-up: the VA runs on the default sigma_VA). The SLAM VA filter reads it.
  [[nodiscard]] std::optional<double> LastEstimatedVariance(int va_id) const;
  /// Forgets everything (new run).
  void Reset() { vas_.clear(); }

 private:
  struct Sample {
    Vec2 agent_m;
    double energy = 0.0;  // Y = |alpha_hat|^2
  };
  struct VaHistory {
    std::deque<Sample> samples;
    double variance_sum = 0.0;
    int variance_count = 0;
    double last_variance = 0.0;  // valid when variance_count > 0
  };
  [[nodiscard]] double FallbackVariance(const VaHistory& history) const;

  RangeVarianceOptions options_;
  double sigma1_squared_m2_ = 0.0;
  std::unordered_map<int, VaHistory> vas_;
};

}  // namespace mirage::estimation
