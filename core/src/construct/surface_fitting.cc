// Gridded surface fitting to a tolerance (FitSurfaceToGrid):
// tensor-product least squares with the knots refined per direction;
// docs/references.md, 'Least-squares fitting to a tolerance'.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "construct/fitting_checks.h"
#include "construct/fixed_end_least_squares.h"
#include "construct/tolerance_refinement.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/fitting.h"
#include "freeform/core/interpolation.h"
#include "freeform/core/points.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"

namespace freeform {
namespace {

using internal::FixedEndLeastSquares;

absl::Status ValidateDirection(int degree, int count, int cap,
                               absl::string_view direction) {
  RETURN_IF_ERROR(internal::ValidateDegreeAndCount(
      degree, count, direction, absl::StrCat("points.count_", direction),
      "points"));
  if (cap <= degree) {
    return InvalidFieldError(
        absl::StrCat("max_control_points_", direction),
        absl::StrCat("must be >= degree_", direction, " + 1, got ", cap));
  }
  return absl::OkStatus();
}

absl::Status ValidateGridFit(const ControlNetView& points,
                             const GridFitOptions& options) {
  RETURN_IF_ERROR(ValidateControlNet(points, "points"));
  RETURN_IF_ERROR(ValidateDirection(options.degree_u, points.count_u,
                                    options.max_control_points_u, "u"));
  RETURN_IF_ERROR(ValidateDirection(options.degree_v, points.count_v,
                                    options.max_control_points_v, "v"));
  return internal::ValidateTolerance(options.tolerance);
}

// GivenParameters checks `count` explicit parameters named `field`.
absl::Status ValidateGiven(absl::Span<const double> parameters, int count,
                           absl::string_view field) {
  if (parameters.empty()) return absl::OkStatus();
  if (parameters.size() != static_cast<size_t>(count)) {
    return InvalidFieldError(
        field,
        absl::StrCat("needs ", count, " values, got ", parameters.size()));
  }
  return internal::ValidateIncreasing(parameters, field);
}

// GridParameters fills the parameters of the fit: the given ones, the
// others as InterpolateSurface chooses them for this grid and these degrees.
absl::Status GridParameters(const ControlNetView& points,
                            const GridFitOptions& options, SurfaceFit& fit) {
  RETURN_IF_ERROR(
      ValidateGiven(options.parameters_u, points.count_u, "parameters_u"));
  RETURN_IF_ERROR(
      ValidateGiven(options.parameters_v, points.count_v, "parameters_v"));
  fit.parameters_u.assign(options.parameters_u.begin(),
                          options.parameters_u.end());
  fit.parameters_v.assign(options.parameters_v.begin(),
                          options.parameters_v.end());
  if (!fit.parameters_u.empty() && !fit.parameters_v.empty()) {
    return absl::OkStatus();
  }
  absl::StatusOr<SurfaceInterpolation> interpolation = InterpolateSurface(
      points, options.degree_u, options.degree_v, options.parameterization,
      KnotRule::kAveraging, options.cancel);
  if (!interpolation.ok()) return interpolation.status();
  if (fit.parameters_u.empty()) {
    fit.parameters_u = std::move(interpolation->parameters_u);
  }
  if (fit.parameters_v.empty()) {
    fit.parameters_v = std::move(interpolation->parameters_v);
  }
  return absl::OkStatus();
}

// Distances returns |a_k - b_k| for `count` points of dimension d.
std::vector<double> Distances(const double* a, const double* b, size_t count,
                              size_t d) {
  std::vector<double> distances(count);
  for (size_t k = 0; k < count; ++k) {
    distances[k] = PointDistance(a + k * d, b + k * d, d);
  }
  return distances;
}

// One tensor-product fit on fixed knots, with the errors split by
// direction.
struct GridRound {
  std::vector<double> control;  // the net of the fit, row after row
  std::vector<double> errors;   // |S(u_k, v_l) - Q[k][l]| over the grid
  std::vector<double> error_u;  // per u parameter: max_l e_u(k, l)
  std::vector<double> error_v;  // per v parameter: max_i e_v(i, l)
};

// FitRows fits every row of the intermediate net R (`rows` rows of
// count_v points) on the v knots: the rows of round.control, their values
// G at the v parameters in `fitted`, and e_v in round.error_v.
absl::Status FitRows(const FixedEndLeastSquares& along_v,
                     const std::vector<double>& columns, size_t rows, size_t d,
                     GridRound& round, std::vector<double>& fitted,
                     const CancellationToken* cancel) {
  const size_t count_v = along_v.data_count();
  const size_t row = count_v * d;
  const size_t net_row = along_v.control_count() * d;
  round.control.resize(rows * net_row);
  fitted.resize(rows * row);
  round.error_v.assign(count_v, 0.0);
  CancellationPoll poll(cancel);
  for (size_t i = 0; i < rows; ++i) {
    RETURN_IF_ERROR(poll.Done(4 * row));
    const double* data = columns.data() + i * row;
    absl::StatusOr<std::vector<double>> net = along_v.Solve(data, d, cancel);
    if (!net.ok()) return net.status();
    std::copy(net->begin(), net->end(),
              round.control.begin() + static_cast<ptrdiff_t>(i * net_row));
    double* value = fitted.data() + i * row;
    RETURN_IF_ERROR(along_v.Evaluate(net->data(), d, value, cancel));
    const std::vector<double> error = Distances(value, data, count_v, d);
    for (size_t l = 0; l < count_v; ++l) {
      round.error_v[l] = std::max(round.error_v[l], error[l]);
    }
  }
  return absl::OkStatus();
}

absl::StatusOr<GridRound> FitOnGrid(const ControlNetView& points,
                                    const SurfaceFit& fit,
                                    const CancellationToken* cancel) {
  const SurfaceData& surface = fit.surface;
  absl::StatusOr<FixedEndLeastSquares> along_u =
      FixedEndLeastSquares::Create(surface.degree_u, surface.knots_u,
                                   fit.parameters_u, "parameters_u", cancel);
  if (!along_u.ok()) return along_u.status();
  absl::StatusOr<FixedEndLeastSquares> along_v =
      FixedEndLeastSquares::Create(surface.degree_v, surface.knots_v,
                                   fit.parameters_v, "parameters_v", cancel);
  if (!along_v.ok()) return along_v.status();
  const size_t d = static_cast<size_t>(points.dimension);
  const size_t count_u = static_cast<size_t>(points.count_u);
  const size_t count_v = static_cast<size_t>(points.count_v);
  const size_t row = count_v * d;
  // Columns: R = the u fit of every column Q[.][l] at once, and e_u.
  absl::StatusOr<std::vector<double>> columns =
      along_u->Solve(points.coordinates.data(), row, cancel);
  if (!columns.ok()) return columns.status();
  std::vector<double> values(count_u * row);
  RETURN_IF_ERROR(
      along_u->Evaluate(columns->data(), row, values.data(), cancel));
  GridRound round;
  const std::vector<double> column_errors =
      Distances(values.data(), points.coordinates.data(), count_u * count_v, d);
  round.error_u.resize(count_u);
  for (size_t k = 0; k < count_u; ++k) {
    const auto line =
        column_errors.begin() + static_cast<ptrdiff_t>(k * count_v);
    round.error_u[k] =
        *std::max_element(line, line + static_cast<ptrdiff_t>(count_v));
  }
  // Rows, then the surface at the grid: the u fit evaluated on G.
  std::vector<double> fitted;
  RETURN_IF_ERROR(FitRows(*along_v, *columns, along_u->control_count(), d,
                          round, fitted, cancel));
  RETURN_IF_ERROR(along_u->Evaluate(fitted.data(), row, values.data(), cancel));
  round.errors =
      Distances(values.data(), points.coordinates.data(), count_u * count_v, d);
  return round;
}

double Max(absl::Span<const double> values) {
  return *std::max_element(values.begin(), values.end());
}

// ControlCount returns the number of functions of degree p on `knots`.
size_t ControlCount(const std::vector<double>& knots, int p) {
  return knots.size() - static_cast<size_t>(p) - 1;
}

// Capacity returns how many control points a direction may still gain: up
// to its cap, and no more than its grid lines (with two parameters per
// span the fits then stay nonsingular).
size_t Capacity(int cap, int lines, const std::vector<double>& knots, int p) {
  return std::min(static_cast<size_t>(cap), static_cast<size_t>(lines)) -
         ControlCount(knots, p);
}

// GridToleranceNotMet is the error of a fit that no direction can refine.
// The total error is at most max e_u + max e_v, so at least one direction
// is above half the tolerance: the error names its cap when that stopped
// it, else the direction with the larger error.
absl::Status GridToleranceNotMet(const SurfaceFit& fit,
                                 const GridFitOptions& options,
                                 const GridRound& round) {
  const double half = 0.5 * options.tolerance;
  const double error_u = Max(round.error_u), error_v = Max(round.error_v);
  const bool u_capped =
      error_u > half && ControlCount(fit.surface.knots_u, options.degree_u) ==
                            static_cast<size_t>(options.max_control_points_u);
  const bool v_capped =
      error_v > half && ControlCount(fit.surface.knots_v, options.degree_v) ==
                            static_cast<size_t>(options.max_control_points_v);
  const bool in_u = u_capped || (!v_capped && error_u >= error_v);
  return internal::ToleranceNotMet(
      fit.max_residual, options.tolerance, u_capped || v_capped,
      in_u ? "max_control_points_u" : "max_control_points_v",
      in_u ? options.max_control_points_u : options.max_control_points_v);
}

}  // namespace

absl::StatusOr<SurfaceFit> FitSurfaceToGrid(const ControlNetView& points,
                                            const GridFitOptions& options) {
  RETURN_IF_ERROR(ValidateGridFit(points, options));
  SurfaceFit fit;
  RETURN_IF_ERROR(GridParameters(points, options, fit));
  const int p = options.degree_u, q = options.degree_v;
  SurfaceData& surface = fit.surface;
  surface.degree_u = p;
  surface.degree_v = q;
  surface.dimension = points.dimension;
  surface.knots_u = internal::SingleSpanKnots(p, fit.parameters_u.front(),
                                              fit.parameters_u.back());
  surface.knots_v = internal::SingleSpanKnots(q, fit.parameters_v.front(),
                                              fit.parameters_v.back());
  const double half = 0.5 * options.tolerance;
  for (int round = 0;; ++round) {
    absl::StatusOr<GridRound> result = FitOnGrid(points, fit, options.cancel);
    if (!result.ok()) return result.status();
    double squares = 0;
    for (double error : result->errors) squares += error * error;
    fit.max_residual = Max(result->errors);
    fit.rms_residual =
        std::sqrt(squares / static_cast<double>(result->errors.size()));
    if (fit.max_residual <= options.tolerance) {
      surface.count_u = static_cast<int>(ControlCount(surface.knots_u, p));
      surface.count_v = static_cast<int>(ControlCount(surface.knots_v, q));
      surface.coordinates = std::move(result->control);
      fit.refinement_rounds = round;
      return fit;
    }
    const std::vector<double> inserted_u = internal::SplitFailingSpans(
        p, surface.knots_u, fit.parameters_u, result->error_u, half,
        Capacity(options.max_control_points_u, points.count_u, surface.knots_u,
                 p));
    const std::vector<double> inserted_v = internal::SplitFailingSpans(
        q, surface.knots_v, fit.parameters_v, result->error_v, half,
        Capacity(options.max_control_points_v, points.count_v, surface.knots_v,
                 q));
    if (inserted_u.empty() && inserted_v.empty()) {
      return GridToleranceNotMet(fit, options, *result);
    }
    surface.knots_u = internal::WithKnots(surface.knots_u, inserted_u);
    surface.knots_v = internal::WithKnots(surface.knots_v, inserted_v);
  }
}

}  // namespace freeform
