// SPDX-License-Identifier: MIT
#include "mirage/core/rng.h"

#include <cassert>
#include <algorithm>
#include <cmath>
#include <limits>

namespace mirage::core {
namespace {

std::uint64_t SplitMix64(std::uint64_t& x) {
  x += 0x9E3779B97F4A7C15ULL;
  std::uint64_t z = x;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

std::uint64_t Fnv1a(std::string_view text, std::uint64_t h) {
  for (const char ch : text) {
    h ^= static_cast<unsigned char>(ch);
    h *= 0x100000001B3ULL;
  }
  return h;
}

std::array<std::uint64_t, 4> StateFromIdentity(std::uint64_t identity) {
  std::uint64_t x = identity;
  std::array<std::uint64_t, 4> s{};
  for (auto& word : s) word = SplitMix64(x);
  return s;
}

std::uint64_t Rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

}  // namespace

Rng::Rng(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t x = seed;
  std::uint64_t identity = SplitMix64(x);
  x = identity ^ (stream * 0xD1B54A32D192ED03ULL);
  identity = SplitMix64(x);
  identity_ = identity;
  state_ = StateFromIdentity(identity_);
}

Rng::Rng(std::array<std::uint64_t, 4> state, std::uint64_t identity)
    : state_(state), identity_(identity) {}

Rng Rng::Substream(std::string_view purpose) const {
  const std::uint64_t identity = Fnv1a(purpose, identity_ ^ 0xCBF29CE484222325ULL);
  return Rng(StateFromIdentity(identity), identity);
}

std::uint64_t Rng::NextU64() {
  // xoshiro256** (Blackman & Vigna, 2018).
  const std::uint64_t result = Rotl(state_[1] * 5, 7) * 9;
  const std::uint64_t t = state_[1] << 17;
  state_[2] ^= state_[0];
  state_[3] ^= state_[1];
  state_[1] ^= state_[2];
  state_[0] ^= state_[3];
  state_[2] ^= t;
  state_[3] = Rotl(state_[3], 45);
  return result;
}

double Rng::Uniform() {
  // 53 random bits -> [0, 1).
  return static_cast<double>(NextU64() >> 11) * 0x1.0p-53;
}

double Rng::Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }

std::uint64_t Rng::UniformInt(std::uint64_t n) {
  assert(n > 0);
  // Rejection to avoid modulo bias.
  const std::uint64_t limit = UINT64_MAX - UINT64_MAX % n;
  std::uint64_t v = NextU64();
  while (v >= limit) v = NextU64();
  return v % n;
}

double Rng::Normal() {
  if (has_spare_normal_) {
    has_spare_normal_ = false;
    return spare_normal_;
  }
  double u = 0.0, v = 0.0, s = 0.0;
  do {
    u = 2.0 * Uniform() - 1.0;
    v = 2.0 * Uniform() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double scale = std::sqrt(-2.0 * std::log(s) / s);
  spare_normal_ = v * scale;
  has_spare_normal_ = true;
  return u * scale;
}

Complex Rng::ComplexNormal(double variance) {
  const double sigma = std::sqrt(variance / 2.0);
  const double re = Normal() * sigma;
  const double im = Normal() * sigma;
  return {re, im};
}

int Rng::Poisson(double mean) {
  assert(mean >= 0.0);
  if (mean <= 0.0) return 0;
  if (mean < 30.0) {
    const double limit = std::exp(-mean);
    int k = 0;
    double p = Uniform();
    while (p > limit) {
      ++k;
      p *= Uniform();
    }
    return k;
  }
  const double x = std::floor(mean + std::sqrt(mean) * Normal() + 0.5);
  return static_cast<int>(std::clamp(x, 0.0, static_cast<double>(std::numeric_limits<int>::max())));
}

}  // namespace mirage::core
