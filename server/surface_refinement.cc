// SurfaceService RPCs that cut or refine surfaces: Split, InsertKnots and
// adaptive Tessellate (unary and streamed).
#include <algorithm>
#include <vector>

#include "absl/strings/str_cat.h"
#include "convert.h"
#include "freeform/core/patches.h"
#include "freeform/core/status.h"
#include "freeform/core/subdivision.h"
#include "freeform/core/tessellation.h"
#include "geometry_out.h"
#include "prepared_surface.h"
#include "rpc.h"
#include "surface_service.h"

namespace freeform::server {
namespace {

absl::Status Split(const v1::SplitSurfaceRequest& request,
                   const ServiceLimits& limits,
                   v1::SplitSurfaceResponse& response) {
  const v1::Surface& surface = request.surface();
  if (surface.has_triangular_bezier()) {
    absl::StatusOr<TriangularPatchView> patch =
        ValidatedTriangularPatch(surface.triangular_bezier(), limits);
    if (!patch.ok()) {
      return PrefixFieldPath(patch.status(), "surface.triangular_bezier");
    }
    absl::StatusOr<std::vector<TriangularPatchData>> pieces =
        SplitTriangularPatch(*patch, request.u(), request.v());
    if (!pieces.ok()) return pieces.status();
    for (const TriangularPatchData& piece : *pieces) {
      ToProto(piece, *response.add_pieces());
    }
    return absl::OkStatus();
  }
  if (!surface.has_bezier()) {
    return InvalidFieldError(
        "surface", "Split takes a tensor Bezier or a triangular patch");
  }
  absl::StatusOr<BezierSurfaceView> view =
      ValidatedBezierSurface(surface.bezier(), limits);
  if (!view.ok()) return PrefixFieldPath(view.status(), "surface.bezier");
  if (request.direction() == v1::SURFACE_DIRECTION_UNSPECIFIED) {
    return InvalidFieldError("direction", "choose U or V");
  }
  absl::StatusOr<std::vector<SurfaceData>> pieces =
      SplitBezierSurface(*view, request.direction() == v1::SURFACE_DIRECTION_U,
                         request.parameter());
  if (!pieces.ok()) return pieces.status();
  for (const SurfaceData& piece : *pieces) {
    ToProto(piece, *response.add_pieces());
  }
  return absl::OkStatus();
}

absl::Status Insert(const v1::InsertSurfaceKnotsRequest& request,
                    const ServiceLimits& limits,
                    v1::InsertSurfaceKnotsResponse& response) {
  if (!request.surface().has_bspline()) {
    return InvalidFieldError("surface",
                             "InsertKnots takes a B-spline or NURBS surface");
  }
  absl::StatusOr<BSplineSurfaceView> view =
      ValidatedBSplineSurface(request.surface().bspline(), limits);
  if (!view.ok()) return PrefixFieldPath(view.status(), "surface.bspline");
  if (request.direction() == v1::SURFACE_DIRECTION_UNSPECIFIED) {
    return InvalidFieldError("direction", "choose U or V");
  }
  const bool in_u = request.direction() == v1::SURFACE_DIRECTION_U;
  const uint64_t points =
      uint64_t{static_cast<uint32_t>(view->control_net.count_u +
                                     (in_u ? request.knots_size() : 0))} *
      static_cast<uint32_t>(view->control_net.count_v +
                            (in_u ? 0 : request.knots_size()));
  if (absl::Status status = CheckPointLimit(points, limits, "knots");
      !status.ok()) {
    return status;
  }
  absl::StatusOr<SurfaceData> refined =
      InsertSurfaceKnots(*view, in_u, SpanOf(request.knots()));
  if (!refined.ok()) return refined.status();
  ToProto(*refined, *response.mutable_surface());
  return absl::OkStatus();
}

// Bezier nets of every surface to mesh (interpolating and Hermite patches
// become their Bezier nets); `storage` owns converted nets.
absl::StatusOr<std::vector<BezierSurfaceView>> PatchesOf(
    const v1::TessellateSurfaceRequest& request, const ServiceLimits& limits,
    std::vector<std::vector<double>>& storage) {
  if (request.surfaces_size() == 0) {
    return InvalidFieldError("surfaces", "needs at least one surface");
  }
  std::vector<BezierSurfaceView> patches;
  storage.reserve(static_cast<size_t>(request.surfaces_size()));
  for (int i = 0; i < request.surfaces_size(); ++i) {
    const v1::Surface& surface = request.surfaces(i);
    const std::string field = absl::StrCat("surfaces[", i, "]");
    if (surface.has_bezier()) {
      absl::StatusOr<BezierSurfaceView> view =
          ValidatedBezierSurface(surface.bezier(), limits);
      if (!view.ok()) {
        return PrefixFieldPath(view.status(), absl::StrCat(field, ".bezier"));
      }
      patches.push_back(*view);
    } else if (surface.has_bicubic_interpolating()) {
      absl::StatusOr<ControlNetView> points = ValidatedNet(
          surface.bicubic_interpolating().points(), limits, "points");
      if (!points.ok() || points->count_u != 4 || points->count_v != 4) {
        return InvalidFieldError(
            absl::StrCat(field, ".bicubic_interpolating.points"),
            "the interpolating patch takes 4 x 4 valid points");
      }
      storage.push_back(
          InterpolatingToBezierNet(points->dimension, points->coordinates));
      patches.push_back({.control_net = {.dimension = points->dimension,
                                         .count_u = 4,
                                         .count_v = 4,
                                         .coordinates = storage.back()},
                         .weights = {}});
    } else {
      return InvalidFieldError(
          field,
          "Tessellate takes tensor Bezier or bicubic interpolating "
          "patches");
    }
    if (patches.back().control_net.dimension != 3) {
      return InvalidFieldError(
          absl::StrCat(field, ".bezier.control_net.dimension"),
          "meshes are 3D");
    }
  }
  return patches;
}

absl::StatusOr<Mesh> MeshOf(const v1::TessellateSurfaceRequest& request,
                            const ServiceLimits& limits,
                            const CancellationToken& token) {
  std::vector<std::vector<double>> storage;
  absl::StatusOr<std::vector<BezierSurfaceView>> patches =
      PatchesOf(request, limits, storage);
  if (!patches.ok()) return patches.status();
  const size_t cap =
      std::min<size_t>(request.max_vertices() > 0 ? request.max_vertices()
                                                  : limits.max_parameters,
                       limits.max_output_values / 16);
  return TessellateBezierPatches(*patches, request.tolerance(), cap, &token);
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

grpc::Status SurfaceServiceImpl::Split(grpc::ServerContext* context,
                                       const v1::SplitSurfaceRequest* request,
                                       v1::SplitSurfaceResponse* response) {
  return RunRpc("SurfaceService.Split", context, *request, response,
                [&](const CancellationToken&) {
                  return freeform::server::Split(*request, limits_, *response);
                });
}

grpc::Status SurfaceServiceImpl::InsertKnots(
    grpc::ServerContext* context, const v1::InsertSurfaceKnotsRequest* request,
    v1::InsertSurfaceKnotsResponse* response) {
  return RunRpc("SurfaceService.InsertKnots", context, *request, response,
                [&](const CancellationToken&) {
                  return Insert(*request, limits_, *response);
                });
}

grpc::Status SurfaceServiceImpl::Tessellate(
    grpc::ServerContext* context, const v1::TessellateSurfaceRequest* request,
    v1::TessellateSurfaceResponse* response) {
  return RunRpc(
      "SurfaceService.Tessellate", context, *request, response,
      [&](const CancellationToken& token) -> absl::Status {
        absl::StatusOr<Mesh> mesh = MeshOf(*request, limits_, token);
        if (!mesh.ok()) return mesh.status();
        const size_t bytes =
            mesh->vertices.size() * 8 * 3 + mesh->triangles.size() * 4;
        if (bytes > static_cast<size_t>(limits_.max_message_bytes)) {
          return absl::ResourceExhaustedError(
              "the mesh is larger than one message; use TessellateStream");
        }
        FillMesh(*mesh, request->normals(), 0, mesh->vertices.size() / 3, 0,
                 mesh->triangles.size() / 3, *response);
        return absl::OkStatus();
      });
}

grpc::Status SurfaceServiceImpl::TessellateStream(
    grpc::ServerContext* context, const v1::TessellateSurfaceRequest* request,
    grpc::ServerWriter<v1::TessellateSurfaceResponse>* writer) {
  size_t streamed_bytes = 0;
  return RunRpc(
      "SurfaceService.TessellateStream", context, *request, nullptr,
      [&](const CancellationToken& token) -> absl::Status {
        absl::StatusOr<Mesh> mesh = MeshOf(*request, limits_, token);
        if (!mesh.ok()) return mesh.status();
        const size_t chunk = request->chunk_size() > 0
                                 ? request->chunk_size()
                                 : limits_.default_stream_chunk;
        const size_t vertices = mesh->vertices.size() / 3;
        const size_t triangles = mesh->triangles.size() / 3;
        // Vertices first, then triangles: indices always refer to vertices
        // already sent.
        if (absl::Status status = StreamChunks<v1::TessellateSurfaceResponse>(
                vertices, chunk, token, writer, streamed_bytes,
                [&](size_t first, size_t last,
                    v1::TessellateSurfaceResponse& response) {
                  FillMesh(*mesh, request->normals(), first, last, 0, 0,
                           response);
                  return absl::OkStatus();
                });
            !status.ok()) {
          return status;
        }
        return StreamChunks<v1::TessellateSurfaceResponse>(
            triangles, chunk, token, writer, streamed_bytes,
            [&](size_t first, size_t last,
                v1::TessellateSurfaceResponse& response) {
              FillMesh(*mesh, false, 0, 0, first, last, response);
              return absl::OkStatus();
            });
      },
      &streamed_bytes);
}

}  // namespace freeform::server
