// Double-double arithmetic: a value hi + lo with |lo| <= ulp(hi) / 2, about
// 106 bits of precision, for the few conversions whose condition number
// exceeds what double precision can carry (LagrangeToBezier). Built from
// the error-free transformations TwoSum (Knuth) and TwoProduct (with a
// fused multiply-add); the operations are those of Hida, Li & Bailey's
// QD library ("accurate" addition), each with relative error below about
// 4 * 2^-106 away from underflow (docs/references.md, 'Double-double
// arithmetic'). Internal to the core.
#ifndef FREEFORM_CORE_SRC_BASE_DOUBLE_DOUBLE_H_
#define FREEFORM_CORE_SRC_BASE_DOUBLE_DOUBLE_H_

#include <cmath>

namespace freeform::internal {

struct DoubleDouble {
  double hi = 0.0;
  double lo = 0.0;

  double ToDouble() const { return hi + lo; }
};

// TwoSum returns a + b exactly as hi + lo (hi = fl(a + b)).
inline DoubleDouble TwoSum(double a, double b) {
  const double sum = a + b;
  const double b_virtual = sum - a;
  const double a_virtual = sum - b_virtual;
  return {sum, (a - a_virtual) + (b - b_virtual)};
}

// QuickTwoSum is TwoSum for |a| >= |b| (or a == 0).
inline DoubleDouble QuickTwoSum(double a, double b) {
  const double sum = a + b;
  return {sum, b - (sum - a)};
}

// TwoProduct returns a * b exactly as hi + lo, away from underflow.
inline DoubleDouble TwoProduct(double a, double b) {
  const double product = a * b;
  return {product, std::fma(a, b, -product)};
}

inline DoubleDouble operator+(const DoubleDouble& a, const DoubleDouble& b) {
  const DoubleDouble high = TwoSum(a.hi, b.hi);
  const DoubleDouble low = TwoSum(a.lo, b.lo);
  const DoubleDouble first = QuickTwoSum(high.hi, high.lo + low.hi);
  return QuickTwoSum(first.hi, first.lo + low.lo);
}

inline DoubleDouble operator-(const DoubleDouble& a) { return {-a.hi, -a.lo}; }

inline DoubleDouble operator-(const DoubleDouble& a, const DoubleDouble& b) {
  return a + (-b);
}

inline DoubleDouble operator*(const DoubleDouble& a, const DoubleDouble& b) {
  const DoubleDouble product = TwoProduct(a.hi, b.hi);
  return QuickTwoSum(product.hi, product.lo + (a.hi * b.lo + a.lo * b.hi));
}

inline DoubleDouble operator/(const DoubleDouble& a, const DoubleDouble& b) {
  // Long division: two quotient digits and a correction.
  const double first = a.hi / b.hi;
  const DoubleDouble remainder = a - b * DoubleDouble{first, 0.0};
  const double second = remainder.hi / b.hi;
  const DoubleDouble rest = remainder - b * DoubleDouble{second, 0.0};
  const double third = rest.hi / b.hi;
  const DoubleDouble quotient = QuickTwoSum(first, second);
  return quotient + DoubleDouble{third, 0.0};
}

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_BASE_DOUBLE_DOUBLE_H_
