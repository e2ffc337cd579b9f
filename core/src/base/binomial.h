// Binomial coefficients in double precision, for the change of basis of
// Bezier curves and the Leibniz rule of rational surfaces. Internal to the
// core.
#ifndef FREEFORM_CORE_SRC_BASE_BINOMIAL_H_
#define FREEFORM_CORE_SRC_BASE_BINOMIAL_H_

namespace freeform::internal {

// Binomial returns n choose k for 0 <= k <= n, exact while it is below
// 2^53 (each partial product n-k+1..n-k+i over i! is an integer).
inline double Binomial(int n, int k) {
  double result = 1.0;
  for (int i = 1; i <= k; ++i) result = result * (n - k + i) / i;
  return result;
}

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_BASE_BINOMIAL_H_
