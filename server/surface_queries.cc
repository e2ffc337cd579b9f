// SurfaceService queries: ClosestPoint, IntersectCurve, Section, Curvature
// and BoundingBox.
#include <algorithm>
#include <memory>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "convert.h"
#include "freeform/core/bounding_box.h"
#include "freeform/core/closest_point.h"
#include "freeform/core/differential_geometry.h"
#include "freeform/core/intersection.h"
#include "freeform/core/section.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "geometry_out.h"
#include "plan.h"
#include "prepare.h"
#include "prepare_options.h"
#include "prepare_samples.h"
#include "queries.h"
#include "surface_service.h"

namespace freeform::server {
namespace {

// SectionError maps the core's work limit to the request's tolerance (a
// surface touching the plane, or crossing itself on it, along a stretch the
// quadtree halves down to its depth).
absl::Status SectionError(const absl::Status& status) {
  if (FieldPathOf(status) != "max_work") return status;
  return ExhaustedFieldError(
      "tolerance",
      absl::StrCat("the section would do more work than the server's limit "
                   "(--max_query_work): ",
                   FieldRuleOf(status)));
}

absl::StatusOr<UnaryWork> PlanClosestPoint(
    const v1::SurfaceClosestPointRequest& request, const ServiceLimits& limits,
    v1::ClosestPointResponse& response) {
  absl::StatusOr<Surface> surface = PrepareSurface(request.surface(), limits);
  if (!surface.ok()) return surface.status();
  absl::StatusOr<uint64_t> work =
      PieceWorkBytes(SurfacePieceValues(*surface), SurfacePieceCount(*surface),
                     kPieceRecordBytes, limits, "surface");
  if (!work.ok()) return work.status();
  return PlanClosestPoints(
      GeometryFieldOf(request), DimensionOf(*surface), 2, *work,
      request.queries(), request.options(),
      [surface = *std::move(surface)](const PointsView& queries,
                                      const ClosestPointOptions& options,
                                      const ExecutionContext& execution) {
        return SurfaceClosestPoints(surface, queries, options, execution);
      },
      limits, response);
}

absl::StatusOr<UnaryWork> PlanIntersectCurve(
    const v1::IntersectCurveSurfaceRequest& request,
    const ServiceLimits& limits, v1::IntersectCurveSurfaceResponse& response) {
  absl::StatusOr<Curve> curve = PrepareCurve(request.curve(), limits);
  if (!curve.ok()) return curve.status();
  absl::StatusOr<Surface> surface = PrepareSurface(request.surface(), limits);
  if (!surface.ok()) return surface.status();
  absl::StatusOr<uint64_t> work = PieceWorkBytes(
      DecomposedCurveValues(*curve), DecomposedCurvePieces(*curve),
      kPartRecordBytes, limits, "curve");
  if (!work.ok()) return work.status();
  absl::StatusOr<uint64_t> surface_work =
      PieceWorkBytes(SurfacePieceValues(*surface), SurfacePieceCount(*surface),
                     kPartRecordBytes, limits, "surface");
  if (!surface_work.ok()) return surface_work.status();
  const int dimension = DimensionOf(*curve);
  if (DimensionOf(*surface) != dimension) {
    return InvalidFieldError(
        "surface", absl::StrCat("must have the curve's dimension ", dimension,
                                ", not ", DimensionOf(*surface)));
  }
  // A point holds (t, u, v) and the curve's point, an overlap two
  // parameters.
  const uint64_t per_result = 3 + static_cast<uint64_t>(dimension);
  absl::StatusOr<IntersectionOptions> options =
      ToCore(request.options(), per_result, limits);
  if (!options.ok()) return options.status();
  const uint64_t values = options->max_results * per_result;
  // The search keeps its candidates besides the answer.
  const uint64_t candidates =
      IntersectionCandidateBytes(options->max_results, dimension);
  return UnaryWork{
      .plan = {.memory_bytes =
                   AnswerPlan(values,
                              8 * values + *work + *surface_work + candidates,
                              limits)
                       .memory_bytes,
               .heavy = true},
      .run = [curve = *std::move(curve), surface = *std::move(surface),
              options = *options,
              &response](const ExecutionContext& execution) -> absl::Status {
        absl::StatusOr<CurveSurfaceIntersections> found = IntersectCurveSurface(
            curve, surface, options, execution.cancellation);
        if (!found.ok()) return IntersectionError(found.status());
        response.set_dimension(static_cast<uint32_t>(found->dimension));
        response.mutable_curve_parameters()->Add(
            found->curve_parameters.begin(), found->curve_parameters.end());
        response.mutable_surface_parameters()->Add(
            found->surface_parameters.begin(), found->surface_parameters.end());
        response.mutable_points()->set_dimension(
            static_cast<uint32_t>(found->dimension));
        response.mutable_points()->mutable_coordinates()->Add(
            found->points.begin(), found->points.end());
        response.mutable_curve_intervals()->Add(found->curve_intervals.begin(),
                                                found->curve_intervals.end());
        return absl::OkStatus();
      }};
}

void WriteSections(const Sections& sections,
                   v1::SectionSurfaceResponse& response) {
  const size_t dimension = static_cast<size_t>(sections.dimension);
  for (size_t k = 0; k + 1 < sections.offsets.size(); ++k) {
    const size_t first = sections.offsets[k], last = sections.offsets[k + 1];
    v1::SectionPolyline& polyline = *response.add_polylines();
    polyline.mutable_points()->set_dimension(static_cast<uint32_t>(dimension));
    polyline.mutable_points()->mutable_coordinates()->Add(
        sections.points.begin() + first * dimension,
        sections.points.begin() + last * dimension);
    polyline.mutable_parameters()->Add(sections.parameters.begin() + 2 * first,
                                       sections.parameters.begin() + 2 * last);
    polyline.set_closed(sections.closed[k] != 0);
    if (!sections.curves.empty()) {
      ToProto(sections.curves[k], *polyline.mutable_curve());
    }
  }
  for (size_t k = 0; k + 1 < sections.region_offsets.size(); ++k) {
    response.add_regions()->mutable_parameters()->Add(
        sections.region_corners.begin() + 2 * sections.region_offsets[k],
        sections.region_corners.begin() + 2 * sections.region_offsets[k + 1]);
  }
}

absl::StatusOr<UnaryWork> PlanSection(const v1::SectionSurfaceRequest& request,
                                      const ServiceLimits& limits,
                                      v1::SectionSurfaceResponse& response) {
  absl::StatusOr<Surface> surface = PrepareSurface(request.surface(), limits);
  if (!surface.ok()) return surface.status();
  absl::StatusOr<double> tolerance =
      RequestTolerance(request, kDefaultSectionTolerance);
  if (!tolerance.ok()) return tolerance.status();
  absl::StatusOr<double> fit_tolerance =
      Tolerance(request.has_fit_tolerance(), request.fit_tolerance(), 0.0,
                "fit_tolerance");
  if (!fit_tolerance.ok()) return fit_tolerance.status();
  absl::StatusOr<uint64_t> work =
      PieceWorkBytes(SurfacePieceValues(*surface), SurfacePieceCount(*surface),
                     kPieceRecordBytes, limits, "surface");
  if (!work.ok()) return work.status();
  const int dimension = DimensionOf(*surface);
  // A vertex holds its point and (u, v), and with a fit at most one
  // control point and a few knots of its curve; a region's corner (u, v);
  // each polyline and region adds a few bytes.
  const uint64_t per_point =
      (*fit_tolerance > 0 ? 2 : 1) * (2 + static_cast<uint64_t>(dimension));
  const uint64_t requested = request.max_points() > 0
                                 ? uint64_t{request.max_points()}
                                 : kDefaultSectionPoints;
  RETURN_IF_ERROR(UnaryAnswerCheck(SaturatingProduct(requested, per_point),
                                   limits, "max_points"));
  const uint64_t values = requested * per_point;
  return UnaryWork{
      .plan =
          {.memory_bytes =
               AnswerPlan(2 * values, 8 * values + *work, limits).memory_bytes,
           .heavy = true},
      .run = [surface = *std::move(surface),
              point = SpanOf(request.plane_point()),
              normal = SpanOf(request.plane_normal()),
              options =
                  SectionOptions{.tolerance = *tolerance,
                                 .max_points = static_cast<size_t>(requested),
                                 .max_work = limits.max_query_work,
                                 .fit_tolerance = *fit_tolerance},
              &response](const ExecutionContext& execution) -> absl::Status {
        absl::StatusOr<Sections> sections = IntersectSurfacePlane(
            surface, point, normal, options, execution.cancellation);
        if (!sections.ok()) return SectionError(sections.status());
        WriteSections(*sections, response);
        return absl::OkStatus();
      }};
}

absl::StatusOr<UnaryWork> PlanCurvature(
    const v1::SurfaceCurvatureRequest& request, const ServiceLimits& limits,
    v1::SurfaceCurvatureResponse& response) {
  const SurfaceCurvatureSizes per_point = CurvatureSizes(1);
  const uint64_t values_per_point =
      uint64_t{per_point.normals} + per_point.gaussian + per_point.mean +
      per_point.principal_curvatures + per_point.principal_directions +
      per_point.statuses;
  ASSIGN_OR_RETURN(SurfacePlan plan,
                   PrepareSurfaceCurvature(request, values_per_point, limits));
  const uint64_t values = plan.size() * values_per_point;
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "parameters"));
  // The core evaluates a copy of the surface rescaled by powers of two (at
  // most its pieces' values) at a copy of the samples (two values each).
  const uint64_t copies =
      SaturatingProduct(SurfacePieceValues(*plan.surface) + 2 * plan.size(), 8);
  return UnaryWork{
      .plan = AnswerPlan(values, 8 * values + copies, limits),
      .run = [plan = std::move(plan),
              &response](const ExecutionContext& execution) -> absl::Status {
        const SurfaceCurvatureSizes sizes = CurvatureSizes(plan.size());
        std::vector<SurfacePointStatus> statuses(sizes.statuses);
        v1::Points& normals = *response.mutable_normals();
        normals.set_dimension(3);
        const SurfaceCurvatureOutput output = {
            .normals = UninitializedArray(*normals.mutable_coordinates(),
                                          sizes.normals),
            .gaussian = UninitializedArray(*response.mutable_gaussian(),
                                           sizes.gaussian),
            .mean = UninitializedArray(*response.mutable_mean(), sizes.mean),
            .principal_curvatures =
                UninitializedArray(*response.mutable_principal_curvatures(),
                                   sizes.principal_curvatures),
            .principal_directions =
                UninitializedArray(*response.mutable_principal_directions(),
                                   sizes.principal_directions),
            .statuses = absl::MakeSpan(statuses)};
        RETURN_IF_ERROR(EvaluateSurfaceCurvatures(*plan.surface, plan.All(),
                                                  output, execution));
        response.mutable_statuses()->Reserve(static_cast<int>(statuses.size()));
        for (const SurfacePointStatus status : statuses) {
          response.add_statuses(static_cast<v1::SurfacePointStatus>(status));
        }
        return absl::OkStatus();
      }};
}

