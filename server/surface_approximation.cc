// SurfaceService RPCs that approximate surfaces: RemoveKnots (knot removal
// and simplification within a certified tolerance), Fit (a grid of points
// to a tolerance) and FitScattered (scattered points, given control
// counts). Every answer and the scattered fit's working memory are bounded
// from the request before any work.
#include <algorithm>
#include <cstdint>
#include <utility>

#include "absl/strings/str_cat.h"
#include "approximation.h"
#include "convert.h"
#include "errors.h"
#include "freeform/core/fitting.h"
#include "freeform/core/knot_removal.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "geometry_out.h"
#include "plan.h"
#include "prepare.h"
#include "prepare_options.h"
#include "surface_service.h"
#include "visit.h"

namespace freeform::server {
namespace {

// Values of a B-spline surface's answer of count_u x count_v control points:
// the points (and weights) and both knot vectors.
uint64_t BSplineSurfaceValues(uint64_t count_u, uint64_t count_v,
                              uint64_t dimension, uint64_t degree_u,
                              uint64_t degree_v, bool rational) {
  return SaturatingProduct(SaturatingProduct(count_u, count_v),
                           dimension + (rational ? 1 : 0)) +
         count_u + count_v + degree_u + degree_v + 2;
}

absl::StatusOr<SurfaceKnotRemoval> Remove(
    const BSplineSurfaceView& view, KnotDirections directions, int times,
    const v1::RemoveSurfaceKnotsRequest& request,
    const CancellationToken* cancel) {
  if (!request.has_knot()) {
    return SimplifySurfaceKnots(view, directions, request.tolerance(), cancel);
  }
  return RemoveSurfaceKnot(view, directions == KnotDirections::kU,
                           request.knot(), times, request.tolerance(), cancel);
}

absl::StatusOr<UnaryWork> PlanBSplineRemove(
    const BSplineSurface& bspline, const v1::RemoveSurfaceKnotsRequest& request,
    const ServiceLimits& limits, v1::RemoveSurfaceKnotsResponse& response) {
  absl::StatusOr<KnotDirections> directions =
      RemovalDirections(request.direction(), request.has_knot());
  if (!directions.ok()) return directions.status();
  absl::StatusOr<int> times = RemovalTimes(request.has_knot(), request.times());
  if (!times.ok()) return times.status();
  const BSplineSurfaceView view = bspline.view();
  const uint64_t values =
      BSplineSurfaceValues(view.control_net.count_u, view.control_net.count_v,
                           static_cast<uint64_t>(view.control_net.dimension),
                           static_cast<uint64_t>(view.degree_u),
                           static_cast<uint64_t>(view.degree_v),
                           view.rational()) +
      3;
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "surface"));
  if (!request.has_knot()) {
    const ControlNetView& net = view.control_net;
    const uint64_t knots_u =
        net.count_u - static_cast<uint64_t>(view.degree_u) - 1;
    const uint64_t knots_v =
        net.count_v - static_cast<uint64_t>(view.degree_v) - 1;
    const uint64_t knots = *directions == KnotDirections::kU ? knots_u
                           : *directions == KnotDirections::kV
                               ? knots_v
                               : knots_u + knots_v;
    RETURN_IF_ERROR(CheckSimplifyWork(
        knots,
        SaturatingProduct(
            SaturatingProduct(net.count_u, net.count_v),
            static_cast<uint64_t>(net.dimension) + (view.rational() ? 1 : 0)),
        limits, "surface.bspline.control_net"));
  }
  // As for curves (curve_approximation.cc): simplifying is always heavy.
  CallPlan plan = AnswerPlan(values, 8 * 6 * values, limits);
  plan.heavy = plan.heavy || !request.has_knot();
  return UnaryWork{
      .plan = plan,
      .run = [view, directions = *directions, times = *times, &request,
              &response](const ExecutionContext& execution) -> absl::Status {
        absl::StatusOr<SurfaceKnotRemoval> removal =
            Remove(view, directions, times, request, execution.cancellation);
        if (!removal.ok()) {
          return PrefixFieldPathExcept(removal.status(), "surface.bspline",
                                       {"tolerance", "knot", "times"});
        }
        ToProto(removal->surface, *response.mutable_surface());
        response.set_removals_u(static_cast<uint32_t>(removal->removals_u));
        response.set_removals_v(static_cast<uint32_t>(removal->removals_v));
        response.set_error_bound(removal->error_bound);
        return absl::OkStatus();
      }};
}

absl::StatusOr<UnaryWork> PlanRemove(
    const v1::RemoveSurfaceKnotsRequest& request, const ServiceLimits& limits,
    v1::RemoveSurfaceKnotsResponse& response) {
  absl::StatusOr<Surface> surface = PrepareSurface(request.surface(), limits);
  if (!surface.ok()) return surface.status();
  return std::visit<absl::StatusOr<UnaryWork>>(
      Overloaded{
          [&](const BSplineSurface& bspline) {
            return PlanBSplineRemove(bspline, request, limits, response);
          },
          Refuse<BezierSurface, TriangularPatch>{
              "surface", "RemoveKnots takes a B-spline or NURBS surface"}},
      *surface);
}

