// SurfaceService RPCs that cut or refine surfaces: Split, InsertKnots and
// adaptive Tessellate (unary and streamed).
#include <algorithm>
#include <vector>

#include "absl/strings/str_cat.h"
#include "convert.h"
#include "freeform/core/mesh.h"
#include "freeform/core/patches.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/subdivision.h"
#include "geometry_out.h"
#include "plan.h"
#include "prepare.h"
#include "prepare_options.h"
#include "queries.h"
#include "surface_service.h"
#include "visit.h"

namespace freeform::server {
namespace {

absl::StatusOr<UnaryWork> PlanTriangularSplit(
    const TriangularPatch& patch, const v1::SplitSurfaceRequest& request,
    const ServiceLimits& limits, v1::SplitSurfaceResponse& response) {
  const TriangularPatchView view = patch.view();
  const uint64_t values =
      3 * view.control_points.coordinates.size() + 3 * view.weights.size();
  return UnaryWork{.plan = AnswerPlan(values, 8 * values, limits),
                   .run = [view, &request,
                           &response](const ExecutionContext&) -> absl::Status {
                     absl::StatusOr<std::vector<TriangularPatchData>> pieces =
                         SplitTriangularPatch(view, request.u(), request.v());
                     if (!pieces.ok()) return pieces.status();
                     for (const TriangularPatchData& piece : *pieces) {
                       ToProto(piece, *response.add_pieces());
                     }
                     return absl::OkStatus();
                   }};
}

absl::StatusOr<UnaryWork> PlanBezierSplit(
    const BezierSurface& bezier, const v1::SplitSurfaceRequest& request,
    const ServiceLimits& limits, v1::SplitSurfaceResponse& response) {
  if (!request.surface().has_bezier()) {
    // A bicubic interpolating or Hermite patch, held in Bezier form: its
    // halves are no longer patches of its own kind.
    return InvalidFieldError(
        "surface", "Split takes a tensor Bezier or a triangular patch");
  }
  absl::StatusOr<bool> in_u = DirectionIsU(request.direction());
  if (!in_u.ok()) return in_u.status();
  const BezierSurfaceView view = bezier.view();
  const uint64_t values =
      2 * (view.control_net.coordinates.size() + view.weights.size());
  return UnaryWork{.plan = AnswerPlan(values, 8 * values, limits),
                   .run = [bezier, in_u = *in_u, &request,
                           &response](const ExecutionContext&) -> absl::Status {
                     absl::StatusOr<std::vector<SurfaceData>> pieces =
                         SplitBezierSurface(bezier.view(), in_u,
                                            request.parameter());
                     if (!pieces.ok()) return pieces.status();
                     for (const SurfaceData& piece : *pieces) {
                       ToProto(piece, *response.add_pieces());
                     }
                     return absl::OkStatus();
                   }};
}

absl::StatusOr<UnaryWork> PlanSplit(const v1::SplitSurfaceRequest& request,
                                    const ServiceLimits& limits,
                                    v1::SplitSurfaceResponse& response) {
  absl::StatusOr<Surface> surface = PrepareSurface(request.surface(), limits);
  if (!surface.ok()) return surface.status();
  return std::visit<absl::StatusOr<UnaryWork>>(
      Overloaded{
          [&](const TriangularPatch& patch) {
            return PlanTriangularSplit(patch, request, limits, response);
          },
          [&](const BezierSurface& bezier) {
            return PlanBezierSplit(bezier, request, limits, response);
          },
          Refuse<BSplineSurface>{
              "surface", "Split takes a tensor Bezier or a triangular patch"}},
      *surface);
}

absl::StatusOr<UnaryWork> PlanBSplineInsert(
    const BSplineSurface& bspline, const v1::InsertSurfaceKnotsRequest& request,
    const ServiceLimits& limits, v1::InsertSurfaceKnotsResponse& response) {
  absl::StatusOr<bool> direction = DirectionIsU(request.direction());
  if (!direction.ok()) return direction.status();
  const BSplineSurfaceView view = bspline.view();
  const bool in_u = *direction;
  const uint64_t knots = static_cast<uint64_t>(request.knots_size());
  const uint64_t points =
      SaturatingProduct(view.control_net.count_u + (in_u ? knots : 0),
                        view.control_net.count_v + (in_u ? 0 : knots));
  RETURN_IF_ERROR(CheckPointLimit(points, limits, "knots"));
  const uint64_t values = SaturatingProduct(
      points, static_cast<uint64_t>(view.control_net.dimension) + 1);
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "knots"));
  return UnaryWork{
      .plan = AnswerPlan(values, 8 * values, limits),
      .run = [view, in_u, &request,
              &response](const ExecutionContext& execution) -> absl::Status {
        absl::StatusOr<SurfaceData> refined = InsertSurfaceKnots(
            view, in_u, SpanOf(request.knots()), execution.cancellation);
        if (!refined.ok()) return refined.status();
        ToProto(*refined, *response.mutable_surface());
        return absl::OkStatus();
      }};
}

