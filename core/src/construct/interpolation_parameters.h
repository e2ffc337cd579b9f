// The parameters t_k at which global interpolation and approximation
// (interpolation.h) place the data points: uniform, chord length,
// centripetal and universal, for open and closed sequences, or given by the
// caller and checked; and the checks of a curve's degree and points.
// Internal to the core; thread-safe (pure functions).
#ifndef FREEFORM_CORE_SRC_CONSTRUCT_INTERPOLATION_PARAMETERS_H_
#define FREEFORM_CORE_SRC_CONSTRUCT_INTERPOLATION_PARAMETERS_H_

#include <cstddef>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "freeform/core/interpolation.h"
#include "freeform/core/points.h"

namespace freeform::internal {

// UniformValues returns k / intervals for k = 0..intervals.
std::vector<double> UniformValues(size_t intervals);

// UniversalParameters returns the maxima of the `count` basis functions of
// degree p on ClampedUniformKnots(count, p). Functions with an all-uniform
// support are symmetric, their maximum is the support's midpoint; the ends
// mirror each other.
std::vector<double> UniversalParameters(int count, int p);

// ValidateParameters checks that the "parameters" are finite and strictly
// increasing.
absl::Status ValidateParameters(absl::Span<const double> parameters);

// ExplicitParameters returns the caller's parameters: one per point, finite
// and strictly increasing.
absl::StatusOr<std::vector<double>> ExplicitParameters(
    absl::Span<const double> parameters, size_t count);

// ValidatePositiveDegree checks that the degree named `field` is at least 1.
absl::Status ValidatePositiveDegree(int degree, absl::string_view field);

// ValidateCurveData checks "degree" (>= 1) and "points" (at least
// degree + 1 of them).
absl::Status ValidateCurveData(const PointsView& points, int degree);

// OpenParameters computes parameters of an open sequence (no universal).
absl::StatusOr<std::vector<double>> OpenParameters(
    const PointsView& points, Parameterization parameterization);

// ClosedParameters returns N + 1 parameters: one per point and the one where
// the curve returns to the first point.
absl::StatusOr<std::vector<double>> ClosedParameters(
    const PointsView& points, const CurveInterpolationOptions& options);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_CONSTRUCT_INTERPOLATION_PARAMETERS_H_