// The degrees of a surface request, within the server's limit.
absl::Status CheckDegrees(uint32_t degree_u, uint32_t degree_v,
                          const ServiceLimits& limits) {
  for (auto [degree, field] :
       {std::pair{degree_u, "degree_u"}, std::pair{degree_v, "degree_v"}}) {
    RETURN_IF_ERROR(CheckDegreeLimit(degree, limits, field));
  }
  return absl::OkStatus();
}

absl::StatusOr<UnaryWork> PlanFit(const v1::FitSurfaceRequest& request,
                                  const ServiceLimits& limits,
                                  v1::FitSurfaceResponse& response) {
  absl::StatusOr<ControlNetView> points =
      PrepareNet(request.points(), limits, "points", false);
  if (!points.ok()) return points.status();
  RETURN_IF_ERROR(CheckDegrees(request.degree_u(), request.degree_v(), limits));
  RETURN_IF_ERROR(CheckEnum(request.parameterization(),
                            v1::Parameterization_IsValid, "parameterization"));
  const v1::ControlNet& net = request.points();
  absl::StatusOr<int> cap_u =
      FitControlCap(request.max_control_points_u(), net.count_u(), limits,
                    "max_control_points_u");
  if (!cap_u.ok()) return cap_u.status();
  absl::StatusOr<int> cap_v =
      FitControlCap(request.max_control_points_v(), net.count_v(), limits,
                    "max_control_points_v");
  if (!cap_v.ok()) return cap_v.status();
  // The answer: at most cap_u x cap_v control points and their knots, the
  // grid parameters. The work per round: the column fits' intermediate net
  // (cap_u x count_v), the residuals and copies of the grid, the bands.
  const uint64_t dimension = net.dimension();
  const uint64_t grid = SaturatingProduct(net.count_u(), net.count_v());
  const uint64_t values =
      BSplineSurfaceValues(static_cast<uint64_t>(*cap_u),
                           static_cast<uint64_t>(*cap_v), dimension,
                           request.degree_u(), request.degree_v(), false) +
      uint64_t{net.count_u()} + net.count_v() + 3;
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "points"));
  const uint64_t work = SaturatingProduct(
      8, SaturatingProduct(grid, 3 * dimension + 2) +
             SaturatingProduct(SaturatingProduct(static_cast<uint64_t>(*cap_u),
                                                 net.count_v()),
                               2 * dimension) +
             4 * values);
  return UnaryWork{
      .plan = AnswerPlan(values, work, limits),
      .run = [points = *points, cap_u = *cap_u, cap_v = *cap_v, &request,
              &response](const ExecutionContext& execution) -> absl::Status {
        GridFitOptions options;
        options.degree_u = static_cast<int>(request.degree_u());
        options.degree_v = static_cast<int>(request.degree_v());
        options.tolerance = request.tolerance();
        options.parameterization = ToCore(request.parameterization());
        options.max_control_points_u = cap_u;
        options.max_control_points_v = cap_v;
        options.cancel = execution.cancellation;
        absl::StatusOr<SurfaceFit> fit = FitSurfaceToGrid(points, options);
        if (!fit.ok()) return fit.status();
        ToProto(fit->surface, *response.mutable_surface());
        response.mutable_parameters_u()->Add(fit->parameters_u.begin(),
                                             fit->parameters_u.end());
        response.mutable_parameters_v()->Add(fit->parameters_v.begin(),
                                             fit->parameters_v.end());
        response.set_max_residual(fit->max_residual);
        response.set_rms_residual(fit->rms_residual);
        response.set_refinement_rounds(
            static_cast<uint32_t>(fit->refinement_rounds));
        return absl::OkStatus();
      }};
}

// The scattered fit's options from the request (control counts checked
// against the server's point limit, each and their product).
absl::StatusOr<ScatteredFitOptions> ScatteredOptions(
    const v1::FitScatteredSurfaceRequest& request,
    const ServiceLimits& limits) {
  RETURN_IF_ERROR(CheckDegrees(request.degree_u(), request.degree_v(), limits));
  // Each count and their product within the point limit (so each fits an
  // int).
  const absl::string_view larger =
      request.control_count_u() >= request.control_count_v()
          ? "control_count_u"
          : "control_count_v";
  for (uint64_t count : {uint64_t{std::max(request.control_count_u(),
                                           request.control_count_v())},
                         SaturatingProduct(request.control_count_u(),
                                           request.control_count_v())}) {
    RETURN_IF_ERROR(CheckPointLimit(count, limits, larger));
  }
  ScatteredFitOptions options;
  options.degree_u = static_cast<int>(request.degree_u());
  options.degree_v = static_cast<int>(request.degree_v());
  options.control_count_u = static_cast<int>(request.control_count_u());
  options.control_count_v = static_cast<int>(request.control_count_v());
  options.parameters = SpanOf(request.parameters());
  if (request.has_smoothing()) options.smoothing = request.smoothing();
  return options;
}

