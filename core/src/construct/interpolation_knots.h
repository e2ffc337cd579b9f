// The knots of global interpolation and approximation (interpolation.h):
// clamped uniform knots, and the knots a KnotRule places for given
// parameters. Internal to the core; thread-safe (pure functions).
#ifndef FREEFORM_CORE_SRC_CONSTRUCT_INTERPOLATION_KNOTS_H_
#define FREEFORM_CORE_SRC_CONSTRUCT_INTERPOLATION_KNOTS_H_

#include <vector>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/interpolation.h"

namespace freeform::internal {

// ClampedUniformKnots returns p + 1 zeros, j / (count - p) for
// j = 1..count-p-1 and p + 1 ones.
std::vector<double> ClampedUniformKnots(int count, int p);

// KnotsFor returns the clamped knots of degree p for the sites t (one
// function per site): ClampedUniformKnots for kUniversal, else by the
// KnotRule (kAveraging: eq. 9.8, N p additions, which poll `cancel`;
// kUniform: equally spaced on [t.front(), t.back()]).
absl::StatusOr<std::vector<double>> KnotsFor(absl::Span<const double> t, int p,
                                             Parameterization parameterization,
                                             KnotRule knot_rule,
                                             const CancellationToken* cancel);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_CONSTRUCT_INTERPOLATION_KNOTS_H_
