// What every curve interpolation and approximation (interpolation.h) ends
// with: its control points and knots as a non-rational B-spline, and the
// distances from the curve at the parameters to the data points, measured
// with EvaluateBSplineCurve. Internal to the core; thread-safe (pure
// functions).
#ifndef FREEFORM_CORE_SRC_CONSTRUCT_INTERPOLATION_RESULT_H_
#define FREEFORM_CORE_SRC_CONSTRUCT_INTERPOLATION_RESULT_H_

#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/geometry_data.h"
#include "freeform/core/interpolation.h"
#include "freeform/core/points.h"
#include "linalg/banded_lu.h"

namespace freeform::internal {

// MakeCurve returns the non-rational B-spline of degree p with the control
// points `coordinates` (of `dimension` values each) on `knots`.
BSplineCurveData MakeCurve(int p, int dimension, Matrix coordinates,
                           std::vector<double> knots);

// CurveResiduals returns max_k |C(t_k) - Q_k| and the sum of their squares;
// fails only with the token's status.
absl::StatusOr<std::pair<double, double>> CurveResiduals(
    const BSplineCurveData& curve, absl::Span<const double> t,
    const PointsView& points, const CancellationToken* cancel);

// FinishInterpolation returns the interpolation of `points` by `curve` at
// the parameters t, with its largest residual.
absl::StatusOr<CurveInterpolation> FinishInterpolation(
    BSplineCurveData curve, std::vector<double> t, const PointsView& points,
    const CancellationToken* cancel);

// FinishMeasuredInterpolation is FinishInterpolation for a residual
// already measured as EvaluateBSplineCurve would (SolveOpenMeasured; NaN
// when a control point is not finite): it checks the knots and the
// parameters as that evaluation does and, when they pass and the residual
// is finite, returns the interpolation with `max_residual`; otherwise it
// returns FinishInterpolation's answer (its error).
absl::StatusOr<CurveInterpolation> FinishMeasuredInterpolation(
    BSplineCurveData curve, std::vector<double> t, double max_residual,
    const PointsView& points, const CancellationToken* cancel);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_CONSTRUCT_INTERPOLATION_RESULT_H_
