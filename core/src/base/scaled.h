// Scale-safe arithmetic for the queries (arc length, closest points,
// curvature): norms whose squares neither underflow nor overflow, and the
// rescaling of a Bezier net's weights by a power of two, which is exact
// (scaled_geometry.h rescales whole geometries the same way):
// docs/references.md, 'Scale-safe norms'.
// Internal to the core; thread-safe (pure functions).
#ifndef FREEFORM_CORE_SRC_BASE_SCALED_H_
#define FREEFORM_CORE_SRC_BASE_SCALED_H_

#include <cmath>
#include <limits>
#include <vector>

#include "absl/types/span.h"

namespace freeform::internal {

// ExponentAbove returns the least e with |x| <= 2^e for a finite nonzero x,
// and 0 for 0 or a value that is not finite.
int ExponentAbove(double x);

// LargestExponent is ExponentAbove of the largest |value| (0 for none).
int LargestExponent(absl::Span<const double> values);

// SafeExponent returns 0 when values of magnitude up to `largest` (itself
// in [2^-500, 2^500]) square safely, else ExponentAbove(largest): the
// exponent by which to divide them first.
inline int SafeExponent(double largest) {
  if (largest >= 0x1p-500 && largest <= 0x1p500) return 0;
  return ExponentAbove(largest);
}

// ScaledNormOf and ScaledDistanceOf are ScaledNorm and ScaledDistance
// with the values divided by the power of two at or above the largest
// magnitude before they are squared.
double ScaledNormOf(const double* v, int d);
double ScaledDistanceOf(const double* a, const double* b, int d);

// A sum of squares at least this large lost nothing that matters to
// underflow (a square below 2^-1074 is 2^-100 of it).
inline constexpr double kSafeSquares = 0x1p-968;

// ScaledNorm returns |v| for `d` values, exact to rounding for every finite
// v (infinite when the norm exceeds the double range, or when a value is
// not finite): the plain sum of squares when it neither overflowed nor
// fell below kSafeSquares, else ScaledNormOf.
inline double ScaledNorm(const double* v, int d) {
  double sum = 0.0;
  for (int j = 0; j < d; ++j) sum += v[j] * v[j];
  if (sum >= kSafeSquares && sum <= std::numeric_limits<double>::max()) {
    return std::sqrt(sum);
  }
  return ScaledNormOf(v, d);
}

// ScaledDistance returns |a - b| as ScaledNorm does.
inline double ScaledDistance(const double* a, const double* b, int d) {
  double sum = 0.0;
  for (int j = 0; j < d; ++j) sum += (a[j] - b[j]) * (a[j] - b[j]);
  if (sum >= kSafeSquares && sum <= std::numeric_limits<double>::max()) {
    return std::sqrt(sum);
  }
  return ScaledDistanceOf(a, b, d);
}

// PowerOfTwoScale multiplies by 2^e as std::ldexp does (exactly, short of
// a subnormal or overflowing result), with one multiplication when 2^e is
// a normal double.
class PowerOfTwoScale {
 public:
  explicit PowerOfTwoScale(int e)
      : e_(e), factor_(e >= -1022 && e <= 1023 ? std::ldexp(1.0, e) : 0.0) {}
  double operator()(double x) const {
    return factor_ != 0.0 ? x * factor_ : std::ldexp(x, e_);
  }

 private:
  int e_;
  double factor_;
};

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_BASE_SCALED_H_
