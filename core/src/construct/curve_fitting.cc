// Curve fitting by least squares: on given knots (FitCurveToKnots) and
// refined to a tolerance (FitCurve); docs/references.md, 'Least-squares
// fitting to a tolerance'.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/types/span.h"
#include "construct/fitting_checks.h"
#include "construct/fixed_end_least_squares.h"
#include "construct/interpolation_result.h"
#include "construct/tolerance_refinement.h"
#include "freeform/core/bspline.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/fitting.h"
#include "freeform/core/interpolation.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"

namespace freeform {
namespace {

using internal::MakeCurve;

using internal::FixedEndLeastSquares;

// A least-squares fit on fixed knots: its control points and the distance
// |C(t_k) - Q_k| at every point.
struct KnotFit {
  std::vector<double> control;
  std::vector<double> errors;
};

absl::StatusOr<KnotFit> FitOnKnots(const PointsView& points, int p,
                                   absl::Span<const double> knots,
                                   absl::Span<const double> t,
                                   const CancellationToken* cancel) {
  absl::StatusOr<FixedEndLeastSquares> system =
      FixedEndLeastSquares::Create(p, knots, t, "parameters", cancel);
  if (!system.ok()) return system.status();
  const size_t d = static_cast<size_t>(points.dimension);
  KnotFit fit;
  absl::StatusOr<std::vector<double>> control =
      system->Solve(points.coordinates.data(), d, cancel);
  if (!control.ok()) return control.status();
  fit.control = *std::move(control);
  std::vector<double> values(points.coordinates.size());
  RETURN_IF_ERROR(
      system->Evaluate(fit.control.data(), d, values.data(), cancel));
  fit.errors.resize(points.size());
  for (size_t k = 0; k < fit.errors.size(); ++k) {
    double sum = 0;
    for (size_t c = 0; c < d; ++c) {
      const double difference = values[k * d + c] - points.point(k)[c];
      sum += difference * difference;
    }
    fit.errors[k] = std::sqrt(sum);
  }
  return fit;
}

// Largest and root-mean-square of `errors`.
std::pair<double, double> ErrorSummary(absl::Span<const double> errors) {
  double max = 0, squares = 0;
  for (double error : errors) {
    max = std::max(max, error);
    squares += error * error;
  }
  return {max, std::sqrt(squares / static_cast<double>(errors.size()))};
}

// CorrectParameters moves every interior t_k by one Newton step on
// f(t) = (C(t) - Q_k) . C'(t), the condition for the closest point (Hoschek
// 1988), when f' > 0 and the step keeps t_k strictly between t_{k-1}
// (already moved) and t_{k+1} and off the knots, so the parameters stay
// strictly increasing.
absl::Status CorrectParameters(const BSplineCurveData& curve,
                               const PointsView& points, std::vector<double>& t,
                               const CancellationToken* cancel) {
  const size_t d = static_cast<size_t>(points.dimension);
  std::vector<double> value(t.size() * d), first(t.size() * d),
      second(t.size() * d);
  const std::vector<absl::Span<double>> output = {
      absl::MakeSpan(value), absl::MakeSpan(first), absl::MakeSpan(second)};
  if (absl::Status status = EvaluateBSplineCurve(
          curve.view(), t, output, ExecutionContext{.cancellation = cancel});
      !status.ok()) {
    return status;
  }
  const int p = curve.degree;
  const int n = static_cast<int>(curve.knots.size()) - p - 2;
  int span = p;
  for (size_t k = 1; k + 1 < t.size(); ++k) {
    double slope = 0, curvature = 0;
    for (size_t c = 0; c < d; ++c) {
      const double offset = value[k * d + c] - points.point(k)[c];
      slope += offset * first[k * d + c];
      curvature +=
          first[k * d + c] * first[k * d + c] + offset * second[k * d + c];
    }
    if (!(curvature > 0)) continue;
    const double moved = t[k] - slope / curvature;
    if (!(t[k - 1] < moved && moved < t[k + 1])) continue;
    span = FindSpanFrom(span, n, p, moved, curve.knots);
    if (curve.knots[static_cast<size_t>(span)] != moved) t[k] = moved;
  }
  return absl::OkStatus();
}

double MaxError(absl::Span<const double> errors) {
  return errors.empty() ? 0 : *std::max_element(errors.begin(), errors.end());
}

// FitWithCorrections fits on `knots`, then up to `corrections` times moves
// the parameters (CorrectParameters) and fits again. A round is kept only
// when it lowers the max residual and leaves every span with at least two
// parameters (Schoenberg-Whitney could fail otherwise) and a system that
// is not singular; the first round that does not is undone and ends the
// corrections.
absl::StatusOr<KnotFit> FitWithCorrections(const PointsView& points, int p,
                                           absl::Span<const double> knots,
                                           int corrections,
                                           std::vector<double>& t,
                                           const CancellationToken* cancel) {
  absl::StatusOr<KnotFit> fit = FitOnKnots(points, p, knots, t, cancel);
  for (int round = 0; fit.ok() && round < corrections; ++round) {
    std::vector<double> previous = t;
    RETURN_IF_ERROR(CorrectParameters(
        MakeCurve(p, points.dimension, fit->control,
                  std::vector<double>(knots.begin(), knots.end())),
        points, t, cancel));
    if (!internal::SpansHoldData(p, knots, t)) {
      t = std::move(previous);
      break;
    }
    absl::StatusOr<KnotFit> corrected = FitOnKnots(points, p, knots, t, cancel);
    if (!corrected.ok() &&
        corrected.status().code() != absl::StatusCode::kInvalidArgument) {
      return corrected.status();  // cancelled
    }
    // A system made singular (in floating point) by parameters moved close
    // together ends the corrections too.
    if (!corrected.ok() ||
        !(MaxError(corrected->errors) < MaxError(fit->errors))) {
      t = std::move(previous);
      break;
    }
    fit = std::move(corrected);
  }
  return fit;
}

absl::Status ValidateCurveFitOptions(const PointsView& points,
                                     const CurveFitOptions& options) {
  if (options.degree < 1) {
    return InvalidFieldError(
        "degree", absl::StrCat("must be >= 1, got ", options.degree));
  }
  RETURN_IF_ERROR(ValidatePoints(points, "points",
                                 static_cast<size_t>(options.degree) + 1));
  RETURN_IF_ERROR(internal::ValidateTolerance(options.tolerance));
  if (options.max_control_points <= options.degree) {
    return InvalidFieldError("max_control_points",
                             absl::StrCat("must be >= degree + 1, got ",
                                          options.max_control_points));
  }
  if (options.parameter_corrections < 0 ||
      options.parameter_corrections > kMaxParameterCorrections) {
    return InvalidFieldError(
        "parameter_corrections",
        absl::StrCat("must lie in [0, ", kMaxParameterCorrections, "], got ",
                     options.parameter_corrections));
  }
  return absl::OkStatus();
}

// ExplicitParameters checks one strictly increasing parameter per point.
absl::StatusOr<std::vector<double>> ExplicitParameters(
    const PointsView& points, absl::Span<const double> parameters) {
  if (parameters.size() != points.size()) {
    return InvalidFieldError(
        "parameters",
        absl::StrCat("needs one parameter per point (", points.size(),
                     "), got ", parameters.size()));
  }
  RETURN_IF_ERROR(internal::ValidateIncreasing(parameters, "parameters"));
  return std::vector<double>(parameters.begin(), parameters.end());
}

// ValidateFitKnots checks clamped knots from t.front() to t.back() with no
// more control points than data.
absl::Status ValidateFitKnots(int p, absl::Span<const double> knots,
                              absl::Span<const double> t) {
  if (absl::Status status = ValidateBSplineBasis(p, knots, {}); !status.ok()) {
    return status;
  }
  const size_t w = static_cast<size_t>(p) + 1;
  const bool clamped =
      std::all_of(knots.begin(), knots.begin() + static_cast<ptrdiff_t>(w),
                  [&](double u) { return u == knots.front(); }) &&
      std::all_of(knots.end() - static_cast<ptrdiff_t>(w), knots.end(),
                  [&](double u) { return u == knots.back(); });
  if (!clamped || knots.front() != t.front() || knots.back() != t.back()) {
    return InvalidFieldError(
        "knots", absl::StrCat("must be clamped (degree + 1 equal knots at "
                              "each end) on [parameters.front(), "
                              "parameters.back()] = [",
                              t.front(), ", ", t.back(), "]"));
  }
  if (knots.size() - w > t.size()) {
    return InvalidFieldError(
        "knots",
        absl::StrCat("give ", knots.size() - w,
                     " control points, more than the ", t.size(), " points"));
  }
  return absl::OkStatus();
}

// RefineFit fits on one span, then inserts knots where the error exceeds
// the tolerance until it does not (FitCurve), correcting the parameters
// `t` after every fit (FitWithCorrections).
absl::StatusOr<CurveFit> RefineFit(const PointsView& points,
                                   const CurveFitOptions& options,
                                   std::vector<double> t) {
  const int p = options.degree;
  // The parameters before any correction: refinement falls back on them
  // when corrected parameters bunch up (below).
  const std::vector<double> initial = t;
  std::vector<double> knots = internal::SingleSpanKnots(p, t.front(), t.back());
  for (int round = 0;; ++round) {
    absl::StatusOr<KnotFit> fit = FitWithCorrections(
        points, p, knots, options.parameter_corrections, t, options.cancel);
    if (!fit.ok()) return fit.status();
    const size_t count = knots.size() - static_cast<size_t>(p) - 1;
    if (MaxError(fit->errors) <= options.tolerance) {
      const auto [max, rms] = ErrorSummary(fit->errors);
      return CurveFit{
          .curve = MakeCurve(p, points.dimension, std::move(fit->control),
                             std::move(knots)),
          .parameters = std::move(t),
          .max_residual = max,
          .rms_residual = rms,
          .refinement_rounds = round};
    }
    // No more control points than points: with two parameters per span
    // Schoenberg-Whitney then holds.
    const size_t capacity =
        std::min(static_cast<size_t>(options.max_control_points),
                 points.size()) -
        count;
    std::vector<double> inserted = internal::SplitFailingSpans(
        p, knots, t, fit->errors, options.tolerance, capacity);
    if (inserted.empty() && t != initial) {
      // Corrections on coarse knots can bunch the parameters where the
      // error is, so that no failing span holds enough of them to split:
      // refine by the initial parameters, which the next round corrects
      // again on the finer knots.
      // (Knots placed between corrected parameters may leave too few
      // initial ones in a span: FitCurve then starts again without
      // corrections.)
      t = initial;
      absl::StatusOr<KnotFit> plain =
          FitOnKnots(points, p, knots, t, options.cancel);
      if (!plain.ok()) return plain.status();
      if (MaxError(plain->errors) <= options.tolerance) continue;
      inserted = internal::SplitFailingSpans(p, knots, t, plain->errors,
                                             options.tolerance, capacity);
      fit = std::move(plain);
    }
    if (inserted.empty()) {
      return internal::ToleranceNotMet(
          MaxError(fit->errors), options.tolerance,
          count == static_cast<size_t>(options.max_control_points),
          "max_control_points", options.max_control_points);
    }
    knots = internal::WithKnots(knots, inserted);
  }
}

}  // namespace

absl::StatusOr<CurveFit> FitCurve(const PointsView& points,
                                  const CurveFitOptions& options) {
  RETURN_IF_ERROR(ValidateCurveFitOptions(points, options));
  const int p = options.degree;
  absl::StatusOr<std::vector<double>> t =
      options.parameters.empty()
          ? InterpolationParameters(points, p, options.parameterization)
          : ExplicitParameters(points, options.parameters);
  if (!t.ok()) return t.status();
  absl::StatusOr<CurveFit> fit = RefineFit(points, options, *t);
  if (fit.ok() || options.parameter_corrections == 0 ||
      (fit.status().code() != absl::StatusCode::kResourceExhausted &&
       fit.status().code() != absl::StatusCode::kInvalidArgument)) {
    return fit;
  }
  // Corrections moved the parameters so that refinement got stuck (or a
  // system became singular) where a fit without them need not: corrections
  // never make FitCurve fail where the plain fit succeeds. (The input was
  // validated above, so INVALID_ARGUMENT here comes from the corrections.)
  CurveFitOptions plain = options;
  plain.parameter_corrections = 0;
  return RefineFit(points, plain, *std::move(t));
}

absl::StatusOr<CurveApproximation> FitCurveToKnots(
    const PointsView& points, int degree, absl::Span<const double> knots,
    absl::Span<const double> parameters, const CancellationToken* cancel) {
  if (degree < 1) {
    return InvalidFieldError("degree",
                             absl::StrCat("must be >= 1, got ", degree));
  }
  RETURN_IF_ERROR(
      ValidatePoints(points, "points", static_cast<size_t>(degree) + 1));
  absl::StatusOr<std::vector<double>> t =
      ExplicitParameters(points, parameters);
  if (!t.ok()) return t.status();
  RETURN_IF_ERROR(ValidateFitKnots(degree, knots, *t));
  absl::StatusOr<KnotFit> fit = FitOnKnots(points, degree, knots, *t, cancel);
  if (!fit.ok()) return fit.status();
  const auto [max, rms] = ErrorSummary(fit->errors);
  return CurveApproximation{
      .curve = MakeCurve(degree, points.dimension, std::move(fit->control),
                         std::vector<double>(knots.begin(), knots.end())),
      .parameters = *std::move(t),
      .max_residual = max,
      .rms_residual = rms};
}

}  // namespace freeform
