// The open collocation systems of global interpolation (The NURBS Book
// A9.1, A9.2; interpolation.h): a row per data point, N_{i,p}(t_k), and a
// row per end condition, C^(order) at t_0 or t_n, factored by a banded LU;
// and the checks of the end derivatives. Internal to the core; thread-safe
// (pure functions).
#ifndef FREEFORM_CORE_SRC_CONSTRUCT_OPEN_INTERPOLATION_H_
#define FREEFORM_CORE_SRC_CONSTRUCT_OPEN_INTERPOLATION_H_

#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/interpolation.h"
#include "freeform/core/points.h"
#include "linalg/banded_lu.h"

namespace freeform::internal {

// A derivative condition C^(order)(t) = value at one end (order 0: none;
// empty value: zero).
struct EndCondition {
  int order = 0;
  absl::Span<const double> value;
};

// The rows of the collocation system: row r holds the coefficients of the
// p + 1 consecutive control points starting at first[r].
struct OpenRows {
  std::vector<int> first;
  std::vector<double> values;  // (p + 1) per row
};

// BuildOpenRows fills the rows of A9.1 / A9.2: the value at t_0, the start
// condition, values at t_1..t_{n-1}, the end condition, the value at t_n.
absl::StatusOr<OpenRows> BuildOpenRows(int p, absl::Span<const double> knots,
                                       absl::Span<const double> t,
                                       EndCondition start, EndCondition end,
                                       const CancellationToken* cancel);

// FactorOpenSystem builds and factors the banded system of the rows; fails
// when the Schoenberg-Whitney condition breaks (a zero diagonal value).
absl::StatusOr<BandedLu> FactorOpenSystem(int p,
                                          const absl::StatusOr<OpenRows>& built,
                                          const CancellationToken* cancel);

// SolveOpen returns the control points of the clamped curve of degree p on
// `knots` through the points at t with the end conditions.
absl::StatusOr<Matrix> SolveOpen(const PointsView& points, int p,
                                 absl::Span<const double> knots,
                                 absl::Span<const double> t, EndCondition start,
                                 EndCondition end,
                                 const CancellationToken* cancel);

// An open system's control points and, when measured, max_k |C(t_k) - Q_k|
// over the data points Q_k, with C(t_k) computed as EvaluateBSplineCurve
// computes it (the same basis values, summed in the same order).
struct OpenSolution {
  Matrix control;
  double max_residual = 0;
};

// SolveOpenMeasured is SolveOpen that also measures the residual when
// `measure`.
absl::StatusOr<OpenSolution> SolveOpenMeasured(const PointsView& points, int p,
                                               absl::Span<const double> knots,
                                               absl::Span<const double> t,
                                               EndCondition start,
                                               EndCondition end, bool measure,
                                               const CancellationToken* cancel);

// ValidateDerivative checks an end derivative named `field`: empty unless
// `required` (only clamped ends take one), else `dimension` finite values.
absl::Status ValidateDerivative(absl::Span<const double> value,
                                absl::string_view field, int dimension,
                                bool required);

// ValidateEndDerivatives checks the end derivatives given to InterpolateCurve:
// `dimension` finite values each, and degree >= 2.
absl::Status ValidateEndDerivatives(const CurveInterpolationOptions& options,
                                    int dimension);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_CONSTRUCT_OPEN_INTERPOLATION_H_
