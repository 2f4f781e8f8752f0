// SPDX-License-Identifier: MIT
// Comparisons of an elapsed time with a limit in seconds, for options that were step counts: a
// step time t_n = n dt computed in floating point (or read from a recording's text) makes the
// difference of two step times differ from the exact multiple of dt by a rounding error, so a
// limit of exactly k steps must not depend on the last bit. Times closer than kTimeToleranceS
// count as equal, which makes `Exceeds(t - t0, k dt)` the old `step - step0 > k` and
// `Reaches(t - t0, k dt)` the old `step - step0 >= k` at any step time well above 1 us.
#pragma once

namespace mirage::methods {

/// Two times closer than this are the same time (s): far below any step time, far above the
/// rounding error of step times of any run's length.
inline constexpr double kTimeToleranceS = 1e-6;

/// elapsed_s > limit_s, beyond rounding (both s).
constexpr bool Exceeds(double elapsed_s, double limit_s) { return elapsed_s > limit_s + kTimeToleranceS; }

/// elapsed_s >= limit_s, up to rounding (both s).
constexpr bool Reaches(double elapsed_s, double limit_s) { return elapsed_s > limit_s - kTimeToleranceS; }

}  // namespace mirage::methods
