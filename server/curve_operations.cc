// CurveService RPCs that build new curves: degree elevation and reduction,
// interpolation and approximation.
#include "absl/strings/str_cat.h"
#include "convert.h"
#include "curve_service.h"
#include "freeform/core/elevation.h"
#include "freeform/core/interpolation.h"
#include "freeform/core/status.h"
#include "geometry_out.h"
#include "prepared_curve.h"
#include "rpc.h"

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

absl::Status ElevateCurve(const v1::ElevateCurveDegreeRequest& request,
                          const ServiceLimits& limits,
                          v1::ElevateCurveDegreeResponse& response) {
  switch (request.curve().kind_case()) {
    case v1::Curve::kBezier: {
      absl::StatusOr<BezierCurveView> curve =
          ValidatedBezier(request.curve().bezier(), limits);
      if (!curve.ok()) {
        return PrefixFieldPath(curve.status(), "curve.bezier");
      }
      if (absl::Status status = CheckBy(request.by(), curve->degree(), limits);
          !status.ok()) {
        return status;
      }
      absl::StatusOr<BezierCurveData> elevated =
          ElevateBezierCurve(*curve, static_cast<int>(request.by()));
      if (!elevated.ok()) return elevated.status();
      ToProto(*elevated, *response.mutable_curve());
      return absl::OkStatus();
    }
    case v1::Curve::kBspline: {
      absl::StatusOr<BSplineCurveView> curve =
          ValidatedBSpline(request.curve().bspline(), limits);
      if (!curve.ok()) {
        return PrefixFieldPath(curve.status(), "curve.bspline");
      }
      if (absl::Status status = CheckBy(request.by(), curve->degree, limits);
          !status.ok()) {
        return status;
      }
      absl::StatusOr<BSplineCurveData> elevated =
          ElevateBSplineCurve(*curve, static_cast<int>(request.by()));
      if (!elevated.ok()) return elevated.status();
      ToProto(*elevated, *response.mutable_curve());
      return absl::OkStatus();
    }
    default:
      return InvalidFieldError(
          "curve", "degree elevation takes a Bezier or B-spline/NURBS curve");
  }
}

absl::Status ReduceCurve(const v1::ReduceCurveDegreeRequest& request,
                         const ServiceLimits& limits,
                         v1::ReduceCurveDegreeResponse& response) {
  if (!request.curve().has_bezier()) {
    return InvalidFieldError(
        "curve", "degree reduction takes a polynomial Bezier curve");
  }
  absl::StatusOr<BezierCurveView> curve =
      ValidatedBezier(request.curve().bezier(), limits);
  if (!curve.ok()) return PrefixFieldPath(curve.status(), "curve.bezier");
  if (request.by() < 1 ||
      static_cast<int64_t>(request.by()) > curve->degree()) {
    return InvalidFieldError(
        "by", absl::StrCat("must be between 1 and the degree ", curve->degree(),
                           ", got ", request.by()));
  }
  absl::StatusOr<ReducedBezierCurve> reduced =
      ReduceBezierCurve(*curve, static_cast<int>(request.by()));
  if (!reduced.ok()) return PrefixFieldPath(reduced.status(), "curve.bezier");
  ToProto(reduced->curve, *response.mutable_curve());
  response.set_error_bound(reduced->error_bound);
  return absl::OkStatus();
}

Parameterization ToCore(v1::Parameterization parameterization) {
  switch (parameterization) {
    case v1::PARAMETERIZATION_UNIFORM:
      return Parameterization::kUniform;
    case v1::PARAMETERIZATION_CENTRIPETAL:
      return Parameterization::kCentripetal;
    case v1::PARAMETERIZATION_UNIVERSAL:
      return Parameterization::kUniversal;
    default:
      return Parameterization::kChordLength;
  }
}

KnotRule ToCore(v1::KnotRule rule) {
  return rule == v1::KNOT_RULE_UNIFORM ? KnotRule::kUniform
                                       : KnotRule::kAveraging;
}

