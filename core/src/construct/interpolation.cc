// Global curve interpolation (InterpolateCurve; The NURBS Book A9.1, A9.2):
// the open curve through the points with optional end derivatives; closed
// curves and the kAtParameters knot rule go to their own files.
#include "freeform/core/interpolation.h"

#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "construct/interpolation_at_parameters.h"
#include "construct/interpolation_knots.h"
#include "construct/interpolation_parameters.h"
#include "construct/interpolation_result.h"
#include "construct/open_interpolation.h"
#include "construct/periodic_interpolation.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "linalg/banded_lu.h"

namespace freeform {
namespace {

using internal::EndCondition;
using internal::ExplicitParameters;
using internal::FinishMeasuredInterpolation;
using internal::InterpolateAtParameters;
using internal::InterpolateClosed;
using internal::KnotsFor;
using internal::MakeCurve;
using internal::OpenParameters;
using internal::OpenSolution;
using internal::SolveOpenMeasured;
using internal::UniversalParameters;
using internal::ValidateCurveData;
using internal::ValidateEndDerivatives;

}  // namespace

absl::StatusOr<CurveInterpolation> InterpolateCurve(
    const PointsView& points, const CurveInterpolationOptions& options) {
  if (options.knot_rule == KnotRule::kAtParameters) {
    return InterpolateAtParameters(points, options);
  }
  if (options.scale_end_derivatives) {
    return InvalidFieldError(
        "scale_end_derivatives",
        "only the kAtParameters knot rule scales end derivatives");
  }
  const int p = options.degree;
  RETURN_IF_ERROR(ValidateCurveData(points, p));
  if (options.closed) return InterpolateClosed(points, options);
  const bool has_start = !options.start_derivative.empty();
  const bool has_end = !options.end_derivative.empty();
  RETURN_IF_ERROR(ValidateEndDerivatives(options, points.dimension));
  const int count = static_cast<int>(points.size()) + has_start + has_end;
  std::vector<double> t;
  const bool universal =
      options.parameters.empty() &&
      options.parameterization == Parameterization::kUniversal;
  if (!options.parameters.empty()) {
    absl::StatusOr<std::vector<double>> given =
        ExplicitParameters(options.parameters, points.size());
    if (!given.ok()) return given.status();
    t = *std::move(given);
  } else if (universal) {
    // The maxima of every basis function except the derivative rows'.
    const std::vector<double> maxima = UniversalParameters(count, p);
    for (int i = 0; i < count; ++i) {
      if ((has_start && i == 1) || (has_end && i == count - 2)) continue;
      t.push_back(maxima[static_cast<size_t>(i)]);
    }
  } else {
    absl::StatusOr<std::vector<double>> computed =
        OpenParameters(points, options.parameterization);
    if (!computed.ok()) return computed.status();
    t = *std::move(computed);
  }
  std::vector<double> doubled;  // t with the derivative ends doubled
  if (has_start || has_end) {
    if (has_start) doubled.push_back(t.front());
    doubled.insert(doubled.end(), t.begin(), t.end());
    if (has_end) doubled.push_back(t.back());
  }
  const absl::Span<const double> sites =
      has_start || has_end ? absl::Span<const double>(doubled) : t;
  absl::StatusOr<std::vector<double>> placed = KnotsFor(
      sites, p,
      universal ? Parameterization::kUniversal : Parameterization::kUniform,
      options.knot_rule, options.cancel);
  if (!placed.ok()) return placed.status();
  std::vector<double> knots = *std::move(placed);
  const EndCondition start{.order = has_start ? 1 : 0,
                           .value = options.start_derivative};
  const EndCondition end{.order = has_end ? 1 : 0,
                         .value = options.end_derivative};
  absl::StatusOr<OpenSolution> solved =
      SolveOpenMeasured(points, p, knots, t, start, end, true, options.cancel);
  if (!solved.ok()) return solved.status();
  return FinishMeasuredInterpolation(
      MakeCurve(p, points.dimension, std::move(solved->control),
                std::move(knots)),
      std::move(t), solved->max_residual, points, options.cancel);
}

}  // namespace freeform