absl::StatusOr<UnaryWork> PlanInsert(
    const v1::InsertSurfaceKnotsRequest& request, const ServiceLimits& limits,
    v1::InsertSurfaceKnotsResponse& response) {
  absl::StatusOr<Surface> surface = PrepareSurface(request.surface(), limits);
  if (!surface.ok()) return surface.status();
  return std::visit<absl::StatusOr<UnaryWork>>(
      Overloaded{
          [&](const BSplineSurface& bspline) {
            return PlanBSplineInsert(bspline, request, limits, response);
          },
          Refuse<BezierSurface, TriangularPatch>{
              "surface", "InsertKnots takes a B-spline or NURBS surface"}},
      *surface);
}

// A mesh request prepared and planned: the surfaces (which the plan reads,
// so the input is moved, never copied), the plan, and its memory (the
// service never sends the triangles' own surfaces and corner parameters,
// so the mesher skips them).
struct MeshInput {
  std::vector<Surface> surfaces;
  std::shared_ptr<const MeshPlan> plan;
  size_t cap = 0;
  MeshSize size;
  MeshMemory memory;

  // Bytes of the answer: per vertex its position, normal, (u, v) and
  // surface; per triangle three indices (at most four bytes each on the
  // wire, as vertex numbers stay below 2^28).
  uint64_t AnswerBytes() const {
    return size.vertices * uint64_t{8 * (3 + 3 + 2) + 4} +
           size.triangles * uint64_t{3 * 4};
  }
  // Bytes of a unary answer's call: the plan, and the mesher at its peak,
  // or its mesh copied into the answer, or the answer and its serialized
  // copy (the mesh is gone by then).
  uint64_t UnaryBytes() const {
    return memory.plan +
           std::max({memory.tessellation, memory.mesh + AnswerBytes(),
                     2 * AnswerBytes()});
  }
  // Bytes of a stream's call: the plan, and the mesher at its peak, or
  // its mesh and the chunk messages the stream holds (`chunk_bytes`).
  uint64_t StreamBytes(uint64_t chunk_bytes) const {
    return memory.plan +
           std::max(memory.tessellation, memory.mesh + chunk_bytes);
  }
};

// The Bezier pieces of all surfaces (SurfacePieceValues), saturating.
uint64_t PieceValues(const std::vector<Surface>& surfaces) {
  uint64_t values = 0;
  for (const Surface& surface : surfaces) {
    values = std::min(values, UINT64_MAX - SurfacePieceValues(surface)) +
             SurfacePieceValues(surface);
  }
  return values;
}

// Bytes of one vertex in an answer, with about two triangles of three
// indices: what the vertex cap allows for.
constexpr uint64_t kVertexBytes = 8 * (3 + 3 + 2) + 4 + 2 * 3 * 4;

// DimensionField returns the path of the field that sets the dimension of
// a surface of the message's kind.
std::string DimensionField(const v1::Surface& message) {
  switch (message.kind_case()) {
    case v1::Surface::kBspline:
      return "bspline.control_net.dimension";
    case v1::Surface::kBicubicInterpolating:
      return "bicubic_interpolating.points.dimension";
    case v1::Surface::kBicubicHermite:
      return "bicubic_hermite.positions.dimension";
    case v1::Surface::kTriangularBezier:
      return "triangular_bezier.control_points.dimension";
    case v1::Surface::kBezier:
    case v1::Surface::KIND_NOT_SET:  // refused by PrepareSurface before
      break;
  }
  return "bezier.control_net.dimension";
}

// MeshPlanning says where a mesh request is planned: on the pool when a
// normal-angle limit makes planning evaluate the surfaces.
Planning MeshPlanning(const v1::TessellateSurfaceRequest& request) {
  return request.has_max_normal_angle() ? Planning::kOnPool
                                        : Planning::kByRequestSize;
}