absl::StatusOr<UnaryWork> PlanBoundingBox(
    const v1::SurfaceBoundingBoxRequest& request, const ServiceLimits& limits,
    v1::BoundingBoxResponse& response) {
  return PlanBoundingBoxOf(
      PrepareSurface(request.surface(), limits), request, "surface",
      [](const Surface& surface) { return SurfaceBoundingBoxBytes(surface); },
      [](const Surface& surface, double tolerance,
         const CancellationToken* cancel) {
        return SurfaceBoundingBox(surface, tolerance, cancel);
      },
      limits, response);
}

}  // namespace

grpc::ServerUnaryReactor* SurfaceServiceImpl::ClosestPoint(
    grpc::CallbackServerContext* context,
    const v1::SurfaceClosestPointRequest* request,
    v1::ClosestPointResponse* response) {
  return frame_->Unary("SurfaceService.ClosestPoint", context, request,
                       response, [this, request, response] {
                         return PlanClosestPoint(*request, frame_->limits(),
                                                 *response);
                       });
}

grpc::ServerUnaryReactor* SurfaceServiceImpl::IntersectCurve(
    grpc::CallbackServerContext* context,
    const v1::IntersectCurveSurfaceRequest* request,
    v1::IntersectCurveSurfaceResponse* response) {
  return frame_->Unary("SurfaceService.IntersectCurve", context, request,
                       response, [this, request, response] {
                         return PlanIntersectCurve(*request, frame_->limits(),
                                                   *response);
                       });
}

