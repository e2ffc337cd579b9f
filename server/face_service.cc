// FaceService: Classify, Evaluate and Area of trimmed faces.
#include "face_service.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "freeform/core/constrained_delaunay.h"
#include "freeform/core/face_mesh.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/trimmed_surface.h"
#include "plan.h"
#include "prepare_face.h"
#include "prepare_options.h"
#include "prepare_samples.h"
#include "queries.h"
#include "surface_evaluation.h"

namespace freeform::server {
namespace {

// A location travels as one packed enum value (a varint of one byte) and
// is computed into one byte: planned as one value per point, generously.
constexpr uint64_t kLocationValues = 1;

v1::FacePointLocation ToProto(PointLocation location) {
  switch (location) {
    case PointLocation::kOutside:
      return v1::FACE_POINT_OUTSIDE;
    case PointLocation::kInside:
      return v1::FACE_POINT_INSIDE;
    case PointLocation::kOnBoundary:
      return v1::FACE_POINT_ON_BOUNDARY;
  }
  return v1::FACE_POINT_LOCATION_UNSPECIFIED;
}

// The boundary tolerance of a request: its own, or the face's.
template <typename Request>
absl::StatusOr<double> BoundaryTolerance(const Request& request,
                                         const FaceRequest& face) {
  return Tolerance(request.has_boundary_tolerance(),
                   request.boundary_tolerance(), face.tolerance,
                   "boundary_tolerance");
}

// Classifies every sample of `samples` against the face and appends the
// locations to `out`.
absl::Status ClassifyInto(const TrimmedSurface& face,
                          const SurfacePlan& samples, double tolerance,
                          const ExecutionContext& execution,
                          google::protobuf::RepeatedField<int>& out) {
  std::vector<PointLocation> locations(samples.size());
  RETURN_IF_ERROR(ClassifySamples(face, samples.All(), tolerance,
                                  absl::MakeSpan(locations), execution));
  out.Reserve(static_cast<int>(locations.size()));
  for (PointLocation location : locations) out.Add(ToProto(location));
  return absl::OkStatus();
}

absl::StatusOr<UnaryWork> PlanClassify(
    const v1::ClassifyFacePointsRequest& request, const ServiceLimits& limits,
    v1::ClassifyFacePointsResponse& response) {
  ASSIGN_OR_RETURN(FaceRequest face, PrepareFace(request.face(), limits));
  ASSIGN_OR_RETURN(SurfacePlan samples,
                   PrepareSamplesOn(face.parts.surface, request.parameters(),
                                    kLocationValues, limits));
  ASSIGN_OR_RETURN(const double tolerance, BoundaryTolerance(request, face));
  ASSIGN_OR_RETURN(const TrimmedSurfaceWork work, FaceWork(face, nullptr));
  const uint64_t points = samples.size();
  ASSIGN_OR_RETURN(const uint64_t work_bytes,
                   CheckWorkBytes(work.bytes + points, limits, "face"));
  return UnaryWork{
      .plan = {.memory_bytes =
                   AnswerPlan(points * kLocationValues, work_bytes, limits)
                       .memory_bytes,
               .heavy = true},
      .run = [face = std::move(face), samples = std::move(samples), tolerance,
              &response](
                 const ExecutionContext& execution) mutable -> absl::Status {
        ASSIGN_OR_RETURN(const TrimmedSurface trimmed,
                         CreateFace(std::move(face), execution.cancellation));
        return ClassifyInto(trimmed, samples, tolerance, execution,
                            *response.mutable_locations());
      }};
}

absl::StatusOr<UnaryWork> PlanEvaluate(const v1::EvaluateFaceRequest& request,
                                       const ServiceLimits& limits,
                                       v1::EvaluateFaceResponse& response) {
  ASSIGN_OR_RETURN(FaceRequest face, PrepareFace(request.face(), limits));
  ASSIGN_OR_RETURN(
      SurfacePlan plan,
      PrepareEvaluationOf(face.parts.surface, request.parameters(),
                          request.derivative_order(), request.normals(),
                          kLocationValues, limits));
  ASSIGN_OR_RETURN(const double tolerance, BoundaryTolerance(request, face));
  ASSIGN_OR_RETURN(const TrimmedSurfaceWork work, FaceWork(face, nullptr));
  const uint64_t points = plan.size();
  const CallPlan evaluation = EvaluationMemory(plan, points, limits);
  ASSIGN_OR_RETURN(const uint64_t work_bytes,
                   CheckWorkBytes(work.bytes + points, limits, "face"));
  return UnaryWork{
      .plan = {.memory_bytes =
                   evaluation.memory_bytes +
                   AnswerPlan(points * kLocationValues, work_bytes, limits)
                       .memory_bytes,
               .heavy = true},
      .run = [face = std::move(face), plan = std::move(plan), tolerance,
              &response](
                 const ExecutionContext& execution) mutable -> absl::Status {
        ASSIGN_OR_RETURN(const TrimmedSurface trimmed,
                         CreateFace(std::move(face), execution.cancellation));
        v1::EvaluateSurfaceResponse& values = *response.mutable_values();
        RETURN_IF_ERROR(EvaluateChunk(plan, 0, plan.size(), execution, values));
        if (plan.normals) {
          google::protobuf::RepeatedField<double>& normals =
              *values.mutable_normals()->mutable_coordinates();
          OrientFaceNormals(
              trimmed, absl::MakeSpan(normals.mutable_data(), normals.size()));
        }
        return ClassifyInto(trimmed, plan, tolerance, execution,
                            *response.mutable_locations());
      }};
}

// The work of one surface point of the area's quadrature, in the units of
// --max_query_work (about a multiply-add): its position and first partials.
constexpr uint64_t kAreaWorkPerPoint = 256;

// AreaError maps the core's work limit to the request's tolerance.
absl::Status AreaError(const absl::Status& status) {
  if (FieldPathOf(status) != "max_work") return status;
  return ExhaustedFieldError(
      "tolerance",
      absl::StrCat("the area would do more work than the server's limit "
                   "(--max_query_work) to reach this tolerance: ",
                   FieldRuleOf(status)));
}

absl::StatusOr<UnaryWork> PlanArea(const v1::FaceAreaRequest& request,
                                   const ServiceLimits& limits,
                                   v1::FaceAreaResponse& response) {
  ASSIGN_OR_RETURN(FaceRequest face, PrepareFace(request.face(), limits));
  ASSIGN_OR_RETURN(const double tolerance,
                   RequestTolerance(request, kDefaultFaceAreaTolerance));
  ASSIGN_OR_RETURN(const TrimmedSurfaceWork work, FaceWork(face, nullptr));
  ASSIGN_OR_RETURN(
      const uint64_t work_bytes,
      CheckWorkBytes(
          work.bytes + FaceAreaWorkBytes(face.parts.surface, work.pieces),
          limits, "face"));
  return UnaryWork{
      .plan = {.memory_bytes = AnswerPlan(3, work_bytes, limits).memory_bytes,
               .heavy = true},
      .run = [face = std::move(face), tolerance,
              max_points = limits.max_query_work / kAreaWorkPerPoint,
              &response](
                 const ExecutionContext& execution) mutable -> absl::Status {
        ASSIGN_OR_RETURN(const TrimmedSurface trimmed,
                         CreateFace(std::move(face), execution.cancellation));
        absl::StatusOr<FaceAreaResult> area =
            FaceArea(trimmed, tolerance, execution.cancellation, max_points);
        if (!area.ok()) return AreaError(area.status());
        response.set_area(area->area);
        response.set_error_bound(area->error_bound);
        response.set_converged(area->error_bound <= tolerance);
        return absl::OkStatus();
      }};
}

// The vertices of a face's mesh when a request sets no cap.
constexpr uint64_t kDefaultFaceMeshVertices = uint64_t{1} << 16;
// An answer's doubles per vertex: position, normal and (u, v), and its
// triangles' indices (about two triangles per vertex, three 4-byte indices
// each: 3 doubles).
constexpr uint64_t kFaceMeshValuesPerVertex = 3 + 3 + 2 + 3;
// The mesher's own bytes per vertex besides the triangulation: the
// boundary and grid points, the mesh's arrays while it is written, and the
// Steiner candidates of a round (two triangles per vertex, three candidate
// points each).
constexpr uint64_t kFaceMeshWorkBytesPerVertex = 16 + 88 + 2 * 3 * 16 + 16;

void WritePoints(int dimension, const std::vector<double>& values,
                 v1::Points& out) {
  out.set_dimension(static_cast<uint32_t>(dimension));
  out.mutable_coordinates()->Add(values.begin(), values.end());
}

absl::StatusOr<UnaryWork> PlanTessellate(
    const v1::TessellateFaceRequest& request, const ServiceLimits& limits,
    v1::TessellateFaceResponse& response) {
  ASSIGN_OR_RETURN(FaceRequest face, PrepareFace(request.face(), limits));
  ASSIGN_OR_RETURN(const double tolerance,
                   GivenTolerance(request.tolerance(), "tolerance"));
  const uint64_t requested = request.max_vertices() > 0
                                 ? uint64_t{request.max_vertices()}
                                 : kDefaultFaceMeshVertices;
  const uint64_t cap =
      std::min(requested, limits.max_output_values / kFaceMeshValuesPerVertex);
  RETURN_IF_ERROR(
      UnaryAnswerCheck(cap * kFaceMeshValuesPerVertex, limits, "max_vertices"));
  ASSIGN_OR_RETURN(const TrimmedSurfaceWork work, FaceWork(face, nullptr));
  const uint64_t mesh_bytes = ConstrainedTriangulationMemoryBound(cap, cap) +
                              cap * kFaceMeshWorkBytesPerVertex;
  ASSIGN_OR_RETURN(
      const uint64_t work_bytes,
      CheckWorkBytes(work.bytes + mesh_bytes, limits, "max_vertices"));
  return UnaryWork{
      .plan = {.memory_bytes = AnswerPlan(cap * kFaceMeshValuesPerVertex,
                                          work_bytes, limits)
                                   .memory_bytes,
               .heavy = true},
      .run = [face = std::move(face), tolerance, cap, &response](
                 const ExecutionContext& execution) mutable -> absl::Status {
        ASSIGN_OR_RETURN(const TrimmedSurface trimmed,
                         CreateFace(std::move(face), execution.cancellation));
        ASSIGN_OR_RETURN(
            const FaceMesh mesh,
            TessellateFace(trimmed,
                           {.tolerance = tolerance,
                            .max_vertices = static_cast<size_t>(cap)},
                           execution.cancellation));
        WritePoints(3, mesh.vertices, *response.mutable_vertices());
        WritePoints(3, mesh.normals, *response.mutable_normals());
        WritePoints(2, mesh.uv, *response.mutable_uv());
        response.mutable_triangles()->Add(mesh.triangles.begin(),
                                          mesh.triangles.end());
        response.set_min_angle_degrees(mesh.min_angle_degrees);
        response.set_deviation_bound(mesh.deviation_bound);
        return absl::OkStatus();
      }};
}

}  // namespace

grpc::ServerUnaryReactor* FaceServiceImpl::Tessellate(
    grpc::CallbackServerContext* context,
    const v1::TessellateFaceRequest* request,
    v1::TessellateFaceResponse* response) {
  return frame_->Unary("FaceService.Tessellate", context, request, response,
                       [this, request, response] {
                         return PlanTessellate(*request, frame_->limits(),
                                               *response);
                       });
}

grpc::ServerUnaryReactor* FaceServiceImpl::Classify(
    grpc::CallbackServerContext* context,
    const v1::ClassifyFacePointsRequest* request,
    v1::ClassifyFacePointsResponse* response) {
  return frame_->Unary("FaceService.Classify", context, request, response,
                       [this, request, response] {
                         return PlanClassify(*request, frame_->limits(),
                                             *response);
                       });
}

grpc::ServerUnaryReactor* FaceServiceImpl::Evaluate(
    grpc::CallbackServerContext* context,
    const v1::EvaluateFaceRequest* request,
    v1::EvaluateFaceResponse* response) {
  return frame_->Unary("FaceService.Evaluate", context, request, response,
                       [this, request, response] {
                         return PlanEvaluate(*request, frame_->limits(),
                                             *response);
                       });
}

grpc::ServerUnaryReactor* FaceServiceImpl::Area(
    grpc::CallbackServerContext* context, const v1::FaceAreaRequest* request,
    v1::FaceAreaResponse* response) {
  return frame_->Unary("FaceService.Area", context, request, response,
                       [this, request, response] {
                         return PlanArea(*request, frame_->limits(), *response);
                       });
}

}  // namespace freeform::server
