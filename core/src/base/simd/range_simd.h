// A Highway kernel that checks a batch of parameters against a closed
// interval at full vector width (range_simd.cc): the check every batch
// evaluator makes first, which point by point costs as much as a fifth of a
// cubic B-spline evaluation. Internal to the core; thread-safe.
#ifndef FREEFORM_CORE_SRC_BASE_SIMD_RANGE_SIMD_H_
#define FREEFORM_CORE_SRC_BASE_SIMD_RANGE_SIMD_H_

#include <cstddef>

namespace freeform::simd {

// AllInRange returns whether lo <= values[i] <= hi for every i < count
// (false for NaN; with finite bounds, false for infinities too).
bool AllInRange(const double* values, size_t count, double lo, double hi);

}  // namespace freeform::simd

#endif  // FREEFORM_CORE_SRC_BASE_SIMD_RANGE_SIMD_H_