// PrepareMesh checks and plans a mesh request; `cancel` stops the planning
// (which evaluates the surfaces when there is a normal-angle limit).
absl::StatusOr<MeshInput> PrepareMesh(
    const v1::TessellateSurfaceRequest& request, const ServiceLimits& limits,
    uint64_t message_limit, const CancellationToken* cancel) {
  if (request.surfaces_size() == 0) {
    return InvalidFieldError("surfaces", "needs at least one surface");
  }
  MeshInput input;
  input.surfaces.reserve(static_cast<size_t>(request.surfaces_size()));
  for (int i = 0; i < request.surfaces_size(); ++i) {
    const std::string field = absl::StrCat("surfaces[", i, "]");
    absl::StatusOr<Surface> surface =
        PrepareSurface(request.surfaces(i), limits, field);
    if (!surface.ok()) return surface.status();
    if (DimensionOf(*surface) != 3) {
      return InvalidFieldError(
          absl::StrCat(field, ".", DimensionField(request.surfaces(i))),
          "surfaces must be 3D to be meshed");
    }
    input.surfaces.push_back(*std::move(surface));
  }
  absl::StatusOr<double> max_edge_length =
      GivenLimit(request.has_max_edge_length(), request.max_edge_length(),
                 "max_edge_length", "must be positive and finite");
  if (!max_edge_length.ok()) return max_edge_length.status();
  absl::StatusOr<double> max_normal_angle =
      GivenLimit(request.has_max_normal_angle(), request.max_normal_angle(),
                 "max_normal_angle", "must be above 0 and below pi (radians)");
  if (!max_normal_angle.ok()) return max_normal_angle.status();
  // The Bezier pieces the mesher cuts the surfaces into (with a normal-angle
  // limit the planner cuts them already).
  RETURN_IF_ERROR(
      PieceWorkBytes(PieceValues(input.surfaces), limits, "surfaces").status());
  const uint64_t requested = request.max_vertices() > 0 ? request.max_vertices()
                                                        : limits.max_parameters;
  input.cap = static_cast<size_t>(
      std::min({requested, uint64_t{limits.max_parameters},
                limits.max_output_values / 16, message_limit / kVertexBytes}));
  absl::StatusOr<std::shared_ptr<const MeshPlan>> plan =
      PlanMesh(input.surfaces,
               {.tolerance = request.tolerance(),
                .max_edge_length = *max_edge_length,
                .max_normal_angle = *max_normal_angle,
                .max_vertices = input.cap},
               cancel);
  if (!plan.ok()) return plan.status();
  input.plan = *std::move(plan);
  input.size = PlannedMeshSize(*input.plan);
  input.memory = PlannedMeshMemory(*input.plan, CornerAttributes::kSkip);
  return input;
}

// Fills `response` with vertices [first_vertex, last_vertex) and triangles
// [first_triangle, last_triangle) of `mesh`.
void FillMesh(const Mesh& mesh, bool normals, size_t first_vertex,
              size_t last_vertex, size_t first_triangle, size_t last_triangle,
              v1::TessellateSurfaceResponse& response) {
  response.mutable_vertices()->set_dimension(3);
  response.mutable_vertices()->mutable_coordinates()->Add(
      mesh.vertices.begin() + 3 * first_vertex,
      mesh.vertices.begin() + 3 * last_vertex);
  if (normals) {
    response.mutable_normals()->set_dimension(3);
    response.mutable_normals()->mutable_coordinates()->Add(
        mesh.normals.begin() + 3 * first_vertex,
        mesh.normals.begin() + 3 * last_vertex);
  }
  response.mutable_surface_index()->Add(mesh.patch.begin() + first_vertex,
                                        mesh.patch.begin() + last_vertex);
  response.mutable_uv()->Add(mesh.uv.begin() + 2 * first_vertex,
                             mesh.uv.begin() + 2 * last_vertex);
  response.mutable_triangles()->Add(mesh.triangles.begin() + 3 * first_triangle,
                                    mesh.triangles.begin() + 3 * last_triangle);
}

}  // namespace

grpc::ServerUnaryReactor* SurfaceServiceImpl::Split(
    grpc::CallbackServerContext* context,
    const v1::SplitSurfaceRequest* request,
    v1::SplitSurfaceResponse* response) {
  return frame_->Unary("SurfaceService.Split", context, request, response,
                       [this, request, response] {
                         return PlanSplit(*request, frame_->limits(),
                                          *response);
                       });
}

grpc::ServerUnaryReactor* SurfaceServiceImpl::InsertKnots(
    grpc::CallbackServerContext* context,
    const v1::InsertSurfaceKnotsRequest* request,
    v1::InsertSurfaceKnotsResponse* response) {
  return frame_->Unary("SurfaceService.InsertKnots", context, request, response,
                       [this, request, response] {
                         return PlanInsert(*request, frame_->limits(),
                                           *response);
                       });
}

