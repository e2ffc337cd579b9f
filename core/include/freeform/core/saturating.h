// Saturating arithmetic for size estimates: a sum or product that would
// overflow uint64_t is UINT64_MAX, so that the estimate of an absurd request
// fails its limit check instead of wrapping to a small number.
#ifndef FREEFORM_CORE_SATURATING_H_
#define FREEFORM_CORE_SATURATING_H_

#include <cstdint>

namespace freeform {

// SaturatingSum returns a + b, or UINT64_MAX when that overflows.
inline uint64_t SaturatingSum(uint64_t a, uint64_t b) {
  uint64_t sum = 0;
  return __builtin_add_overflow(a, b, &sum) ? UINT64_MAX : sum;
}

// SaturatingProduct returns a * b, or UINT64_MAX when that overflows.
inline uint64_t SaturatingProduct(uint64_t a, uint64_t b) {
  uint64_t product = 0;
  return __builtin_mul_overflow(a, b, &product) ? UINT64_MAX : product;
}

}  // namespace freeform

#endif  // FREEFORM_CORE_SATURATING_H_
