// CurveService RPCs that build new curves: degree elevation and reduction,
// interpolation and approximation.
#include <algorithm>

#include "absl/strings/str_cat.h"
#include "convert.h"
#include "curve_service.h"
#include "freeform/core/elevation.h"
#include "freeform/core/interpolation.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "geometry_out.h"
#include "plan.h"
#include "prepare.h"
#include "prepare_options.h"
#include "visit.h"

namespace freeform::server {
namespace {

absl::Status CheckBy(uint32_t by, int degree, const ServiceLimits& limits) {
  if (by < 1) return InvalidFieldError("by", "must be at least 1");
  if (int64_t{degree} + by > limits.max_degree) {
    return InvalidFieldError(
        "by", absl::StrCat("degree ", degree, " + ", by,
                           " would exceed the server's limit of ",
                           limits.max_degree, " (--max_degree)"));
  }
  return absl::OkStatus();
}

absl::StatusOr<UnaryWork> PlanBezierElevate(
    const BezierCurve& bezier, const v1::ElevateCurveDegreeRequest& request,
    const ServiceLimits& limits, v1::ElevateCurveDegreeResponse& response) {
  RETURN_IF_ERROR(CheckBy(request.by(), bezier.degree(), limits));
  const int by = static_cast<int>(request.by());
  const BezierCurveView view = bezier.view();
  const uint64_t values = (view.control_points.size() + by) *
                          (static_cast<uint64_t>(bezier.dimension()) + 1);
  return UnaryWork{
      .plan = AnswerPlan(values, 8 * values, limits),
      .run = [bezier, by, &response](const ExecutionContext&) -> absl::Status {
        absl::StatusOr<BezierCurveData> elevated =
            ElevateBezierCurve(bezier.view(), by);
        if (!elevated.ok()) return elevated.status();
        ToProto(*elevated, *response.mutable_curve());
        return absl::OkStatus();
      }};
}

absl::StatusOr<UnaryWork> PlanBSplineElevate(
    const BSplineCurve& bspline, const v1::ElevateCurveDegreeRequest& request,
    const ServiceLimits& limits, v1::ElevateCurveDegreeResponse& response) {
  RETURN_IF_ERROR(CheckBy(request.by(), bspline.degree(), limits));
  const int by = static_cast<int>(request.by());
  const BSplineCurveView view = bspline.view();
  // Every distinct knot gains `by` copies: at most (n + 2) by more points.
  const uint64_t count =
      view.control_points.size() + (view.control_points.size() + 1) * by;
  RETURN_IF_ERROR(CheckPointLimit(count, limits, "by"));
  const uint64_t values =
      count * (static_cast<uint64_t>(bspline.dimension()) + 2) +
      view.knots.size();
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "by"));
  return UnaryWork{
      .plan = AnswerPlan(values, 8 * values, limits),
      .run = [view, by,
              &response](const ExecutionContext& execution) -> absl::Status {
        absl::StatusOr<BSplineCurveData> elevated =
            ElevateBSplineCurve(view, by, execution.cancellation);
        if (!elevated.ok()) return elevated.status();
        ToProto(*elevated, *response.mutable_curve());
        return absl::OkStatus();
      }};
}

absl::StatusOr<UnaryWork> PlanElevate(
    const v1::ElevateCurveDegreeRequest& request, const ServiceLimits& limits,
    v1::ElevateCurveDegreeResponse& response) {
  absl::StatusOr<Curve> curve = PrepareCurve(request.curve(), limits);
  if (!curve.ok()) return curve.status();
  return std::visit<absl::StatusOr<UnaryWork>>(
      Overloaded{
          [&](const BezierCurve& bezier) {
            return PlanBezierElevate(bezier, request, limits, response);
          },
          [&](const BSplineCurve& bspline) {
            return PlanBSplineElevate(bspline, request, limits, response);
          },
          Refuse<LagrangeCurve, HermiteCurve>{
              "curve",
              "degree elevation takes a Bezier, power-form or B-spline/NURBS "
              "curve"}},
      *curve);
}

constexpr char kReductionTakes[] =
    "degree reduction takes a polynomial Bezier curve";

