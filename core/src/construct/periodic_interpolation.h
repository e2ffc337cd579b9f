// Periodic (closed) global interpolation (interpolation.h): a periodic
// B-spline through N points, whose cyclic collocation system is solved by a
// banded LU bordered with a dense Schur complement. Closed curves and the
// periodic cubic spline are solved with it; the closed kAtParameters curve
// takes its periodic knots. Internal to the core; thread-safe (pure
// functions).
#ifndef FREEFORM_CORE_SRC_CONSTRUCT_PERIODIC_INTERPOLATION_H_
#define FREEFORM_CORE_SRC_CONSTRUCT_PERIODIC_INTERPOLATION_H_

#include <cstddef>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/interpolation.h"
#include "freeform/core/points.h"

namespace freeform::internal {

// A periodic knot sequence kappa_j = base[j mod N] + floor(j / N) period.
struct PeriodicKnots {
  std::vector<double> base;
  double period = 1;

  double operator()(long j) const {
    const long n = static_cast<long>(base.size());
    const long q = j >= 0 ? j / n : -((-j + n - 1) / n);
    return base[static_cast<size_t>(j - q * n)] +
           static_cast<double>(q) * period;
  }
};

// InterpolatePeriodic returns the periodic B-spline of degree p through the
// N points at the increasing sites t (t_{N-1} < t_0 + period) on the
// periodic knots. The basis function whose support starts at
// kappa_{m - shift} belongs to site m (it contains t_m inside its support),
// which makes the cyclic system banded around the diagonal. The curve's
// knots are u_i = kappa_{i + o} with u_p the last knot <= t_0, so its domain
// [u_p, u_p + period] holds every site (modulo the period).
absl::StatusOr<CurveInterpolation> InterpolatePeriodic(
    const PointsView& points, int p, absl::Span<const double> t,
    const PeriodicKnots& kappa, int shift, const CancellationToken* cancel);

// InterpolateClosed returns InterpolateCurve's closed curve through the
// points (options.closed): periodic knots, uniform or averaged (eq. 9.8)
// over the periodically extended parameters; end derivatives are refused.
absl::StatusOr<CurveInterpolation> InterpolateClosed(
    const PointsView& points, const CurveInterpolationOptions& options);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_CONSTRUCT_PERIODIC_INTERPOLATION_H_