SplineEnd ToCore(v1::SplineEndCondition end) {
  switch (end) {
    case v1::SPLINE_END_CONDITION_NATURAL:
      return SplineEnd::kNatural;
    case v1::SPLINE_END_CONDITION_CLAMPED:
      return SplineEnd::kClamped;
    case v1::SPLINE_END_CONDITION_PERIODIC:
      return SplineEnd::kPeriodic;
    default:
      return SplineEnd::kNotAKnot;
  }
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
                                    v1::InterpolateCurveResponse& response) {
  const v1::BSplineInterpolation& method = request.bspline();
  CurveInterpolationOptions options;
  options.degree = static_cast<int>(method.degree());
  options.parameterization = ToCore(method.parameterization());
  options.parameters = SpanOf(method.parameters());
  options.knot_rule = ToCore(method.knot_rule());
  options.start_derivative = SpanOf(method.start_derivative().coordinates());
  options.end_derivative = SpanOf(method.end_derivative().coordinates());
  options.closed = method.closed();
  absl::StatusOr<CurveInterpolation> result = InterpolateCurve(points, options);
  if (!result.ok()) return result.status();
  Answer(result->curve, result->parameters, result->max_residual, 0.0,
         response);
  return absl::OkStatus();
}

absl::Status InterpolateWithCubicSpline(
    const v1::InterpolateCurveRequest& request, const PointsView& points,
    v1::InterpolateCurveResponse& response) {
  const v1::CubicSplineInterpolation& method = request.cubic_spline();
  absl::StatusOr<CurveInterpolation> result = InterpolateCubicSpline(
      points, SpanOf(method.parameters()), ToCore(method.end_condition()),
      SpanOf(method.start_derivative().coordinates()),
      SpanOf(method.end_derivative().coordinates()));
  if (!result.ok()) return result.status();
  Answer(result->curve, result->parameters, result->max_residual, 0.0,
         response);
  return absl::OkStatus();
}

absl::Status ApproximateWithLeastSquares(
    const v1::InterpolateCurveRequest& request, const PointsView& points,
    v1::InterpolateCurveResponse& response) {
  const v1::LeastSquaresApproximation& method = request.least_squares();
  absl::StatusOr<CurveApproximation> result = ApproximateCurve(
      points, static_cast<int>(method.degree()),
      static_cast<int>(method.control_point_count()),
      ToCore(method.parameterization()), SpanOf(method.parameters()));
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
                         const ServiceLimits& limits,
                         v1::InterpolateCurveResponse& response) {
  if (absl::Status status =
          CheckDimensionLimit(request.points().dimension(), limits, "points");
      !status.ok()) {
    return status;
  }
  const PointsView points = ViewOf(request.points());
  if (absl::Status status = CheckPointLimit(points.size(), limits, "points");
      !status.ok()) {
    return status;
  }
  switch (request.method_case()) {
    case v1::InterpolateCurveRequest::kBspline:
      if (absl::Status status = CheckDegreeLimit(request.bspline().degree(),
                                                 limits, "bspline.degree");
          !status.ok()) {
        return status;
      }
      return WithMethodPrefix(InterpolateWithBSpline(request, points, response),
                              "bspline");
    case v1::InterpolateCurveRequest::kCubicSpline:
      return WithMethodPrefix(
          InterpolateWithCubicSpline(request, points, response),
          "cubic_spline");
    case v1::InterpolateCurveRequest::kLeastSquares:
      if (absl::Status status = CheckDegreeLimit(
              request.least_squares().degree(), limits, "least_squares.degree");
          !status.ok()) {
        return status;
      }
      return WithMethodPrefix(
          ApproximateWithLeastSquares(request, points, response),
          "least_squares");
    case v1::InterpolateCurveRequest::METHOD_NOT_SET:
      break;
  }
  return InvalidFieldError(
      "bspline", "set a method: bspline, cubic_spline or least_squares");
}

}  // namespace

grpc::Status CurveServiceImpl::ElevateDegree(
    grpc::ServerContext* context, const v1::ElevateCurveDegreeRequest* request,
    v1::ElevateCurveDegreeResponse* response) {
  return RunRpc("CurveService.ElevateDegree", context, *request, response,
                [&](const CancellationToken&) {
                  return ElevateCurve(*request, limits_, *response);
                });
}

grpc::Status CurveServiceImpl::ReduceDegree(
    grpc::ServerContext* context, const v1::ReduceCurveDegreeRequest* request,
    v1::ReduceCurveDegreeResponse* response) {
  return RunRpc("CurveService.ReduceDegree", context, *request, response,
                [&](const CancellationToken&) {
                  return ReduceCurve(*request, limits_, *response);
                });
}

grpc::Status CurveServiceImpl::Interpolate(
    grpc::ServerContext* context, const v1::InterpolateCurveRequest* request,
    v1::InterpolateCurveResponse* response) {
  return RunRpc("CurveService.Interpolate", context, *request, response,
                [&](const CancellationToken&) {
                  return freeform::server::Interpolate(*request, limits_,
                                                       *response);
                });
}

}  // namespace freeform::server
