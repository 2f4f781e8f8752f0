// SPDX-License-Identifier: MIT
#include "mirage/core/fft.h"

#include <algorithm>
#include <cassert>
#include <mutex>
#include <utility>
#include <vector>

#include <fftw3.h>

namespace mirage::core {
namespace {

// FFTW's planner is not thread-safe; execution with the new-array interface is.
std::mutex& PlannerMutex() {
  static std::mutex mutex;
  return mutex;
}

fftw_plan MakePlan(std::size_t n, int sign) {
  std::vector<Complex> in(n), out(n);
  std::lock_guard<std::mutex> lock(PlannerMutex());
  return fftw_plan_dft_1d(static_cast<int>(n), reinterpret_cast<fftw_complex*>(in.data()),
                          reinterpret_cast<fftw_complex*>(out.data()), sign,
                          FFTW_ESTIMATE | FFTW_UNALIGNED);
}

void Destroy(void* plan) {
  if (plan == nullptr) return;
  std::lock_guard<std::mutex> lock(PlannerMutex());
  fftw_destroy_plan(static_cast<fftw_plan>(plan));
}

}  // namespace

std::size_t NextFastFftSize(std::size_t n) {
  for (std::size_t candidate = std::max<std::size_t>(n, 1);; ++candidate) {
    std::size_t rest = candidate;
    for (const std::size_t factor : {2U, 3U, 5U}) {
      while (rest % factor == 0) rest /= factor;
    }
    if (rest == 1) return candidate;
  }
}

Fft::Fft(std::size_t size)
    : size_(size), forward_plan_(MakePlan(size, FFTW_FORWARD)), inverse_plan_(MakePlan(size, FFTW_BACKWARD)) {
  assert(size > 0);
}

Fft::~Fft() {
  Destroy(forward_plan_);
  Destroy(inverse_plan_);
}

Fft::Fft(Fft&& other) noexcept
    : size_(std::exchange(other.size_, 0)),
      forward_plan_(std::exchange(other.forward_plan_, nullptr)),
      inverse_plan_(std::exchange(other.inverse_plan_, nullptr)) {}

Fft& Fft::operator=(Fft&& other) noexcept {
  if (this != &other) {
    Destroy(forward_plan_);
    Destroy(inverse_plan_);
    size_ = std::exchange(other.size_, 0);
    forward_plan_ = std::exchange(other.forward_plan_, nullptr);
    inverse_plan_ = std::exchange(other.inverse_plan_, nullptr);
  }
  return *this;
}

namespace {
// The plans are out-of-place; FFTW requires new-array execution to be out-of-place too, so an
// aliased call goes through a copy. FFTW does not modify the input of an out-of-place c2c
// transform, hence the const_cast is safe.
void Execute(void* plan, std::span<const Complex> in, std::span<Complex> out) {
  std::vector<Complex> copy;
  const Complex* src = in.data();
  if (src == out.data()) {
    copy.assign(in.begin(), in.end());
    src = copy.data();
  }
  fftw_execute_dft(static_cast<fftw_plan>(plan),
                   reinterpret_cast<fftw_complex*>(const_cast<Complex*>(src)),
                   reinterpret_cast<fftw_complex*>(out.data()));
}
}  // namespace

void Fft::Forward(std::span<const Complex> in, std::span<Complex> out) const {
  assert(in.size() == size_ && out.size() == size_);
  Execute(forward_plan_, in, out);
}

void Fft::Inverse(std::span<const Complex> in, std::span<Complex> out) const {
  assert(in.size() == size_ && out.size() == size_);
  Execute(inverse_plan_, in, out);
  const double scale = 1.0 / static_cast<double>(size_);
  for (auto& v : out) v *= scale;
}

}  // namespace mirage::core