absl::StatusOr<UnaryWork> PlanBezierReduce(
    const BezierCurve& bezier, const v1::ReduceCurveDegreeRequest& request,
    const ServiceLimits& limits, v1::ReduceCurveDegreeResponse& response) {
  if (bezier.view().rational()) {
    return InvalidFieldError("curve.bezier.weights", kReductionTakes);
  }
  if (request.by() < 1 ||
      static_cast<int64_t>(request.by()) >= bezier.degree()) {
    return InvalidFieldError(
        "by", absl::StrCat("must be between 1 and the degree - 1 = ",
                           bezier.degree() - 1,
                           " (a curve keeps degree 1 or "
                           "more), got ",
                           request.by()));
  }
  const BezierCurveView view = bezier.view();
  const uint64_t values = view.control_points.coordinates.size() + 1;
  // The work: the degree-elevation matrix, its binomials in long double,
  // and the least-squares system, each about (n + 1)^2 values.
  const uint64_t points = view.control_points.size();
  return UnaryWork{.plan = AnswerPlan(values, 64 * points * points, limits),
                   .run = [bezier, by = static_cast<int>(request.by()),
                           &response](const ExecutionContext&) -> absl::Status {
                     absl::StatusOr<ReducedBezierCurve> reduced =
                         ReduceBezierCurve(bezier.view(), by);
                     if (!reduced.ok()) {
                       return PrefixFieldPath(reduced.status(), "curve.bezier");
                     }
                     ToProto(reduced->curve, *response.mutable_curve());
                     response.set_error_bound(reduced->error_bound);
                     return absl::OkStatus();
                   }};
}

absl::StatusOr<UnaryWork> PlanReduce(
    const v1::ReduceCurveDegreeRequest& request, const ServiceLimits& limits,
    v1::ReduceCurveDegreeResponse& response) {
  absl::StatusOr<Curve> curve = PrepareCurve(request.curve(), limits);
  if (!curve.ok()) return curve.status();
  return std::visit<absl::StatusOr<UnaryWork>>(
      Overloaded{[&](const BezierCurve& bezier) {
                   return PlanBezierReduce(bezier, request, limits, response);
                 },
                 Refuse<BSplineCurve, LagrangeCurve, HermiteCurve>{
                     "curve", kReductionTakes}},
      *curve);
}

// Writes an interpolation's result into the response.
void Answer(const BSplineCurveData& curve, const std::vector<double>& params,
            double max_residual, double rms_residual,
            v1::InterpolateCurveResponse& response) {
  ToProto(curve, *response.mutable_curve());
  response.mutable_parameters()->Add(params.begin(), params.end());
  response.set_max_residual(max_residual);
  response.set_rms_residual(rms_residual);
}

absl::Status InterpolateWithBSpline(const v1::InterpolateCurveRequest& request,
                                    const PointsView& points,
                                    const CancellationToken* cancel,
                                    v1::InterpolateCurveResponse& response) {
  const v1::BSplineInterpolation& method = request.bspline();
  RETURN_IF_ERROR(CheckEnum(method.parameterization(),
                            v1::Parameterization_IsValid, "parameterization"));
  RETURN_IF_ERROR(
      CheckEnum(method.knot_rule(), v1::KnotRule_IsValid, "knot_rule"));
  CurveInterpolationOptions options;
  options.degree = static_cast<int>(method.degree());
  options.parameterization = ToCore(method.parameterization());
  options.parameters = SpanOf(method.parameters());
  options.knot_rule = ToCore(method.knot_rule());
  options.start_derivative = SpanOf(method.start_derivative().coordinates());
  options.end_derivative = SpanOf(method.end_derivative().coordinates());
  options.scale_end_derivatives = method.scale_end_derivatives();
  options.closed = method.closed();
  options.cancel = cancel;
  absl::StatusOr<CurveInterpolation> result = InterpolateCurve(points, options);
  if (!result.ok()) return result.status();
  Answer(result->curve, result->parameters, result->max_residual, 0.0,
         response);
  return absl::OkStatus();
}

absl::Status InterpolateWithCubicSpline(
    const v1::InterpolateCurveRequest& request, const PointsView& points,
    const CancellationToken* cancel, v1::InterpolateCurveResponse& response) {
  const v1::CubicSplineInterpolation& method = request.cubic_spline();
  RETURN_IF_ERROR(CheckEnum(method.end_condition(),
                            v1::SplineEndCondition_IsValid, "end_condition"));
  absl::StatusOr<CurveInterpolation> result = InterpolateCubicSpline(
      points, SpanOf(method.parameters()), ToCore(method.end_condition()),
      SpanOf(method.start_derivative().coordinates()),
      SpanOf(method.end_derivative().coordinates()), cancel);
  if (!result.ok()) return result.status();
  Answer(result->curve, result->parameters, result->max_residual, 0.0,
         response);
  return absl::OkStatus();
}

absl::Status ApproximateWithLeastSquares(
    const v1::InterpolateCurveRequest& request, const PointsView& points,
    const CancellationToken* cancel, v1::InterpolateCurveResponse& response) {
  const v1::LeastSquaresApproximation& method = request.least_squares();
  RETURN_IF_ERROR(CheckEnum(method.parameterization(),
                            v1::Parameterization_IsValid, "parameterization"));
  absl::StatusOr<CurveApproximation> result = ApproximateCurve(
      points, static_cast<int>(method.degree()),
      static_cast<int>(method.control_point_count()),
      ToCore(method.parameterization()), SpanOf(method.parameters()), cancel);
  if (!result.ok()) return result.status();
  Answer(result->curve, result->parameters, result->max_residual,
         result->rms_residual, response);
  return absl::OkStatus();
}

