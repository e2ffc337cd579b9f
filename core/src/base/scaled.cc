#include "base/scaled.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "freeform/core/points.h"

namespace freeform::internal {
namespace {

// SumOfScaledSquares returns sum_j (v_j 2^-e)^2.
template <typename Value>
double SumOfScaledSquares(int d, int e, Value value) {
  double sum = 0.0;
  for (int j = 0; j < d; ++j) {
    const double x = e == 0 ? value(j) : std::ldexp(value(j), -e);
    sum += x * x;
  }
  return sum;
}

// Values whose magnitudes lie in [2^-500, 2^500] square without underflow
// or overflow (a sum of 64 such squares included).
constexpr double kSafeLow = 0x1p-500;
constexpr double kSafeHigh = 0x1p500;

// NormOf returns the norm of the d values value(j) (ScaledNorm): the plain
// sum of squares when the largest value is safe to square, else the scaled
// one.
template <typename Value>
double NormOf(int d, Value value) {
  double largest = 0.0;
  for (int j = 0; j < d; ++j) largest = std::max(largest, std::abs(value(j)));
  if (largest == 0.0 || !std::isfinite(largest)) return largest;
  if (largest >= kSafeLow && largest <= kSafeHigh) {
    return std::sqrt(SumOfScaledSquares(d, 0, value));
  }
  const int e = ExponentAbove(largest);
  return std::ldexp(std::sqrt(SumOfScaledSquares(d, e, value)), e);
}

}  // namespace

int LargestExponent(absl::Span<const double> values) {
  double largest = 0.0;
  for (const double value : values) {
    largest = std::max(largest, std::abs(value));
  }
  return ExponentAbove(largest);
}

int ExponentAbove(double x) {
  if (x == 0.0 || !std::isfinite(x)) return 0;
  int e = 0;
  const double fraction = std::frexp(std::abs(x), &e);  // in [0.5, 1)
  return fraction == 0.5 ? e - 1 : e;
}

double ScaledNormOf(const double* v, int d) {
  return NormOf(d, [v](int j) { return v[j]; });
}

double ScaledDistanceOf(const double* a, const double* b, int d) {
  return NormOf(d, [a, b](int j) { return a[j] - b[j]; });
}

}  // namespace freeform::internal
