// SurfaceService RPCs that build new surfaces: degree elevation and
// interpolation of a grid of points.
#include "absl/strings/str_cat.h"
#include "freeform/core/elevation.h"
#include "freeform/core/interpolation.h"
#include "freeform/core/patches.h"
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

// Elevation amounts `by` and the degree they raise, named `field`.
absl::Status CheckElevation(uint32_t by, int degree,
                            const ServiceLimits& limits,
                            absl::string_view field) {
  if (int64_t{degree} + by > limits.max_degree) {
    return InvalidFieldError(
        field, absl::StrCat("degree ", degree, " + ", by,
                            " would exceed the server's limit of ",
                            limits.max_degree, " (--max_degree)"));
  }
  return absl::OkStatus();
}

absl::Status CheckTensorElevation(
    const v1::ElevateSurfaceDegreeRequest& request, int degree_u, int degree_v,
    const ServiceLimits& limits) {
  if (request.by_u() == 0 && request.by_v() == 0) {
    return InvalidFieldError("by_u", "set by_u, by_v or both to at least 1");
  }
  RETURN_IF_ERROR(CheckElevation(request.by_u(), degree_u, limits, "by_u"));
  return CheckElevation(request.by_v(), degree_v, limits, "by_v");
}

// Runs `elevate` (called with the call's cancellation token) with the answer
// size `values` planned.
template <typename Elevate>
UnaryWork ElevationWork(uint64_t values, const ServiceLimits& limits,
                        v1::ElevateSurfaceDegreeResponse& response,
                        Elevate elevate) {
  return UnaryWork{
      .plan = AnswerPlan(values, 8 * values, limits),
      .run = [elevate = std::move(elevate),
              &response](const ExecutionContext& execution) -> absl::Status {
        auto elevated = elevate(execution.cancellation);
        if (!elevated.ok()) return elevated.status();
        ToProto(*elevated, *response.mutable_surface());
        return absl::OkStatus();
      }};
}

// by_u and by_v within what CheckTensorElevation allows.
int ByU(const v1::ElevateSurfaceDegreeRequest& request) {
  return static_cast<int>(std::min<uint32_t>(request.by_u(), 1 << 20));
}
int ByV(const v1::ElevateSurfaceDegreeRequest& request) {
  return static_cast<int>(std::min<uint32_t>(request.by_v(), 1 << 20));
}

absl::StatusOr<UnaryWork> PlanBezierElevate(
    const BezierSurface& bezier, const v1::ElevateSurfaceDegreeRequest& request,
    const ServiceLimits& limits, v1::ElevateSurfaceDegreeResponse& response) {
  const BezierSurfaceView view = bezier.view();
  RETURN_IF_ERROR(CheckTensorElevation(request, view.control_net.count_u - 1,
                                       view.control_net.count_v - 1, limits));
  const int by_u = ByU(request);
  const int by_v = ByV(request);
  const uint64_t values = uint64_t(view.control_net.count_u + by_u) *
                          (view.control_net.count_v + by_v) *
                          (view.control_net.dimension + 1);
  return ElevationWork(values, limits, response,
                       [bezier, by_u, by_v](const CancellationToken* cancel) {
                         return ElevateBezierSurface(bezier.view(), by_u, by_v,
                                                     cancel);
                       });
}

absl::StatusOr<UnaryWork> PlanBSplineElevate(
    const BSplineSurface& bspline,
    const v1::ElevateSurfaceDegreeRequest& request, const ServiceLimits& limits,
    v1::ElevateSurfaceDegreeResponse& response) {
  const BSplineSurfaceView view = bspline.view();
  RETURN_IF_ERROR(
      CheckTensorElevation(request, view.degree_u, view.degree_v, limits));
  const int by_u = ByU(request);
  const int by_v = ByV(request);
  const uint64_t count_u =
      view.control_net.count_u + uint64_t(view.control_net.count_u + 1) * by_u;
  const uint64_t count_v =
      view.control_net.count_v + uint64_t(view.control_net.count_v + 1) * by_v;
  RETURN_IF_ERROR(
      CheckPointLimit(SaturatingProduct(count_u, count_v), limits, "by_u"));
  const uint64_t values = SaturatingProduct(
      count_u * count_v, uint64_t(view.control_net.dimension) + 1);
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "by_u"));
  return ElevationWork(values, limits, response,
                       [view, by_u, by_v](const CancellationToken* cancel) {
                         return ElevateBSplineSurface(view, by_u, by_v, cancel);
                       });
}

