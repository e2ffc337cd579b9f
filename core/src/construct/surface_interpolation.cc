// Surface interpolation through a grid of points (InterpolateSurface; The
// NURBS Book A9.4): averaged grid parameters, then one open collocation
// system per direction, factored once and solved for every line of the grid.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/types/span.h"
#include "construct/interpolation_knots.h"
#include "construct/interpolation_parameters.h"
#include "construct/open_interpolation.h"
#include "freeform/core/interpolation.h"
#include "freeform/core/points.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/surface_output.h"
#include "freeform/core/tensor_surface.h"
#include "linalg/banded_lu.h"

namespace freeform {
namespace {

using internal::BandedLu;
using internal::BuildOpenRows;
using internal::FactorOpenSystem;
using internal::KnotsFor;
using internal::UniformValues;
using internal::UniversalParameters;
using internal::ValidatePositiveDegree;

// GridParameters averages the parameters of the count_u "columns"
// Q[.][l] (u direction) or of the rows (v direction, `along_u` false),
// skipping lines of zero length for chord length and centripetal (A9.3).
absl::StatusOr<std::vector<double>> GridParameters(
    const ControlNetView& net, bool along_u, int degree,
    Parameterization parameterization) {
  const int count = along_u ? net.count_u : net.count_v;
  const int lines = along_u ? net.count_v : net.count_u;
  if (parameterization == Parameterization::kUniversal) {
    return UniversalParameters(count, degree);
  }
  if (parameterization == Parameterization::kUniform) {
    return UniformValues(static_cast<size_t>(count) - 1);
  }
  const bool centripetal = parameterization == Parameterization::kCentripetal;
  std::vector<double> sum(static_cast<size_t>(count), 0.0), line(sum);
  int used = 0;
  for (int l = 0; l < lines; ++l) {
    for (int k = 1; k < count; ++k) {
      const double chord = PointDistance(
          along_u ? net.point(k, l) : net.point(l, k),
          along_u ? net.point(k - 1, l) : net.point(l, k - 1), net.dimension);
      line[static_cast<size_t>(k)] = line[static_cast<size_t>(k) - 1] +
                                     (centripetal ? std::sqrt(chord) : chord);
    }
    const double total = line.back();
    if (!(total > 0)) continue;
    ++used;
    for (int k = 1; k < count; ++k) {
      sum[static_cast<size_t>(k)] += line[static_cast<size_t>(k)] / total;
    }
  }
  if (used == 0) {
    return InvalidFieldError("points", "every grid line has zero length");
  }
  for (double& value : sum) value /= used;
  sum.back() = 1.0;
  for (size_t k = 1; k < sum.size(); ++k) {
    if (!(sum[k] > sum[k - 1])) {
      return InvalidFieldError(
          "points", absl::StrCat("the averaged ", along_u ? "u" : "v",
                                 " parameters repeat at index ", k,
                                 " (a whole grid line repeated)"));
    }
  }
  return sum;
}

absl::StatusOr<double> SurfaceResidual(const SurfaceInterpolation& result,
                                       const ControlNetView& points,
                                       const CancellationToken* cancel) {
  std::vector<double> values(points.coordinates.size());
  const std::vector<absl::Span<double>> output = {absl::MakeSpan(values)};
  if (absl::Status status = EvaluateBSplineSurface(
          result.surface.bspline_view(),
          SurfaceSamples::Grid(result.parameters_u, result.parameters_v),
          output, ExecutionContext{.cancellation = cancel});
      !status.ok()) {
    return status;
  }
  double max = 0;
  const size_t d = static_cast<size_t>(points.dimension);
  for (size_t k = 0; k * d < values.size(); ++k) {
    max = std::max(max, PointDistance(values.data() + k * d,
                                      points.coordinates.data() + k * d,
                                      points.dimension));
  }
  return max;
}

}  // namespace

absl::StatusOr<SurfaceInterpolation> InterpolateSurface(
    const ControlNetView& points, int degree_u, int degree_v,
    Parameterization parameterization, KnotRule knot_rule,
    const CancellationToken* cancel) {
  if (knot_rule == KnotRule::kAtParameters) {
    return InvalidFieldError(
        "knot_rule",
        "kAtParameters needs end derivatives, which surfaces do not take");
  }
  RETURN_IF_ERROR(ValidatePositiveDegree(degree_u, "degree_u"));
  RETURN_IF_ERROR(ValidatePositiveDegree(degree_v, "degree_v"));
  RETURN_IF_ERROR(
      ValidateControlNet(points, "points", degree_u + 1, degree_v + 1));
  SurfaceInterpolation result;
  absl::StatusOr<std::vector<double>> tu =
      GridParameters(points, true, degree_u, parameterization);
  if (!tu.ok()) return tu.status();
  absl::StatusOr<std::vector<double>> tv =
      GridParameters(points, false, degree_v, parameterization);
  if (!tv.ok()) return tv.status();
  result.parameters_u = *std::move(tu);
  result.parameters_v = *std::move(tv);
  SurfaceData& surface = result.surface;
  surface.degree_u = degree_u;
  surface.degree_v = degree_v;
  surface.dimension = points.dimension;
  surface.count_u = points.count_u;
  surface.count_v = points.count_v;
  for (const bool in_u : {true, false}) {
    absl::StatusOr<std::vector<double>> knots = KnotsFor(
        in_u ? result.parameters_u : result.parameters_v,
        in_u ? degree_u : degree_v, parameterization, knot_rule, cancel);
    if (!knots.ok()) return knots.status();
    (in_u ? surface.knots_u : surface.knots_v) = *std::move(knots);
  }
  // Two factorizations (docs/references.md, 'Global B-spline
  // interpolation'): u once for all columns, v once for all rows of the
  // intermediate net.
  auto factor = [&](int degree, absl::Span<const double> knots,
                    absl::Span<const double> t) {
    return FactorOpenSystem(
        degree, BuildOpenRows(degree, knots, t, {}, {}, cancel), cancel);
  };
  absl::StatusOr<BandedLu> along_u =
      factor(degree_u, surface.knots_u, result.parameters_u);
  if (!along_u.ok()) return along_u.status();
  absl::StatusOr<BandedLu> along_v =
      factor(degree_v, surface.knots_v, result.parameters_v);
  if (!along_v.ok()) return along_v.status();
  surface.coordinates.assign(points.coordinates.begin(),
                             points.coordinates.end());
  const size_t row = static_cast<size_t>(points.count_v) *
                     static_cast<size_t>(points.dimension);
  RETURN_IF_ERROR(
      along_u->Solve(surface.coordinates.data(), static_cast<int>(row)));
  for (size_t k = 0; k < static_cast<size_t>(points.count_u); ++k) {
    RETURN_IF_ERROR(
        along_v->Solve(surface.coordinates.data() + k * row, points.dimension));
  }
  absl::StatusOr<double> residual = SurfaceResidual(result, points, cancel);
  if (!residual.ok()) return residual.status();
  result.max_residual = *residual;
  return result;
}

}  // namespace freeform