grpc::ServerUnaryReactor* SurfaceServiceImpl::Tessellate(
    grpc::CallbackServerContext* context,
    const v1::TessellateSurfaceRequest* request,
    v1::TessellateSurfaceResponse* response) {
  return frame_->Unary(
      "SurfaceService.Tessellate", context, request, response,
      [this, context, request, response]() -> absl::StatusOr<UnaryWork> {
        const ServiceLimits& limits = frame_->limits();
        CancellationToken planning;
        WatchCall(*context, limits.max_call_time, planning);
        absl::StatusOr<MeshInput> input = PrepareMesh(
            *request, limits, static_cast<uint64_t>(limits.max_message_bytes),
            &planning);
        if (!input.ok()) return input.status();
        return UnaryWork{
            .plan = {.memory_bytes = input->UnaryBytes(), .heavy = true},
            .run = [input = *std::move(input), request, response](
                       const ExecutionContext& execution) -> absl::Status {
              absl::StatusOr<Mesh> mesh = TessellatePlanned(
                  *input.plan, execution.cancellation, CornerAttributes::kSkip);
              if (!mesh.ok()) return mesh.status();
              FillMesh(*mesh, request->normals(), 0, mesh->vertices.size() / 3,
                       0, mesh->triangles.size() / 3, *response);
              return absl::OkStatus();
            }};
      },
      MeshPlanning(*request));
}

grpc::ServerWriteReactor<v1::TessellateSurfaceResponse>*
SurfaceServiceImpl::TessellateStream(
    grpc::CallbackServerContext* context,
    const v1::TessellateSurfaceRequest* request) {
  using Work = StreamWork<v1::TessellateSurfaceResponse>;
  return frame_->Stream<v1::TessellateSurfaceResponse>(
      "SurfaceService.TessellateStream", context, request,
      [this, context, request]() -> absl::StatusOr<Work> {
        const ServiceLimits& limits = frame_->limits();
        CancellationToken planning;
        WatchCall(*context, limits.max_call_time, planning);
        absl::StatusOr<MeshInput> input =
            PrepareMesh(*request, limits, UINT64_MAX, &planning);
        if (!input.ok()) return input.status();
        // Vertices or triangles per message: the request's or the default,
        // within half a message.
        const size_t chunk = static_cast<size_t>(std::min<uint64_t>(
            request->chunk_size() > 0 ? request->chunk_size()
                                      : limits.default_stream_chunk,
            std::max<uint64_t>(
                1, static_cast<uint64_t>(limits.max_message_bytes) / 2 /
                       kVertexBytes)));
        const uint64_t chunk_bytes =
            std::min<uint64_t>(chunk, input->size.vertices) *
            (kVertexBytes + 3 * 4);
        // The mesh is made first; chunks of vertices, then of triangles,
        // are cut from it (indices always refer to vertices already sent).
        auto mesh = std::make_shared<Mesh>();
        auto shared = std::make_shared<MeshInput>(*std::move(input));
        return Work{
            .plan = {.memory_bytes = shared->StreamBytes(
                         2 * frame_->chunks_in_flight() * chunk_bytes),
                     .heavy = true},
            .chunk_count = 0,
            .prepare = [mesh, shared, chunk](const ExecutionContext& execution)
                -> absl::StatusOr<size_t> {
              absl::StatusOr<Mesh> made =
                  TessellatePlanned(*shared->plan, execution.cancellation,
                                    CornerAttributes::kSkip);
              if (!made.ok()) return made.status();
              *mesh = *std::move(made);
              const size_t vertices = mesh->vertices.size() / 3;
              const size_t triangles = mesh->triangles.size() / 3;
              return (vertices + chunk - 1) / chunk +
                     (triangles + chunk - 1) / chunk;
            },
            .fill =
                [mesh, chunk, request](size_t k,
                                       v1::TessellateSurfaceResponse& out,
                                       const ExecutionContext&) {
                  const size_t vertices = mesh->vertices.size() / 3;
                  const size_t triangles = mesh->triangles.size() / 3;
                  const size_t vertex_chunks = (vertices + chunk - 1) / chunk;
                  if (k < vertex_chunks) {
                    FillMesh(*mesh, request->normals(), k * chunk,
                             std::min(vertices, (k + 1) * chunk), 0, 0, out);
                  } else {
                    const size_t first = (k - vertex_chunks) * chunk;
                    FillMesh(*mesh, false, 0, 0, first,
                             std::min(triangles, first + chunk), out);
                  }
                  return absl::OkStatus();
                }};
      },
      MeshPlanning(*request));
}

}  // namespace freeform::server
