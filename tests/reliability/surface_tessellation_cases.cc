// SurfaceService.Tessellate and TessellateStream: every vertex lies on its
// patch at its (u, v), normals are the unit S_u x S_v, triangles are
// counter-clockwise about it and within the tolerance of the surface
// (linear interpolation over each parameter triangle, the mesher's bound in
// freeform/core/mesh.h), and the mesh is one welded disk: each edge
// shared by at most two triangles in opposite directions and Euler
// characteristic V - E + F = 1, also for two patches that share an edge.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

#include "absl/strings/str_cat.h"
#include "cases.h"

namespace freeform::reliability {
namespace {

constexpr size_t kGeometryChecks = 500;

// Partial (order_u, order_v) of one patch at (u, v).
using PatchAt = std::function<Values(double u, double v, int ou, int ov)>;

// A mesh as the client assembles it from one answer or a stream.
struct MeshData {
  Values vertices;
  Values normals;
  Values uv;
  std::vector<uint32_t> triangles;
  std::vector<uint32_t> surface_index;

  void Append(const v1::TessellateSurfaceResponse& message) {
    const Values v = Flat(message.vertices());
    vertices.insert(vertices.end(), v.begin(), v.end());
    const Values n = Flat(message.normals());
    normals.insert(normals.end(), n.begin(), n.end());
    uv.insert(uv.end(), message.uv().begin(), message.uv().end());
    triangles.insert(triangles.end(), message.triangles().begin(),
                     message.triangles().end());
    surface_index.insert(surface_index.end(), message.surface_index().begin(),
                         message.surface_index().end());
  }
};

// Patches to mesh together and their references.
struct PatchSet {
  std::vector<v1::Surface> surfaces;
  std::vector<PatchAt> at;
};

PatchSet RandomPatchSet(Rng& rng) {
  PatchSet set;
  const int kind = UniformInt(rng, 0, 3);
  if (kind == 0 || kind == 1) {
    const CubicPatchShape shape = RandomCubicPatch(rng, kind == 1);
    set.surfaces.push_back(shape.ToSurface());
    set.at.push_back([shape](double u, double v, int ou, int ov) {
      return shape.At(u, v, ou, ov);
    });
    return set;
  }
  TensorShape a = RandomBezierPatch(rng, UniformInt(rng, 1, 4),
                                    UniformInt(rng, 1, 4), false);
  set.surfaces.push_back(a.ToSurface());
  set.at.push_back(
      [a](double u, double v, int ou, int ov) { return a.At(u, v, ou, ov); });
  if (kind == 2) return set;
  // A second patch to the right of the first, sharing its edge u = 1 as its
  // own edge u = 0 (the same control points, so the same boundary curve).
  TensorShape b =
      RandomBezierPatch(rng, UniformInt(rng, 1, 4), a.degree_v, false);
  for (size_t r = 0; r < b.net.size(); r += 3) b.net[r] += 1;
  std::copy(a.net.end() - 3 * a.count_v, a.net.end(), b.net.begin());
  set.surfaces.push_back(b.ToSurface());
  set.at.push_back(
      [b](double u, double v, int ou, int ov) { return b.At(u, v, ou, ov); });
  return set;
}

Values UnitNormal(const PatchAt& at, double u, double v) {
  Values n = Cross(at(u, v, 1, 0), at(u, v, 0, 1));
  const double length = Norm(n);
  if (length < 1e-9) return {};
  for (double& x : n) x /= length;
  return n;
}

void CheckMesh(const MeshData& mesh, const PatchSet& set, double tolerance,
               bool normals, Checker& check) {
  const size_t count = mesh.vertices.size() / 3;
  if (!check.True(count > 0 && mesh.vertices.size() == 3 * count &&
                      mesh.uv.size() == 2 * count &&
                      mesh.surface_index.size() == count &&
                      mesh.normals.size() == (normals ? 3 * count : 0) &&
                      mesh.triangles.size() % 3 == 0 && !mesh.triangles.empty(),
                  "per-vertex arrays of one length, whole triangles")) {
    return;
  }
  const auto vertex = [&](size_t r) {
    return Coordinates(mesh.vertices).subspan(3 * r, 3);
  };
  // The geometry of about kGeometryChecks vertices and triangles per mesh
  // (the client shares the cores with the server); the topology of all.
  const size_t vertex_stride = std::max<size_t>(1, count / kGeometryChecks);
  const size_t triangle_stride =
      std::max<size_t>(1, mesh.triangles.size() / 3 / kGeometryChecks);
  for (size_t r = 0; r < count; r += vertex_stride) {
    const uint32_t patch = mesh.surface_index[r];
    const double u = mesh.uv[2 * r], v = mesh.uv[2 * r + 1];
    if (!check.True(
            patch < set.at.size() && u >= 0 && u <= 1 && v >= 0 && v <= 1,
            "vertex patch and (u, v) in range") ||
        !check.NearPoint(vertex(r), set.at[patch](u, v, 0, 0), kTight,
                         "vertex on its patch", u)) {
      return;
    }
    if (!normals) continue;
    const Coordinates n = Coordinates(mesh.normals).subspan(3 * r, 3);
    const Values expected = UnitNormal(set.at[patch], u, v);
    check.Near(Norm(n), 1, 1e-9, "unit normal");
    if (!expected.empty()) {
      check.True(Dot(n, expected) > 1 - 1e-6, "normal along S_u x S_v");
    }
  }
  std::map<std::pair<uint32_t, uint32_t>, int> edges;  // +1 forward, -1 back
  std::vector<bool> used(count, false);
  for (size_t t = 0; t < mesh.triangles.size(); t += 3) {
    const uint32_t c[3] = {mesh.triangles[t], mesh.triangles[t + 1],
                           mesh.triangles[t + 2]};
    if (!check.True(c[0] < count && c[1] < count && c[2] < count &&
                        c[0] != c[1] && c[1] != c[2] && c[0] != c[2],
                    "triangle indices")) {
      return;
    }
    for (int k = 0; k < 3; ++k) {
      used[c[k]] = true;
      const uint32_t from = c[k], to = c[(k + 1) % 3];
      int& uses = edges[{std::min(from, to), std::max(from, to)}];
      // Forward uses count +1, backward uses count 10: a welded, consistently
      // oriented mesh has 1, 10 or 11 per edge.
      uses += from < to ? 1 : 10;
    }
    const uint32_t patch = mesh.surface_index[c[0]];
    if ((t / 3) % triangle_stride != 0) continue;
    if (mesh.surface_index[c[1]] != patch ||
        mesh.surface_index[c[2]] != patch) {
      continue;  // a seam triangle: its corners' (u, v) are in two patches
    }
    // Linear interpolation at the centroid and the edge midpoints.
    for (const auto& lambda : {std::array<double, 3>{1.0 / 3, 1.0 / 3, 1.0 / 3},
                               std::array<double, 3>{0.5, 0.5, 0},
                               std::array<double, 3>{0, 0.5, 0.5},
                               std::array<double, 3>{0.5, 0, 0.5}}) {
      Values point(3, 0.0);
      double u = 0, v = 0;
      for (int k = 0; k < 3; ++k) {
        for (int j = 0; j < 3; ++j) point[j] += lambda[k] * vertex(c[k])[j];
        u += lambda[k] * mesh.uv[2 * c[k]];
        v += lambda[k] * mesh.uv[2 * c[k] + 1];
      }
      const double distance = Distance(point, set.at[patch](u, v, 0, 0));
      if (!check.True(
              distance <= tolerance * (1 + 1e-9) + 1e-12,
              absl::StrCat("triangle ", t / 3, " is ", distance,
                           " from the surface at (", u, ", ", v, ")"))) {
        return;
      }
    }
    Values e1(3), e2(3);
    for (int j = 0; j < 3; ++j) {
      e1[j] = vertex(c[1])[j] - vertex(c[0])[j];
      e2[j] = vertex(c[2])[j] - vertex(c[0])[j];
    }
    const Values area = Cross(e1, e2);
    const double u =
        (mesh.uv[2 * c[0]] + mesh.uv[2 * c[1]] + mesh.uv[2 * c[2]]) / 3;
    const double v = (mesh.uv[2 * c[0] + 1] + mesh.uv[2 * c[1] + 1] +
                      mesh.uv[2 * c[2] + 1]) /
                     3;
    const Values n = UnitNormal(set.at[patch], u, v);
    if (Norm(area) > 1e-12 && !n.empty()) {
      check.True(Dot(area, n) > 0, "counter-clockwise about S_u x S_v");
    }
  }
  check.True(std::all_of(used.begin(), used.end(), [](bool b) { return b; }),
             "every vertex in a triangle");
  for (const auto& [edge, uses] : edges) {
    if (!check.True(uses == 1 || uses == 10 || uses == 11,
                    absl::StrCat("edge ", edge.first, "-", edge.second,
                                 " used once or twice in opposite "
                                 "directions"))) {
      return;
    }
  }
  const auto euler = static_cast<int64_t>(count) -
                     static_cast<int64_t>(edges.size()) +
                     static_cast<int64_t>(mesh.triangles.size() / 3);
  check.True(euler == 1, absl::StrCat("one welded disk: V - E + F = ", euler));
}

v1::TessellateSurfaceRequest RandomRequest(Rng& rng, const PatchSet& set) {
  v1::TessellateSurfaceRequest request;
  for (const v1::Surface& surface : set.surfaces) {
    *request.add_surfaces() = surface;
  }
  request.set_tolerance(std::pow(10.0, Uniform(rng, -3, -1.7)));
  request.set_normals(Coin(rng));
  return request;
}

CallResult Tessellate(Client& client, Rng& rng) {
  const PatchSet set = RandomPatchSet(rng);
  const v1::TessellateSurfaceRequest request = RandomRequest(rng, set);
  auto answer = client.TessellateSurfaces(request);
  Checker check(request, 2);
  if (answer.ok()) {
    MeshData mesh;
    mesh.Append(*answer);
    CheckMesh(mesh, set, request.tolerance(), request.normals(), check);
  }
  return check.Result(answer.status());
}

CallResult TessellateStream(Client& client, Rng& rng) {
  const PatchSet set = RandomPatchSet(rng);
  v1::TessellateSurfaceRequest request = RandomRequest(rng, set);
  request.set_chunk_size(static_cast<uint32_t>(UniformInt(rng, 16, 512)));
  std::unique_ptr<grpc::ClientContext> context = client.NewContext();
  auto reader = client.surfaces().TessellateStream(context.get(), request);
  std::vector<v1::TessellateSurfaceResponse> chunks;
  const absl::Status status = ReadStream(*reader, &chunks);
  Checker check(request, 2);
  if (status.ok()) {
    MeshData mesh;
    for (const v1::TessellateSurfaceResponse& chunk : chunks) {
      check.True(static_cast<uint32_t>(chunk.triangles_size()) <=
                     3 * request.chunk_size(),
                 "at most chunk_size triangles per chunk");
      mesh.Append(chunk);
    }
    CheckMesh(mesh, set, request.tolerance(), request.normals(), check);
  }
  return check.Result(status, chunks.size());
}

}  // namespace

std::vector<RpcCase> SurfaceTessellationCases() {
  return {{"SurfaceService.Tessellate", false, Tessellate},
          {"SurfaceService.TessellateStream", true, TessellateStream}};
}

}  // namespace freeform::reliability
