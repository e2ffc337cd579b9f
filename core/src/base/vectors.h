// Small vector arithmetic on raw coordinate arrays, shared by the core's
// algorithms: the dot product and the 3-D cross product. Norms are
// ScaledNorm (scaled.h), which neither underflows nor overflows. Internal
// to the core.
#ifndef FREEFORM_CORE_SRC_BASE_VECTORS_H_
#define FREEFORM_CORE_SRC_BASE_VECTORS_H_

#include <cstddef>

namespace freeform::internal {

// Dot returns sum_k a[k] b[k] over `count` values.
inline double Dot(const double* a, const double* b, size_t count) {
  double sum = 0.0;
  for (size_t k = 0; k < count; ++k) sum += a[k] * b[k];
  return sum;
}

// Cross writes a x b of two 3-D vectors into `out` (not aliasing them).
inline void Cross(const double* a, const double* b, double* out) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_BASE_VECTORS_H_
