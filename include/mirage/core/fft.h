// SPDX-License-Identifier: MIT
// A complex-to-complex FFT of fixed length, a thin RAII wrapper around FFTW3.
// Execution is thread-safe (FFTW's new-array execute); plan creation is serialised internally.
#pragma once

#include <cstddef>
#include <span>

#include "mirage/core/types.h"

namespace mirage::core {

/// Smallest n' >= n of the form 2^a 3^b 5^c, a length FFTW transforms fast (n >= 1).
std::size_t NextFastFftSize(std::size_t n);

/// Forward X[k] = sum_n x[n] e^{-j 2 pi k n / N}; inverse x[n] = (1/N) sum_k X[k] e^{+j 2 pi k n / N}.
class Fft {
 public:
  /// @param size transform length N (> 0); powers of two are fastest.
  explicit Fft(std::size_t size);
  ~Fft();
  Fft(const Fft&) = delete;
  Fft& operator=(const Fft&) = delete;
  Fft(Fft&& other) noexcept;
  Fft& operator=(Fft&& other) noexcept;

  /// Transform length N.
  [[nodiscard]] std::size_t size() const { return size_; }
  /// Forward transform; in and out must both hold N values and may alias.
  void Forward(std::span<const Complex> in, std::span<Complex> out) const;
  /// Inverse transform including the 1/N factor; in and out may alias.
  void Inverse(std::span<const Complex> in, std::span<Complex> out) const;

 private:
  std::size_t size_ = 0;
  void* forward_plan_ = nullptr;  // fftw_plan, kept opaque so that callers need no fftw3.h
  void* inverse_plan_ = nullptr;
};

}  // namespace mirage::core
