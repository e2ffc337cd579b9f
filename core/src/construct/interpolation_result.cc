#include "construct/interpolation_result.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "freeform/core/bspline.h"
#include "freeform/core/points.h"
#include "freeform/core/status_macros.h"

namespace freeform::internal {

BSplineCurveData MakeCurve(int p, int dimension, Matrix coordinates,
                           std::vector<double> knots) {
  return BSplineCurveData{.degree = p,
                          .dimension = dimension,
                          .coordinates = std::move(coordinates),
                          .knots = std::move(knots),
                          .weights = {}};
}

absl::StatusOr<std::pair<double, double>> CurveResiduals(
    const BSplineCurveData& curve, absl::Span<const double> t,
    const PointsView& points, const CancellationToken* cancel) {
  std::vector<double> values(points.coordinates.size());
  const std::vector<absl::Span<double>> output = {absl::MakeSpan(values)};
  if (absl::Status status = EvaluateBSplineCurve(
          curve.view(), t, output, ExecutionContext{.cancellation = cancel});
      !status.ok()) {
    return status;
  }
  double max = 0, sum = 0;
  for (size_t k = 0; k < points.size(); ++k) {
    const double distance =
        PointDistance(values.data() + k * static_cast<size_t>(points.dimension),
                      points.point(k), points.dimension);
    max = std::max(max, distance);
    sum += distance * distance;
  }
  return std::make_pair(max, sum);
}

absl::StatusOr<CurveInterpolation> FinishInterpolation(
    BSplineCurveData curve, std::vector<double> t, const PointsView& points,
    const CancellationToken* cancel) {
  absl::StatusOr<std::pair<double, double>> residuals =
      CurveResiduals(curve, t, points, cancel);
  if (!residuals.ok()) return residuals.status();
  return CurveInterpolation{.curve = std::move(curve),
                            .parameters = std::move(t),
                            .max_residual = residuals->first};
}

absl::StatusOr<CurveInterpolation> FinishMeasuredInterpolation(
    BSplineCurveData curve, std::vector<double> t, double max_residual,
    const PointsView& points, const CancellationToken* cancel) {
  // The checks EvaluateBSplineCurve would make of the curve and t.
  bool evaluable =
      std::isfinite(max_residual) && ValidateBSplineCurve(curve.view()).ok();
  if (evaluable) {
    const ParameterDomain domain = BSplineDomain(curve.view());
    evaluable = ValidateInRange(t, domain.start, domain.end, "parameters").ok();
  }
  if (!evaluable) {
    return FinishInterpolation(std::move(curve), std::move(t), points, cancel);
  }
  RETURN_IF_ERROR(CheckCancelled(cancel));
  return CurveInterpolation{.curve = std::move(curve),
                            .parameters = std::move(t),
                            .max_residual = max_residual};
}

}  // namespace freeform::internal
