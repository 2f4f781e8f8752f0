// SPDX-License-Identifier: MIT
// What a state block is: the dimension of its mean, the dimension of its tangent space (the rows
// of the covariance it owns) and how a correction is applied to it (boxplus) and how two values
// are compared (boxminus). Euclidean blocks (positions, velocities, offsets) add and subtract;
// a manifold block such as an orientation quaternion (4 numbers, 3 degrees of freedom) brings
// its own operators. The set of types is open: a method defines its own BlockType constant
// anywhere; the built-in ones are in block_types.h. Types are told apart by an integer id, so a
// lookup in the hot path compares integers, never strings.
#pragma once

namespace mirage::estimation {

/// x [+] delta: the mean x (dim values) corrected by the tangent vector delta (tangent_dim
/// values), written to out (dim values; may alias x).
using BoxPlusFn = void (*)(const double* x, const double* delta, double* out);
/// x [-] y: the tangent vector (tangent_dim values) that takes y to x.
using BoxMinusFn = void (*)(const double* x, const double* y, double* out);

/// A block type. Ids are unique program-wide: the built-in types use 1-99 (block_types.h),
/// methods 100 and above; a layout asserts that one id always means the same type.
struct BlockType {
  int id = 0;                   ///< unique integer id
  const char* name = "";        ///< for messages and reports
  int dim = 0;                  ///< values in the mean
  int tangent_dim = 0;          ///< degrees of freedom: rows of the covariance
  BoxPlusFn boxplus = nullptr;  ///< nullptr: Euclidean (x + delta)
  BoxMinusFn boxminus = nullptr;  ///< nullptr: Euclidean (x - y)

  /// True for a vector space block (dim == tangent_dim, plain addition).
  [[nodiscard]] constexpr bool euclidean() const { return boxplus == nullptr; }
};

}  // namespace mirage::estimation
