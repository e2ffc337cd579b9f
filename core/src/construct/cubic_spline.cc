// Cubic splines with the classic end conditions (InterpolateCubicSpline;
// de Boor, "A Practical Guide to Splines", ch. IV): the open ones as open
// collocation systems, the periodic one as a periodic interpolation.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/types/span.h"
#include "base/point_array.h"
#include "construct/interpolation_parameters.h"
#include "construct/interpolation_result.h"
#include "construct/open_interpolation.h"
#include "construct/periodic_interpolation.h"
#include "freeform/core/interpolation.h"
#include "freeform/core/points.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "linalg/banded_lu.h"
#include "refine/knot_insertion.h"

namespace freeform {
namespace {

using internal::EndCondition;
using internal::FinishInterpolation;
using internal::InterpolatePeriodic;
using internal::MakeCurve;
using internal::Matrix;
using internal::PeriodicKnots;
using internal::PointArray;
using internal::RefineKnots;
using internal::SolveOpen;
using internal::Spline;
using internal::ValidateDerivative;
using internal::ValidateParameters;

// CubicKnots returns x_0 (x4), x_1, ..., x_{n-1}, x_n (x4), without x_1
// and x_{n-1} when `not_a_knot`.
std::vector<double> CubicKnots(absl::Span<const double> x, bool not_a_knot) {
  std::vector<double> knots(4, x.front());
  for (size_t k = 1; k + 1 < x.size(); ++k) {
    if (not_a_knot && (k == 1 || k + 2 == x.size())) continue;
    knots.push_back(x[k]);
  }
  knots.insert(knots.end(), 4, x.back());
  return knots;
}

// WithKnots returns the non-rational `curve` with the non-decreasing knots
// `x` inserted (knot_insertion.h): the same curve on more knots.
absl::StatusOr<BSplineCurveData> WithKnots(BSplineCurveData curve,
                                           absl::Span<const double> x,
                                           const CancellationToken* cancel) {
  absl::StatusOr<Spline> refined = RefineKnots(
      Spline{curve.degree, std::move(curve.knots),
             PointArray{curve.dimension, std::move(curve.coordinates)}},
      x, cancel);
  if (!refined.ok()) return refined.status();
  curve.knots = std::move(refined->knots);
  curve.coordinates = std::move(refined->points.values);
  return curve;
}

// PolynomialEndSlopes returns the end derivatives of the line (2 points) or
// parabola (3 points) through the data, from divided differences.
std::pair<Matrix, Matrix> PolynomialEndSlopes(const PointsView& values,
                                              absl::Span<const double> x) {
  const size_t d = static_cast<size_t>(values.dimension);
  const size_t last = values.size() - 1;
  Matrix start(d), end(d);
  for (size_t c = 0; c < d; ++c) {
    const double f01 =
        (values.point(1)[c] - values.point(0)[c]) / (x[1] - x[0]);
    if (last == 1) {
      start[c] = end[c] = f01;
      continue;
    }
    const double f12 =
        (values.point(2)[c] - values.point(1)[c]) / (x[2] - x[1]);
    const double f012 = (f12 - f01) / (x[2] - x[0]);
    start[c] = f01 + f012 * (x[0] - x[1]);
    end[c] = f12 + f012 * (x[2] - x[1]);
  }
  return {std::move(start), std::move(end)};
}

absl::Status ValidatePeriodicEnds(const PointsView& values) {
  double scale = 1;
  for (double value : values.coordinates) {
    scale = std::max(scale, std::abs(value));
  }
  const double gap = PointDistance(
      values.point(0), values.point(values.size() - 1), values.dimension);
  if (gap > 1e-12 * scale) {
    return InvalidFieldError(
        "points", "a periodic spline needs the last value equal to the first");
  }
  return absl::OkStatus();
}

absl::StatusOr<CurveInterpolation> PeriodicCubicSpline(
    const PointsView& values, absl::Span<const double> x,
    const CancellationToken* cancel) {
  RETURN_IF_ERROR(ValidatePeriodicEnds(values));
  const size_t n = values.size() - 1;
  const PointsView distinct{.dimension = values.dimension,
                            .coordinates = values.coordinates.subspan(
                                0, n * static_cast<size_t>(values.dimension))};
  PeriodicKnots kappa{.base = std::vector<double>(x.begin(), x.end() - 1),
                      .period = x.back() - x.front()};
  absl::StatusOr<CurveInterpolation> result =
      InterpolatePeriodic(distinct, 3, x.subspan(0, n), kappa, 2, cancel);
  if (!result.ok()) return result;
  // The knots u_3..u_{n+3} are the abscissas themselves (x_0 + T may differ
  // from x_n in the last bit).
  std::copy(x.begin(), x.end(), result->curve.knots.begin() + 3);
  result->parameters.assign(x.begin(), x.end());
  return FinishInterpolation(std::move(result->curve),
                             std::move(result->parameters), values, cancel);
}

absl::Status ValidateSplineInput(const PointsView& values,
                                 absl::Span<const double> x, SplineEnd end,
                                 absl::Span<const double> start_derivative,
                                 absl::Span<const double> end_derivative) {
  RETURN_IF_ERROR(
      ValidatePoints(values, "points", end == SplineEnd::kPeriodic ? 3 : 2));
  if (x.size() != values.size()) {
    return InvalidFieldError("parameters",
                             absl::StrCat("needs one abscissa per point (",
                                          values.size(), "), got ", x.size()));
  }
  RETURN_IF_ERROR(ValidateParameters(x));
  const bool clamped = end == SplineEnd::kClamped;
  RETURN_IF_ERROR(ValidateDerivative(start_derivative, "start_derivative",
                                     values.dimension, clamped));
  return ValidateDerivative(end_derivative, "end_derivative", values.dimension,
                            clamped);
}

}  // namespace

absl::StatusOr<CurveInterpolation> InterpolateCubicSpline(
    const PointsView& values, absl::Span<const double> x, SplineEnd end,
    absl::Span<const double> start_derivative,
    absl::Span<const double> end_derivative, const CancellationToken* cancel) {
  RETURN_IF_ERROR(
      ValidateSplineInput(values, x, end, start_derivative, end_derivative));
  if (end == SplineEnd::kPeriodic) {
    return PeriodicCubicSpline(values, x, cancel);
  }
  std::vector<double> t(x.begin(), x.end());
  if (end == SplineEnd::kNotAKnot && values.size() >= 4) {
    absl::StatusOr<Matrix> control =
        SolveOpen(values, 3, CubicKnots(x, true), x, {}, {}, cancel);
    if (!control.ok()) return control.status();
    const double removed[] = {x[1], x[x.size() - 2]};
    absl::StatusOr<BSplineCurveData> curve =
        WithKnots(MakeCurve(3, values.dimension, *std::move(control),
                            CubicKnots(x, true)),
                  removed, cancel);
    if (!curve.ok()) return curve.status();
    return FinishInterpolation(*std::move(curve), std::move(t), values, cancel);
  }
  EndCondition start{.order = 2, .value = {}}, finish{.order = 2, .value = {}};
  std::pair<Matrix, Matrix> slopes;
  if (end == SplineEnd::kNotAKnot) {  // 2 or 3 points: line or parabola
    slopes = PolynomialEndSlopes(values, x);
    start = {.order = 1, .value = slopes.first};
    finish = {.order = 1, .value = slopes.second};
  } else if (end == SplineEnd::kClamped) {
    start = {.order = 1, .value = start_derivative};
    finish = {.order = 1, .value = end_derivative};
  }
  absl::StatusOr<Matrix> control =
      SolveOpen(values, 3, CubicKnots(x, false), x, start, finish, cancel);
  if (!control.ok()) return control.status();
  return FinishInterpolation(
      MakeCurve(3, values.dimension, *std::move(control), CubicKnots(x, false)),
      std::move(t), values, cancel);
}

}  // namespace freeform