absl::StatusOr<UnaryWork> PlanTriangularElevate(
    const TriangularPatch& patch,
    const v1::ElevateSurfaceDegreeRequest& request, const ServiceLimits& limits,
    v1::ElevateSurfaceDegreeResponse& response) {
  const TriangularPatchView view = patch.view();
  if (request.by() < 1) return InvalidFieldError("by", "must be at least 1");
  RETURN_IF_ERROR(CheckElevation(request.by(), view.degree, limits, "by"));
  const int by = static_cast<int>(request.by());
  const uint64_t values = TriangularPointCount(view.degree + by) *
                          (uint64_t(view.control_points.dimension) + 1);
  return ElevationWork(values, limits, response,
                       [view, by](const CancellationToken*) {
                         return ElevateTriangularPatch(view, by);
                       });
}

absl::StatusOr<UnaryWork> PlanElevate(
    const v1::ElevateSurfaceDegreeRequest& request, const ServiceLimits& limits,
    v1::ElevateSurfaceDegreeResponse& response) {
  absl::StatusOr<Surface> surface = PrepareSurface(request.surface(), limits);
  if (!surface.ok()) return surface.status();
  return std::visit(
      Overloaded{
          [&](const BezierSurface& bezier) {
            return PlanBezierElevate(bezier, request, limits, response);
          },
          [&](const BSplineSurface& bspline) {
            return PlanBSplineElevate(bspline, request, limits, response);
          },
          [&](const TriangularPatch& patch) {
            return PlanTriangularElevate(patch, request, limits, response);
          }},
      *surface);
}

absl::Status InterpolateGrid(const v1::InterpolateSurfaceRequest& request,
                             const ServiceLimits& limits,
                             const CancellationToken* cancel,
                             v1::InterpolateSurfaceResponse& response) {
  absl::StatusOr<ControlNetView> points =
      PrepareNet(request.points(), limits, "points", false);
  if (!points.ok()) return points.status();
  RETURN_IF_ERROR(ValidateControlNet(*points, "points"));
  for (auto [degree, field] : {std::pair{request.degree_u(), "degree_u"},
                               std::pair{request.degree_v(), "degree_v"}}) {
    RETURN_IF_ERROR(CheckDegreeLimit(degree, limits, field));
  }
  RETURN_IF_ERROR(CheckEnum(request.parameterization(),
                            v1::Parameterization_IsValid, "parameterization"));
  RETURN_IF_ERROR(
      CheckEnum(request.knot_rule(), v1::KnotRule_IsValid, "knot_rule"));
  absl::StatusOr<SurfaceInterpolation> result = InterpolateSurface(
      *points, static_cast<int>(request.degree_u()),
      static_cast<int>(request.degree_v()), ToCore(request.parameterization()),
      ToCore(request.knot_rule()), cancel);
  if (!result.ok()) return result.status();
  ToProto(result->surface, *response.mutable_surface());
  response.mutable_parameters_u()->Add(result->parameters_u.begin(),
                                       result->parameters_u.end());
  response.mutable_parameters_v()->Add(result->parameters_v.begin(),
                                       result->parameters_v.end());
  return absl::OkStatus();
}

}  // namespace

grpc::ServerUnaryReactor* SurfaceServiceImpl::ElevateDegree(
    grpc::CallbackServerContext* context,
    const v1::ElevateSurfaceDegreeRequest* request,
    v1::ElevateSurfaceDegreeResponse* response) {
  return frame_->Unary("SurfaceService.ElevateDegree", context, request,
                       response, [this, request, response] {
                         return PlanElevate(*request, frame_->limits(),
                                            *response);
                       });
}

grpc::ServerUnaryReactor* SurfaceServiceImpl::Interpolate(
    grpc::CallbackServerContext* context,
    const v1::InterpolateSurfaceRequest* request,
    v1::InterpolateSurfaceResponse* response) {
  return frame_->Unary(
      "SurfaceService.Interpolate", context, request, response,
      [this, request, response]() -> absl::StatusOr<UnaryWork> {
        const ServiceLimits& limits = frame_->limits();
        const uint64_t values = SaturatingProduct(
            uint64_t{request->points().count_u()} * request->points().count_v(),
            uint64_t{request->points().dimension()} + 1);
        RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "points"));
        return UnaryWork{
            .plan = AnswerPlan(values, 32 * values, limits),
            .run = [request, response, &limits](
                       const ExecutionContext& execution) -> absl::Status {
              return InterpolateGrid(*request, limits, execution.cancellation,
                                     *response);
            }};
      });
}

}  // namespace freeform::server
