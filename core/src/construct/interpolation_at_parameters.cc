#include "construct/interpolation_at_parameters.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "construct/interpolation_parameters.h"
#include "construct/interpolation_result.h"
#include "construct/open_interpolation.h"
#include "construct/periodic_interpolation.h"
#include "freeform/core/lagrange.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "linalg/banded_lu.h"

namespace freeform::internal {
namespace {

// LagrangeSlope returns the derivative at `at` of the Lagrange polynomial
// through the `count` points from `first` at their parameters t.
Matrix LagrangeSlope(const PointsView& points, absl::Span<const double> t,
                     size_t first, size_t count, double at) {
  const absl::Span<const double> nodes = t.subspan(first, count);
  const std::vector<double> weights = BarycentricWeights(nodes);
  std::vector<double> basis(2 * count), scratch(2);
  LagrangeBasis(nodes, weights, at, 1, absl::MakeSpan(scratch),
                absl::MakeSpan(basis));
  const size_t d = static_cast<size_t>(points.dimension);
  Matrix slope(d, 0.0);
  for (size_t i = 0; i < count; ++i) {
    const double* point = points.point(first + i);
    for (size_t c = 0; c < d; ++c) slope[c] += basis[count + i] * point[c];
  }
  return slope;
}

double SumOfAbsolutes(absl::Span<const double> values) {
  double sum = 0;
  for (double value : values) sum += std::abs(value);
  return sum;
}

// EndSlope returns the derivative condition at the start (or end) of the
// open sequence at t: the given derivative; scaled by |L'|_1 / |given|_1
// with L the Lagrange polynomial through the first min(N, 3) points,
// evaluated at that end (GeomAPI_Interpolate's ScaleTangents, which takes
// the first points for every tangent); or, when not given, the derivative
// of the Lagrange polynomial through the min(N, 4) points at that end.
absl::StatusOr<Matrix> EndSlope(const PointsView& points,
                                absl::Span<const double> t,
                                absl::Span<const double> given, bool at_end,
                                bool scale, absl::string_view field) {
  const double at = at_end ? t.back() : t.front();
  if (given.empty()) {
    const size_t count = std::min<size_t>(t.size(), 4);
    return LagrangeSlope(points, t, at_end ? t.size() - count : 0, count, at);
  }
  Matrix slope(given.begin(), given.end());
  if (!scale) return slope;
  const double length = SumOfAbsolutes(given);
  if (!(length > 0)) {
    return InvalidFieldError(field,
                             "a zero vector has no direction to scale "
                             "(scale_end_derivatives)");
  }
  const double ratio = SumOfAbsolutes(LagrangeSlope(
                           points, t, 0, std::min<size_t>(t.size(), 3), at)) /
                       length;
  for (double& value : slope) value *= ratio;
  return slope;
}

// AtParametersDegree returns the degree of GeomAPI_Interpolate's curve: 1
// for two points and 2 for three open points without derivatives, else 3.
int AtParametersDegree(size_t count, const CurveInterpolationOptions& options) {
  if (!options.start_derivative.empty() || !options.end_derivative.empty() ||
      count > 3) {
    return 3;
  }
  if (count == 2) return 1;
  return options.closed ? 3 : 2;
}

absl::Status ValidateAtParameters(const PointsView& points,
                                  const CurveInterpolationOptions& options) {
  RETURN_IF_ERROR(ValidatePoints(points, "points", 2));
  if (options.closed && !options.end_derivative.empty()) {
    return InvalidFieldError(
        "end_derivative",
        "a closed curve takes its one derivative, where it closes, in "
        "start_derivative");
  }
  if (options.parameters.empty() &&
      options.parameterization == Parameterization::kUniversal) {
    return InvalidFieldError(
        "parameterization",
        "kUniversal fixes its own knots; the kAtParameters knot rule takes "
        "chord length, centripetal, uniform or explicit parameters");
  }
  const int degree = AtParametersDegree(points.size(), options);
  if (options.degree != degree) {
    return InvalidFieldError(
        "degree",
        absl::StrCat("the kAtParameters knot rule needs degree ", degree,
                     " for these ", points.size(),
                     " points and derivatives, got ", options.degree));
  }
  return ValidateEndDerivatives(options, points.dimension);
}

// InterpolateOpenAtParameters: the polygon (degree 1), the parabola
// (degree 2, knots t_0 (x3), t_2 (x3)) or the clamped cubic with a knot at
// every parameter and the two end derivatives.
absl::StatusOr<CurveInterpolation> InterpolateOpenAtParameters(
    const PointsView& points, const CurveInterpolationOptions& options) {
  absl::StatusOr<std::vector<double>> t =
      options.parameters.empty()
          ? OpenParameters(points, options.parameterization)
          : ExplicitParameters(options.parameters, points.size());
  if (!t.ok()) return t.status();
  const int p = options.degree;
  if (p < 3) {
    std::vector<double> knots(static_cast<size_t>(p) + 1, t->front());
    knots.insert(knots.end(), static_cast<size_t>(p) + 1, t->back());
    absl::StatusOr<Matrix> control =
        SolveOpen(points, p, knots, *t, {}, {}, options.cancel);
    if (!control.ok()) return control.status();
    return FinishInterpolation(
        MakeCurve(p, points.dimension, *std::move(control), std::move(knots)),
        *std::move(t), points, options.cancel);
  }
  absl::StatusOr<Matrix> start =
      EndSlope(points, *t, options.start_derivative, false,
               options.scale_end_derivatives, "start_derivative");
  if (!start.ok()) return start.status();
  absl::StatusOr<Matrix> end =
      EndSlope(points, *t, options.end_derivative, true,
               options.scale_end_derivatives, "end_derivative");
  if (!end.ok()) return end.status();
  return InterpolateCubicSpline(points, *t, SplineEnd::kClamped, *start, *end,
                                options.cancel);
}

// InterpolateClosedAtParameters: GeomAPI_Interpolate's periodic curve, a
// cubic on the periodic knots t_0, t_0, t_1, ..., t_{N-1} (period T)
// solved as an open system with C(t_0) = C(t_N) = Q_0 and C'(t_0) =
// C'(t_N) = the start derivative, whose solution is the periodic one: its
// poles N+1, N+2 repeat 0, 1.
// Two points without a derivative give the closed polygon.
absl::StatusOr<CurveInterpolation> InterpolateClosedAtParameters(
    const PointsView& points, const CurveInterpolationOptions& options) {
  absl::StatusOr<std::vector<double>> t = ClosedParameters(points, options);
  if (!t.ok()) return t.status();
  const size_t n = points.size(), d = static_cast<size_t>(points.dimension);
  const int p = options.degree;
  const int before = p == 1 ? 1 : 2;  // knots before t_0
  PeriodicKnots kappa{.base = std::vector<double>(t->begin(), t->end() - 1),
                      .period = t->back() - t->front()};
  if (p == 3) kappa.base.insert(kappa.base.begin(), t->front());
  // N + 3 poles for the cubic (N + 1 knots a period, t_0 doubled), 3 for
  // the polygon.
  const size_t poles = kappa.base.size() + static_cast<size_t>(p + 1 - before);
  std::vector<double> knots(poles + static_cast<size_t>(p) + 1);
  for (size_t i = 0; i < knots.size(); ++i) {
    knots[i] = kappa(static_cast<long>(i) - before);
  }
  // The domain ends at t_N itself (t_0 + T may differ in the last bit).
  std::fill_n(
      knots.begin() + static_cast<ptrdiff_t>(kappa.base.size()) + before,
      before, t->back());
  Matrix closing(points.coordinates.begin(), points.coordinates.end());
  closing.insert(closing.end(), points.point(0), points.point(0) + d);
  Matrix control;
  if (p == 1) {
    control = std::move(closing);
  } else {
    const absl::Span<const double> open = absl::MakeConstSpan(*t).subspan(0, n);
    absl::StatusOr<Matrix> slope =
        EndSlope(points, open, options.start_derivative, false,
                 options.scale_end_derivatives, "start_derivative");
    if (!slope.ok()) return slope.status();
    const EndCondition seam{.order = 1, .value = *slope};
    absl::StatusOr<Matrix> solved =
        SolveOpen({.dimension = points.dimension, .coordinates = closing}, p,
                  knots, *t, seam, seam, options.cancel);
    if (!solved.ok()) return solved.status();
    control = *std::move(solved);
    // The last two poles equal the first two up to rounding; as
    // OpenCASCADE, keep the first ones, so the curve closes exactly.
    std::copy_n(control.begin(), 2 * d,
                control.end() - 2 * static_cast<ptrdiff_t>(d));
  }
  t->pop_back();
  return FinishInterpolation(
      MakeCurve(p, points.dimension, std::move(control), std::move(knots)),
      *std::move(t), points, options.cancel);
}

}  // namespace

absl::StatusOr<CurveInterpolation> InterpolateAtParameters(
    const PointsView& points, const CurveInterpolationOptions& options) {
  RETURN_IF_ERROR(ValidateAtParameters(points, options));
  return options.closed ? InterpolateClosedAtParameters(points, options)
                        : InterpolateOpenAtParameters(points, options);
}

}  // namespace freeform::internal
