// SPDX-License-Identifier: MIT
// Deterministic random numbers: xoshiro256** seeded through splitmix64, with named sub-streams.
// Every random draw in mirage comes from an Rng passed in by the caller (STYLE.md §10).
// The distributions are implemented here rather than taken from <random> so that the same seed
// gives the same numbers with every standard library.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "mirage/core/types.h"

namespace mirage::core {

/// Seeded pseudo-random generator; cheap to copy, not thread-safe (one per thread or purpose).
class Rng {
 public:
  /// @param seed   the scenario seed.
  /// @param stream an index that separates independent streams (e.g. the Monte-Carlo run).
  explicit Rng(std::uint64_t seed, std::uint64_t stream = 0);

  /// A generator for one purpose ("noise", "diffuse", "init"), independent of this one and of
  /// other purposes, so adding a consumer never shifts another consumer's numbers.
  [[nodiscard]] Rng Substream(std::string_view purpose) const;

  /// Next raw 64-bit value.
  std::uint64_t NextU64();
  /// Uniform in [0, 1).
  double Uniform();
  /// Uniform in [lo, hi).
  double Uniform(double lo, double hi);
  /// Uniform integer in [0, n); n must be > 0.
  std::uint64_t UniformInt(std::uint64_t n);
  /// Standard normal N(0, 1) (Marsaglia polar method).
  double Normal();
  /// Normal N(mean, sigma^2).
  double Normal(double mean, double sigma) { return mean + sigma * Normal(); }
  /// Circularly-symmetric complex normal CN(0, variance): real and imaginary parts each have
  /// variance/2.
  Complex ComplexNormal(double variance);
  /// Poisson count with the given mean (>= 0). Exact (Knuth) below a mean of 30, normal
  /// approximation with continuity correction above.
  int Poisson(double mean);
  /// True with probability p.
  bool Bernoulli(double p) { return Uniform() < p; }

 private:
  Rng(std::array<std::uint64_t, 4> state, std::uint64_t identity);

  std::array<std::uint64_t, 4> state_{};
  std::uint64_t identity_ = 0;  // hash of (seed, stream, purposes) used to derive sub-streams
  double spare_normal_ = 0.0;
  bool has_spare_normal_ = false;
};

}  // namespace mirage::core
