// Scale-safe arithmetic for the queries (arc length, closest points,
// curvature): norms whose squares neither underflow nor overflow, and the
// rescaling of a Bezier net's weights by a power of two, which is exact
// (scaled_geometry.h rescales whole geometries the same way):
// docs/references.md, 'Scale-safe norms'.
// Internal to the core; thread-safe (pure functions).
#ifndef FREEFORM_CORE_SRC_SCALED_H_
#define FREEFORM_CORE_SRC_SCALED_H_

#include <vector>

#include "bezier_net.h"

namespace freeform::internal {

// ExponentAbove returns the least e with |x| <= 2^e for a finite nonzero x,
// and 0 for 0 or a value that is not finite.
int ExponentAbove(double x);

// SafeExponent returns 0 when values of magnitude up to `largest` (itself
// at least 2^-500) square safely, else ExponentAbove(largest): the exponent
// by which to divide them first.
int SafeExponent(double largest);

// ScaledNorm returns |v| for `d` values: they are divided by the power of
// two at or above the largest magnitude before they are squared, so the
// result is exact to rounding for every finite v (infinite when the norm
// exceeds the double range, or when a value is not finite).
double ScaledNorm(const double* v, int d);

// ScaledDistance returns |a - b| as ScaledNorm does.
double ScaledDistance(const double* a, const double* b, int d);

// NormalizeWeights divides the homogeneous values of a rational net by
// the power of two at or above its largest weight (the same net, with
// weights at most 1); a polynomial net is left as it is.
void NormalizeWeights(Net& net);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_SCALED_H_