// Paths of the core's errors: "points..." stays at the top of the request,
// everything else belongs to the chosen method.
absl::Status WithMethodPrefix(const absl::Status& status,
                              absl::string_view method) {
  const std::string path = FieldPathOf(status).value_or("");
  if (path.rfind("points", 0) == 0) return status;
  return PrefixFieldPath(status, method);
}

absl::Status Interpolate(const v1::InterpolateCurveRequest& request,
                         const PointsView& points, const ServiceLimits& limits,
                         const CancellationToken* cancel,
                         v1::InterpolateCurveResponse& response) {
  switch (request.method_case()) {
    case v1::InterpolateCurveRequest::kBspline:
      RETURN_IF_ERROR(CheckDegreeLimit(request.bspline().degree(), limits,
                                       "bspline.degree"));
      return WithMethodPrefix(
          InterpolateWithBSpline(request, points, cancel, response), "bspline");
    case v1::InterpolateCurveRequest::kCubicSpline:
      return WithMethodPrefix(
          InterpolateWithCubicSpline(request, points, cancel, response),
          "cubic_spline");
    case v1::InterpolateCurveRequest::kLeastSquares:
      RETURN_IF_ERROR(CheckDegreeLimit(request.least_squares().degree(), limits,
                                       "least_squares.degree"));
      return WithMethodPrefix(
          ApproximateWithLeastSquares(request, points, cancel, response),
          "least_squares");
    case v1::InterpolateCurveRequest::METHOD_NOT_SET:
      break;
  }
  return InvalidFieldError(
      "bspline", "set a method: bspline, cubic_spline or least_squares");
}

absl::StatusOr<UnaryWork> PlanInterpolate(
    const v1::InterpolateCurveRequest& request, const ServiceLimits& limits,
    v1::InterpolateCurveResponse& response) {
  RETURN_IF_ERROR(
      CheckDimensionLimit(request.points().dimension(), limits, "points"));
  const PointsView points = ViewOf(request.points());
  const uint64_t count = points.size();
  RETURN_IF_ERROR(CheckPointLimit(count, limits, "points"));
  if (request.has_least_squares() &&
      request.least_squares().control_point_count() > count) {
    return InvalidFieldError(
        "least_squares.control_point_count",
        absl::StrCat("must be at most the number of points ", count, ", got ",
                     request.least_squares().control_point_count()));
  }
  // The answer: control points (at most the points, their derivatives and
  // a closing wrap), knots and parameters; the work per point: the rows of
  // the collocation or normal equations and the band of their LU (3 (p + 1)
  // values), copies of the data and residuals (3 d) and bookkeeping.
  const uint64_t dimension = static_cast<uint64_t>(points.dimension);
  const uint64_t degree = std::min<uint64_t>(
      request.has_bspline()         ? request.bspline().degree()
      : request.has_least_squares() ? request.least_squares().degree()
                                    : 3,
      static_cast<uint64_t>(limits.max_degree));
  const uint64_t values = (count + 8) * (dimension + 3);
  const uint64_t work =
      8 * (count + 8) * (3 * (degree + 1) + 3 * dimension + 8);
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "points"));
  return UnaryWork{
      .plan = AnswerPlan(values, work, limits),
      .run = [points, &request, &limits,
              &response](const ExecutionContext& execution) -> absl::Status {
        return Interpolate(request, points, limits, execution.cancellation,
                           response);
      }};
}

}  // namespace

grpc::ServerUnaryReactor* CurveServiceImpl::ElevateDegree(
    grpc::CallbackServerContext* context,
    const v1::ElevateCurveDegreeRequest* request,
    v1::ElevateCurveDegreeResponse* response) {
  return frame_->Unary("CurveService.ElevateDegree", context, request, response,
                       [this, request, response] {
                         return PlanElevate(*request, frame_->limits(),
                                            *response);
                       });
}

grpc::ServerUnaryReactor* CurveServiceImpl::ReduceDegree(
    grpc::CallbackServerContext* context,
    const v1::ReduceCurveDegreeRequest* request,
    v1::ReduceCurveDegreeResponse* response) {
  return frame_->Unary("CurveService.ReduceDegree", context, request, response,
                       [this, request, response] {
                         return PlanReduce(*request, frame_->limits(),
                                           *response);
                       });
}

grpc::ServerUnaryReactor* CurveServiceImpl::Interpolate(
    grpc::CallbackServerContext* context,
    const v1::InterpolateCurveRequest* request,
    v1::InterpolateCurveResponse* response) {
  return frame_->Unary("CurveService.Interpolate", context, request, response,
                       [this, request, response] {
                         return PlanInterpolate(*request, frame_->limits(),
                                                *response);
                       });
}

}  // namespace freeform::server
