// SurfaceService RPCs that build new surfaces: degree elevation and
// interpolation of a grid of points.
#include "absl/strings/str_cat.h"
#include "convert.h"
#include "freeform/core/elevation.h"
#include "freeform/core/interpolation.h"
#include "freeform/core/patches.h"
#include "freeform/core/status.h"
#include "geometry_out.h"
#include "prepared_surface.h"
#include "rpc.h"
#include "surface_service.h"

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
  if (absl::Status status =
          CheckElevation(request.by_u(), degree_u, limits, "by_u");
      !status.ok()) {
    return status;
  }
  return CheckElevation(request.by_v(), degree_v, limits, "by_v");
}

absl::Status ElevateBezierNet(const BezierSurfaceView& surface,
                              const v1::ElevateSurfaceDegreeRequest& request,
                              const ServiceLimits& limits,
                              v1::ElevateSurfaceDegreeResponse& response) {
  if (absl::Status status =
          CheckTensorElevation(request, surface.control_net.count_u - 1,
                               surface.control_net.count_v - 1, limits);
      !status.ok()) {
    return status;
  }
  absl::StatusOr<SurfaceData> elevated =
      ElevateBezierSurface(surface, static_cast<int>(request.by_u()),
                           static_cast<int>(request.by_v()));
  if (!elevated.ok()) return elevated.status();
  ToProto(*elevated, *response.mutable_surface());
  return absl::OkStatus();
}

absl::Status ElevateSurface(const v1::ElevateSurfaceDegreeRequest& request,
                            const ServiceLimits& limits,
                            v1::ElevateSurfaceDegreeResponse& response) {
  const v1::Surface& surface = request.surface();
  switch (surface.kind_case()) {
    case v1::Surface::kBezier: {
      absl::StatusOr<BezierSurfaceView> view =
          ValidatedBezierSurface(surface.bezier(), limits);
      if (!view.ok()) return PrefixFieldPath(view.status(), "surface.bezier");
      return ElevateBezierNet(*view, request, limits, response);
    }
    case v1::Surface::kBspline: {
      absl::StatusOr<BSplineSurfaceView> view =
          ValidatedBSplineSurface(surface.bspline(), limits);
      if (!view.ok()) return PrefixFieldPath(view.status(), "surface.bspline");
      if (absl::Status status = CheckTensorElevation(request, view->degree_u,
                                                     view->degree_v, limits);
          !status.ok()) {
        return status;
      }
      absl::StatusOr<SurfaceData> elevated =
          ElevateBSplineSurface(*view, static_cast<int>(request.by_u()),
                                static_cast<int>(request.by_v()));
      if (!elevated.ok()) return elevated.status();
      ToProto(*elevated, *response.mutable_surface());
      return absl::OkStatus();
    }
    case v1::Surface::kBicubicInterpolating: {
      absl::StatusOr<ControlNetView> points = ValidatedNet(
          surface.bicubic_interpolating().points(), limits, "points");
      if (!points.ok()) {
        return PrefixFieldPath(points.status(),
                               "surface.bicubic_interpolating");
      }
      if (points->count_u != 4 || points->count_v != 4) {
        return InvalidFieldError("surface.bicubic_interpolating.points",
                                 "the interpolating patch takes 4 x 4 points");
      }
      const std::vector<double> net =
          InterpolatingToBezierNet(points->dimension, points->coordinates);
      return ElevateBezierNet({.control_net = {.dimension = points->dimension,
                                               .count_u = 4,
                                               .count_v = 4,
                                               .coordinates = net},
                               .weights = {}},
                              request, limits, response);
    }
    case v1::Surface::kTriangularBezier: {
      absl::StatusOr<TriangularPatchView> patch =
          ValidatedTriangularPatch(surface.triangular_bezier(), limits);
      if (!patch.ok()) {
        return PrefixFieldPath(patch.status(), "surface.triangular_bezier");
      }
      if (request.by() < 1) {
        return InvalidFieldError("by", "must be at least 1");
      }
      if (absl::Status status =
              CheckElevation(request.by(), patch->degree, limits, "by");
          !status.ok()) {
        return status;
      }
      absl::StatusOr<TriangularPatchData> elevated =
          ElevateTriangularPatch(*patch, static_cast<int>(request.by()));
      if (!elevated.ok()) return elevated.status();
      ToProto(*elevated, *response.mutable_surface());
      return absl::OkStatus();
    }
    default:
      return InvalidFieldError(
          "surface",
          "degree elevation takes a Bezier, B-spline/NURBS, bicubic "
          "interpolating or triangular surface");
  }
}

absl::Status InterpolateGrid(const v1::InterpolateSurfaceRequest& request,
                             const ServiceLimits& limits,
                             v1::InterpolateSurfaceResponse& response) {
  absl::StatusOr<ControlNetView> points =
      ValidatedNet(request.points(), limits, "points");
  if (!points.ok()) return points.status();
  for (auto [degree, field] : {std::pair{request.degree_u(), "degree_u"},
                               std::pair{request.degree_v(), "degree_v"}}) {
    if (absl::Status status = CheckDegreeLimit(degree, limits, field);
        !status.ok()) {
      return status;
    }
  }
  const Parameterization parameterization =
      request.parameterization() == v1::PARAMETERIZATION_UNIFORM
          ? Parameterization::kUniform
      : request.parameterization() == v1::PARAMETERIZATION_CENTRIPETAL
          ? Parameterization::kCentripetal
      : request.parameterization() == v1::PARAMETERIZATION_UNIVERSAL
          ? Parameterization::kUniversal
          : Parameterization::kChordLength;
  absl::StatusOr<SurfaceInterpolation> result = InterpolateSurface(
      *points, static_cast<int>(request.degree_u()),
      static_cast<int>(request.degree_v()), parameterization,
      request.knot_rule() == v1::KNOT_RULE_UNIFORM ? KnotRule::kUniform
                                                   : KnotRule::kAveraging);
  if (!result.ok()) return result.status();
  ToProto(result->surface, *response.mutable_surface());
  response.mutable_parameters_u()->Add(result->parameters_u.begin(),
                                       result->parameters_u.end());
  response.mutable_parameters_v()->Add(result->parameters_v.begin(),
                                       result->parameters_v.end());
  return absl::OkStatus();
}

}  // namespace

grpc::Status SurfaceServiceImpl::ElevateDegree(
    grpc::ServerContext* context,
    const v1::ElevateSurfaceDegreeRequest* request,
    v1::ElevateSurfaceDegreeResponse* response) {
  return RunRpc("SurfaceService.ElevateDegree", context, *request, response,
                [&](const CancellationToken&) {
                  return ElevateSurface(*request, limits_, *response);
                });
}

grpc::Status SurfaceServiceImpl::Interpolate(
    grpc::ServerContext* context, const v1::InterpolateSurfaceRequest* request,
    v1::InterpolateSurfaceResponse* response) {
  return RunRpc("SurfaceService.Interpolate", context, *request, response,
                [&](const CancellationToken&) {
                  return InterpolateGrid(*request, limits_, *response);
                });
}

}  // namespace freeform::server
