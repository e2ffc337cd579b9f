// CurveService RPCs that refine or cut curves: Split, InsertKnots,
// Decompose, Subdivide (polygons) and Tessellate.
#include <cmath>
#include <memory>

#include "absl/strings/str_cat.h"
#include "convert.h"
#include "curve_service.h"
#include "freeform/core/bezier.h"
#include "freeform/core/hermite.h"
#include "freeform/core/status.h"
#include "freeform/core/subdivision.h"
#include "freeform/core/tessellation.h"
#include "geometry_out.h"
#include "prepared_curve.h"
#include "rpc.h"

namespace freeform::server {
namespace {

absl::Status Split(const v1::SplitCurveRequest& request,
                   const ServiceLimits& limits,
                   v1::SplitCurveResponse& response) {
  if (!request.curve().has_bezier()) {
    return InvalidFieldError(
        "curve",
        "Split takes a Bezier curve; use InsertKnots or Decompose "
        "for B-splines");
  }
  absl::StatusOr<BezierCurveView> curve =
      ValidatedBezier(request.curve().bezier(), limits);
  if (!curve.ok()) return PrefixFieldPath(curve.status(), "curve.bezier");
  if (request.parameters_size() == 0) {
    return InvalidFieldError("parameters", "needs at least one parameter");
  }
  if (static_cast<size_t>(request.parameters_size()) >
      limits.max_control_points) {
    return absl::ResourceExhaustedError(
        "parameters: more split parameters than --max_control_points");
  }
  absl::StatusOr<std::vector<BezierCurveData>> pieces =
      SplitBezierCurve(*curve, SpanOf(request.parameters()));
  if (!pieces.ok()) return pieces.status();
  for (const BezierCurveData& piece : *pieces) {
    ToProto(piece, *response.add_pieces());
  }
  return absl::OkStatus();
}

absl::Status Insert(const v1::InsertKnotsRequest& request,
                    const ServiceLimits& limits,
                    v1::InsertKnotsResponse& response) {
  if (!request.curve().has_bspline()) {
    return InvalidFieldError("curve",
                             "InsertKnots takes a B-spline or NURBS curve");
  }
  absl::StatusOr<BSplineCurveView> curve =
      ValidatedBSpline(request.curve().bspline(), limits);
  if (!curve.ok()) return PrefixFieldPath(curve.status(), "curve.bspline");
  if (absl::Status status = CheckPointLimit(
          curve->control_points.size() + request.knots_size(), limits, "knots");
      !status.ok()) {
    return status;
  }
  absl::StatusOr<BSplineCurveData> refined =
      InsertKnots(*curve, SpanOf(request.knots()));
  if (!refined.ok()) return refined.status();
  ToProto(*refined, *response.mutable_curve());
  return absl::OkStatus();
}

// The Bezier pieces of a Hermite curve, one per segment.
BezierDecomposition HermiteSegments(const HermiteCurveView& curve) {
  BezierDecomposition decomposition;
  decomposition.breakpoints = HermiteNodes(curve);
  for (size_t k = 0; k + 1 < decomposition.breakpoints.size(); ++k) {
    decomposition.segments.push_back({.dimension = curve.points.dimension,
                                      .coordinates = HermiteSegmentBezier(
                                          curve, decomposition.breakpoints, k),
                                      .weights = {}});
  }
  return decomposition;
}

absl::StatusOr<BezierDecomposition> Decompose(const v1::Curve& message,
                                              const ServiceLimits& limits) {
  switch (message.kind_case()) {
    case v1::Curve::kBezier: {
      absl::StatusOr<BezierCurveView> curve =
          ValidatedBezier(message.bezier(), limits);
      if (!curve.ok()) return PrefixFieldPath(curve.status(), "curve.bezier");
      BezierDecomposition single;
      single.segments.push_back(
          {.dimension = curve->control_points.dimension,
           .coordinates = {curve->control_points.coordinates.begin(),
                           curve->control_points.coordinates.end()},
           .weights = {curve->weights.begin(), curve->weights.end()}});
      single.breakpoints = {0.0, 1.0};
      return single;
    }
    case v1::Curve::kBspline: {
      absl::StatusOr<BSplineCurveView> curve =
          ValidatedBSpline(message.bspline(), limits);
      if (!curve.ok()) return PrefixFieldPath(curve.status(), "curve.bspline");
      return DecomposeBSplineCurve(*curve);
    }
    case v1::Curve::kPower: {
      const PointsView coefficients = ViewOf(message.power().coefficients());
      if (absl::Status status =
              CheckDimensionLimit(message.power().coefficients().dimension(),
                                  limits, "curve.power.coefficients");
          !status.ok()) {
        return status;
      }
      if (absl::Status status = PrefixFieldPath(
              ValidatePoints(coefficients, "coefficients"), "curve.power");
          !status.ok()) {
        return status;
      }
      BezierDecomposition single;
      single.segments.push_back({.dimension = coefficients.dimension,
                                 .coordinates = PowerToBezier(coefficients),
                                 .weights = {}});
      single.breakpoints = {0.0, 1.0};
      return single;
    }
    case v1::Curve::kHermite: {
      const HermiteCurveView curve{
          .points = ViewOf(message.hermite().points()),
          .tangents = ViewOf(message.hermite().tangents()),
          .nodes = SpanOf(message.hermite().nodes())};
      if (absl::Status status =
              CheckDimensionLimit(message.hermite().points().dimension(),
                                  limits, "curve.hermite.points");
          !status.ok()) {
        return status;
      }
      if (absl::Status status =
              PrefixFieldPath(ValidateHermiteCurve(curve), "curve.hermite");
          !status.ok()) {
        return status;
      }
      return HermiteSegments(curve);
    }
    default:
      return InvalidFieldError(
          "curve",
          "Decompose takes a Bezier, B-spline, Hermite or power-form "
          "curve");
  }
}

absl::Status Subdivide(const v1::SubdivideRequest& request,
                       const ServiceLimits& limits,
                       v1::SubdivideResponse& response) {
  if (absl::Status status =
          CheckDimensionLimit(request.polygon().dimension(), limits, "polygon");
      !status.ok()) {
    return status;
  }
  const PointsView polygon = ViewOf(request.polygon());
  if (absl::Status status = ValidatePoints(polygon, "polygon"); !status.ok()) {
    return status;
  }
  if (request.scheme() == v1::SUBDIVISION_SCHEME_UNSPECIFIED) {
    return InvalidFieldError("scheme", "choose CHAIKIN or UNIFORM_BSPLINE");
  }
  // Every level doubles the points: refuse answers over the output limit.
  const double points = static_cast<double>(polygon.size()) *
                        std::pow(2.0, static_cast<double>(request.levels()));
  if (points * polygon.dimension >
      static_cast<double>(limits.max_output_values)) {
    return absl::ResourceExhaustedError(absl::StrCat(
        "levels: ", request.levels(), " levels would make about ", points,
        " points, over the server's limit (--max_output_values)"));
  }
  const SubdivisionScheme scheme =
      request.scheme() == v1::SUBDIVISION_SCHEME_CHAIKIN
          ? SubdivisionScheme::kChaikin
          : SubdivisionScheme::kUniformBSpline;
  absl::StatusOr<std::vector<std::vector<double>>> levels = SubdividePolygon(
      polygon, request.closed(), scheme, static_cast<int>(request.degree()),
      static_cast<int>(request.levels()));
  if (!levels.ok()) return levels.status();
  const uint32_t dimension = request.polygon().dimension();
  for (size_t level = 0; level < levels->size(); ++level) {
    const bool last = level + 1 == levels->size();
    if (!last && !request.keep_levels()) continue;
    v1::Points* out = last ? response.mutable_polygon() : response.add_levels();
    out->set_dimension(dimension);
    out->mutable_coordinates()->Add((*levels)[level].begin(),
                                    (*levels)[level].end());
    if (last && request.keep_levels()) *response.add_levels() = *out;
  }
  return absl::OkStatus();
}

absl::Status Tessellate(const v1::TessellateCurveRequest& request,
                        const ServiceLimits& limits,
                        const CancellationToken& token,
                        v1::TessellateCurveResponse& response) {
  const size_t cap =
      request.max_points() > 0
          ? std::min<size_t>(request.max_points(), limits.max_parameters)
          : limits.max_parameters;
  absl::StatusOr<Polyline> polyline;
  switch (request.curve().kind_case()) {
    case v1::Curve::kBezier: {
      absl::StatusOr<BezierCurveView> curve =
          ValidatedBezier(request.curve().bezier(), limits);
      if (!curve.ok()) return PrefixFieldPath(curve.status(), "curve.bezier");
      polyline =
          TessellateBezierCurve(*curve, request.tolerance(), cap, &token);
      break;
    }
    case v1::Curve::kBspline: {
      absl::StatusOr<BSplineCurveView> curve =
          ValidatedBSpline(request.curve().bspline(), limits);
      if (!curve.ok()) return PrefixFieldPath(curve.status(), "curve.bspline");
      polyline =
          TessellateBSplineCurve(*curve, request.tolerance(), cap, &token);
      break;
    }
    default:
      return InvalidFieldError(
          "curve", "Tessellate takes a Bezier or B-spline/NURBS curve");
  }
  if (!polyline.ok()) return polyline.status();
  response.mutable_points()->set_dimension(
      static_cast<uint32_t>(polyline->dimension));
  response.mutable_points()->mutable_coordinates()->Add(
      polyline->points.begin(), polyline->points.end());
  response.mutable_parameters()->Add(polyline->parameters.begin(),
                                     polyline->parameters.end());
  return absl::OkStatus();
}

}  // namespace

grpc::Status CurveServiceImpl::Split(grpc::ServerContext* context,
                                     const v1::SplitCurveRequest* request,
                                     v1::SplitCurveResponse* response) {
  return RunRpc("CurveService.Split", context, *request, response,
                [&](const CancellationToken&) {
                  return freeform::server::Split(*request, limits_, *response);
                });
}

grpc::Status CurveServiceImpl::InsertKnots(
    grpc::ServerContext* context, const v1::InsertKnotsRequest* request,
    v1::InsertKnotsResponse* response) {
  return RunRpc("CurveService.InsertKnots", context, *request, response,
                [&](const CancellationToken&) {
                  return Insert(*request, limits_, *response);
                });
}

grpc::Status CurveServiceImpl::Decompose(
    grpc::ServerContext* context, const v1::DecomposeCurveRequest* request,
    v1::DecomposeCurveResponse* response) {
  return RunRpc(
      "CurveService.Decompose", context, *request, response,
      [&](const CancellationToken&) -> absl::Status {
        absl::StatusOr<BezierDecomposition> decomposition =
            freeform::server::Decompose(request->curve(), limits_);
        if (!decomposition.ok()) return decomposition.status();
        for (const BezierCurveData& segment : decomposition->segments) {
          ToProto(segment, *response->add_segments());
        }
        response->mutable_breakpoints()->Add(decomposition->breakpoints.begin(),
                                             decomposition->breakpoints.end());
        return absl::OkStatus();
      });
}

grpc::Status CurveServiceImpl::Subdivide(grpc::ServerContext* context,
                                         const v1::SubdivideRequest* request,
                                         v1::SubdivideResponse* response) {
  return RunRpc("CurveService.Subdivide", context, *request, response,
                [&](const CancellationToken&) {
                  return freeform::server::Subdivide(*request, limits_,
                                                     *response);
                });
}

grpc::Status CurveServiceImpl::Tessellate(
    grpc::ServerContext* context, const v1::TessellateCurveRequest* request,
    v1::TessellateCurveResponse* response) {
  return RunRpc("CurveService.Tessellate", context, *request, response,
                [&](const CancellationToken& token) {
                  return freeform::server::Tessellate(*request, limits_, token,
                                                      *response);
                });
}

}  // namespace freeform::server