grpc::ServerUnaryReactor* SurfaceServiceImpl::Section(
    grpc::CallbackServerContext* context,
    const v1::SectionSurfaceRequest* request,
    v1::SectionSurfaceResponse* response) {
  return frame_->Unary("SurfaceService.Section", context, request, response,
                       [this, request, response] {
                         return PlanSection(*request, frame_->limits(),
                                            *response);
                       });
}

grpc::ServerUnaryReactor* SurfaceServiceImpl::Curvature(
    grpc::CallbackServerContext* context,
    const v1::SurfaceCurvatureRequest* request,
    v1::SurfaceCurvatureResponse* response) {
  return frame_->Unary("SurfaceService.Curvature", context, request, response,
                       [this, request, response] {
                         return PlanCurvature(*request, frame_->limits(),
                                              *response);
                       });
}

grpc::ServerUnaryReactor* SurfaceServiceImpl::BoundingBox(
    grpc::CallbackServerContext* context,
    const v1::SurfaceBoundingBoxRequest* request,
    v1::BoundingBoxResponse* response) {
  return frame_->Unary("SurfaceService.BoundingBox", context, request, response,
                       [this, request, response] {
                         return PlanBoundingBox(*request, frame_->limits(),
                                                *response);
                       });
}

}  // namespace freeform::server
