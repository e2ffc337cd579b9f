// CurveService RPCs that approximate curves: RemoveKnots (knot removal and
// simplification within a certified tolerance) and Fit (least squares to a
// tolerance). Both answers are bounded by the input before any work:
// removal never grows the curve, a fit never has more control points than
// its cap or its data.
#include <cstdint>

#include "absl/strings/str_cat.h"
#include "approximation.h"
#include "convert.h"
#include "curve_service.h"
#include "errors.h"
#include "freeform/core/fitting.h"
#include "freeform/core/knot_removal.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "geometry_out.h"
#include "plan.h"
#include "prepare.h"
#include "prepare_options.h"
#include "visit.h"

namespace freeform::server {
namespace {

// Values of a B-spline curve's answer: control points (and weights), knots.
uint64_t BSplineCurveValues(uint64_t count, uint64_t dimension, int degree,
                            bool rational) {
  return SaturatingProduct(count, dimension + (rational ? 1 : 0)) + count +
         static_cast<uint64_t>(degree) + 1;
}

absl::StatusOr<UnaryWork> PlanBSplineRemove(
    const BSplineCurve& bspline, const v1::RemoveCurveKnotsRequest& request,
    const ServiceLimits& limits, v1::RemoveCurveKnotsResponse& response) {
  absl::StatusOr<int> times = RemovalTimes(request.has_knot(), request.times());
  if (!times.ok()) return times.status();
  const BSplineCurveView view = bspline.view();
  const uint64_t values =
      BSplineCurveValues(view.control_points.size(),
                         static_cast<uint64_t>(bspline.dimension()),
                         view.degree, view.rational()) +
      2;
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "curve"));
  if (!request.has_knot()) {
    const uint64_t count = view.control_points.size();
    RETURN_IF_ERROR(CheckSimplifyWork(
        count - static_cast<uint64_t>(view.degree) - 1,
        SaturatingProduct(count, static_cast<uint64_t>(bspline.dimension()) +
                                     (view.rational() ? 1 : 0)),
        limits, "curve.bspline.control_points"));
  }
  // The work: the curve being reduced, the original's homogeneous points
  // and the candidates' refined points, a few copies of the input each.
  // Simplifying evaluates every knot, again after each removal near it:
  // always heavy.
  CallPlan plan = AnswerPlan(values, 8 * 6 * values, limits);
  plan.heavy = plan.heavy || !request.has_knot();
  return UnaryWork{
      .plan = plan,
      .run = [view, times = *times, &request,
              &response](const ExecutionContext& execution) -> absl::Status {
        absl::StatusOr<CurveKnotRemoval> removal =
            request.has_knot()
                ? RemoveCurveKnot(view, request.knot(), times,
                                  request.tolerance(), execution.cancellation)
                : SimplifyCurveKnots(view, request.tolerance(),
                                     execution.cancellation);
        if (!removal.ok()) {
          return PrefixFieldPathExcept(removal.status(), "curve.bspline",
                                       {"tolerance", "knot", "times"});
        }
        ToProto(removal->curve, *response.mutable_curve());
        response.set_removals(static_cast<uint32_t>(removal->removals));
        response.set_error_bound(removal->error_bound);
        return absl::OkStatus();
      }};
}

absl::StatusOr<UnaryWork> PlanRemove(const v1::RemoveCurveKnotsRequest& request,
                                     const ServiceLimits& limits,
                                     v1::RemoveCurveKnotsResponse& response) {
  absl::StatusOr<Curve> curve = PrepareCurve(request.curve(), limits);
  if (!curve.ok()) return curve.status();
  return std::visit<absl::StatusOr<UnaryWork>>(
      Overloaded{[&](const BSplineCurve& bspline) {
                   return PlanBSplineRemove(bspline, request, limits, response);
                 },
                 Refuse<BezierCurve, LagrangeCurve, HermiteCurve>{
                     "curve", "RemoveKnots takes a B-spline or NURBS curve"}},
      *curve);
}

absl::StatusOr<UnaryWork> PlanFit(const v1::FitCurveRequest& request,
                                  const ServiceLimits& limits,
                                  v1::FitCurveResponse& response) {
  absl::StatusOr<PointsView> points =
      PreparePoints(request.points(), limits, "points");
  if (!points.ok()) return points.status();
  RETURN_IF_ERROR(CheckDegreeLimit(request.degree(), limits, "degree"));
  RETURN_IF_ERROR(CheckEnum(request.parameterization(),
                            v1::Parameterization_IsValid, "parameterization"));
  if (request.parameter_corrections() >
      static_cast<uint32_t>(kMaxParameterCorrections)) {
    return InvalidFieldError(
        "parameter_corrections",
        absl::StrCat("must be at most ", kMaxParameterCorrections, ", got ",
                     request.parameter_corrections()));
  }
  absl::StatusOr<int> cap =
      FitControlCap(request.max_control_points(), points->size(), limits,
                    "max_control_points");
  if (!cap.ok()) return cap.status();
  // The answer: at most min(cap, points) control points, their knots, one
  // parameter per point. The work per round: the parameters, basis rows
  // and residuals per point, the band and right-hand sides per control
  // point.
  const uint64_t count = points->size();
  const uint64_t dimension = static_cast<uint64_t>(points->dimension);
  const uint64_t degree = request.degree();
  const uint64_t controls = static_cast<uint64_t>(*cap);
  const uint64_t values =
      BSplineCurveValues(controls, dimension, static_cast<int>(degree), false) +
      count + 3;
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "points"));
  const uint64_t work = 8 * (count * (2 * dimension + degree + 6) +
                             controls * (3 * (degree + 1) + 3 * dimension + 4));
  return UnaryWork{
      .plan = AnswerPlan(values, work, limits),
      .run = [points = *points, cap = *cap, &request,
              &response](const ExecutionContext& execution) -> absl::Status {
        CurveFitOptions options;
        options.degree = static_cast<int>(request.degree());
        options.tolerance = request.tolerance();
        options.parameterization = ToCore(request.parameterization());
        options.parameters = SpanOf(request.parameters());
        options.max_control_points = cap;
        options.parameter_corrections =
            static_cast<int>(request.parameter_corrections());
        options.cancel = execution.cancellation;
        absl::StatusOr<CurveFit> fit = FitCurve(points, options);
        if (!fit.ok()) return fit.status();
        ToProto(fit->curve, *response.mutable_curve());
        response.mutable_parameters()->Add(fit->parameters.begin(),
                                           fit->parameters.end());
        response.set_max_residual(fit->max_residual);
        response.set_rms_residual(fit->rms_residual);
        response.set_refinement_rounds(
            static_cast<uint32_t>(fit->refinement_rounds));
        return absl::OkStatus();
      }};
}

}  // namespace

grpc::ServerUnaryReactor* CurveServiceImpl::RemoveKnots(
    grpc::CallbackServerContext* context,
    const v1::RemoveCurveKnotsRequest* request,
    v1::RemoveCurveKnotsResponse* response) {
  return frame_->Unary("CurveService.RemoveKnots", context, request, response,
                       [this, request, response] {
                         return PlanRemove(*request, frame_->limits(),
                                           *response);
                       });
}

grpc::ServerUnaryReactor* CurveServiceImpl::Fit(
    grpc::CallbackServerContext* context, const v1::FitCurveRequest* request,
    v1::FitCurveResponse* response) {
  return frame_->Unary("CurveService.Fit", context, request, response,
                       [this, request, response] {
                         return PlanFit(*request, frame_->limits(), *response);
                       });
}

}  // namespace freeform::server