// RESOURCE_EXHAUSTED when the fit's working memory exceeds what calls may
// reserve together, naming "points" when the points alone need too much,
// else the larger control count.
absl::Status CheckScatteredMemory(const ScatteredFitWork& work,
                                  const ScatteredFitWork& net_work,
                                  const v1::FitScatteredSurfaceRequest& request,
                                  uint64_t capacity) {
  if (work.memory_bytes <= capacity) return absl::OkStatus();
  const bool net_fits = net_work.memory_bytes <= capacity;
  const absl::string_view field =
      net_fits ? "points"
      : request.control_count_u() >= request.control_count_v()
          ? "control_count_u"
          : "control_count_v";
  return ExhaustedFieldError(
      field, absl::StrCat("the fit needs ", work.memory_bytes,
                          " bytes of working memory, more than the server's "
                          "budget allows (",
                          capacity, ", --memory_budget_bytes)"));
}

absl::StatusOr<UnaryWork> PlanFitScattered(
    const v1::FitScatteredSurfaceRequest& request, const ServiceLimits& limits,
    v1::FitScatteredSurfaceResponse& response) {
  absl::StatusOr<PointsView> points =
      PreparePoints(request.points(), limits, "points");
  if (!points.ok()) return points.status();
  absl::StatusOr<ScatteredFitOptions> options =
      ScatteredOptions(request, limits);
  if (!options.ok()) return options.status();
  const uint64_t count = points->size();
  const ScatteredFitWork work =
      EstimateScatteredFit(count, points->dimension, *options);
  const ScatteredFitWork net_work =
      EstimateScatteredFit(0, points->dimension, *options);
  RETURN_IF_ERROR(CheckScatteredMemory(work, net_work, request,
                                       limits.memory_budget_bytes / 4 * 3));
  // The answer: the net and its knots, two parameters and a residual per
  // point.
  const uint64_t values =
      BSplineSurfaceValues(request.control_count_u(), request.control_count_v(),
                           static_cast<uint64_t>(points->dimension),
                           request.degree_u(), request.degree_v(), false) +
      SaturatingProduct(count, 3) + 2;
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "points"));
  return UnaryWork{
      .plan = {.memory_bytes =
                   AnswerPlan(values, work.memory_bytes, limits).memory_bytes,
               .heavy = true},
      .run = [points = *points, options = *options,
              &response](const ExecutionContext& execution) -> absl::Status {
        ScatteredFitOptions run_options = options;
        run_options.cancel = execution.cancellation;
        absl::StatusOr<ScatteredFit> fit =
            FitScatteredSurface(points, run_options);
        if (!fit.ok()) return fit.status();
        ToProto(fit->surface, *response.mutable_surface());
        response.mutable_parameters()->Add(fit->parameters.begin(),
                                           fit->parameters.end());
        response.mutable_residuals()->Add(fit->residuals.begin(),
                                          fit->residuals.end());
        response.set_max_residual(fit->max_residual);
        response.set_rms_residual(fit->rms_residual);
        return absl::OkStatus();
      }};
}

}  // namespace

grpc::ServerUnaryReactor* SurfaceServiceImpl::RemoveKnots(
    grpc::CallbackServerContext* context,
    const v1::RemoveSurfaceKnotsRequest* request,
    v1::RemoveSurfaceKnotsResponse* response) {
  return frame_->Unary("SurfaceService.RemoveKnots", context, request, response,
                       [this, request, response] {
                         return PlanRemove(*request, frame_->limits(),
                                           *response);
                       });
}

grpc::ServerUnaryReactor* SurfaceServiceImpl::Fit(
    grpc::CallbackServerContext* context, const v1::FitSurfaceRequest* request,
    v1::FitSurfaceResponse* response) {
  return frame_->Unary("SurfaceService.Fit", context, request, response,
                       [this, request, response] {
                         return PlanFit(*request, frame_->limits(), *response);
                       });
}

grpc::ServerUnaryReactor* SurfaceServiceImpl::FitScattered(
    grpc::CallbackServerContext* context,
    const v1::FitScatteredSurfaceRequest* request,
    v1::FitScatteredSurfaceResponse* response) {
  return frame_->Unary("SurfaceService.FitScattered", context, request,
                       response, [this, request, response] {
                         return PlanFitScattered(*request, frame_->limits(),
                                                 *response);
                       });
}

}  // namespace freeform::server
