// Meshes of every surface kind (mesh.h), checked against the mathematics:
// vertices on the exact surfaces, sample points of every triangle within
// the tolerance (by the exact distance to a sphere or a torus, or by a
// point of the surface found by Gauss-Newton from the triangle's
// parameters, which bounds the distance from above), consistent
// orientation, no edge used by more than two triangles, no T-junction, and
// no boundary edge at all on closed surfaces.
#include "freeform/core/mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <initializer_list>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "freeform/core/status.h"
#include "freeform/core/surface_output.h"
#include "shapes.h"
#include "teapot.h"

namespace freeform {
namespace {

using testing_util::NurbsSphere;
using testing_util::NurbsTorus;
using testing_util::Patches;
using testing_util::ReadTeapot;

double Distance(const double* a, const double* b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

// Shapes owns surfaces of every kind and their data.
struct Shapes {
  std::vector<std::unique_ptr<SurfaceData>> data;
  std::vector<std::unique_ptr<std::vector<double>>> triangles;
  std::vector<Surface> surfaces;

  void AddBSpline(SurfaceData surface) {
    data.push_back(std::make_unique<SurfaceData>(std::move(surface)));
    absl::StatusOr<BSplineSurface> made =
        BSplineSurface::Create(data.back()->bspline_view());
    ASSERT_TRUE(made.ok()) << made.status();
    surfaces.push_back(*made);
  }
  void AddBezier(SurfaceData surface) {
    data.push_back(std::make_unique<SurfaceData>(std::move(surface)));
    absl::StatusOr<BezierSurface> made =
        BezierSurface::Create(data.back()->bezier_view());
    ASSERT_TRUE(made.ok()) << made.status();
    surfaces.push_back(*made);
  }
  // AddTriangular adds a degree-n patch with points P(i, j, k) = f(i, j).
  void AddTriangular(int n, std::function<std::array<double, 4>(int, int)> f) {
    auto points = std::make_unique<std::vector<double>>();
    auto weights = std::make_unique<std::vector<double>>();
    const size_t count = TriangularPointCount(n);
    points->resize(3 * count);
    weights->resize(count);
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) {
        const std::array<double, 4> p = f(i, j);
        const size_t k = TriangularIndex(n, i, j);
        std::copy(p.begin(), p.begin() + 3, points->begin() + 3 * k);
        (*weights)[k] = p[3];
      }
    }
    const bool rational = std::any_of(weights->begin(), weights->end(),
                                      [](double w) { return w != 1.0; });
    absl::StatusOr<TriangularPatch> made = TriangularPatch::Create(
        {.degree = n,
         .control_points = {.dimension = 3, .coordinates = *points},
         .weights = rational ? absl::Span<const double>(*weights)
                             : absl::Span<const double>(),
         .domain_triangle = {}});
    ASSERT_TRUE(made.ok()) << made.status();
    triangles.push_back(std::move(points));
    triangles.push_back(std::move(weights));
    surfaces.push_back(*made);
  }
};

// A bicubic rational Bezier patch with uneven weights over a wavy net.
SurfaceData RationalBezierPatch() {
  SurfaceData patch{
      .degree_u = 3, .degree_v = 3, .dimension = 3, .count_u = 4, .count_v = 4};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      patch.coordinates.insert(
          patch.coordinates.end(),
          {1.0 * i, 1.0 * j + 0.3 * i, 0.8 * std::sin(1.7 * i + 0.9 * j)});
      patch.weights.push_back(0.5 + 1.5 * std::fabs(std::sin(3.1 * i + j)));
    }
  }
  return patch;
}

// A bicubic B-spline surface with a double knot in u (a crease at u = 0.5)
// and unevenly spaced knots in v.
SurfaceData DoubleKnotSurface() {
  SurfaceData surface{
      .degree_u = 3, .degree_v = 3, .dimension = 3, .count_u = 7, .count_v = 6};
  for (int i = 0; i < 7; ++i) {
    for (int j = 0; j < 6; ++j) {
      surface.coordinates.insert(
          surface.coordinates.end(),
          {1.0 * i, 0.8 * j,
           (i == 3 ? 1.5 : 0.0) + 0.4 * std::cos(i + 2.0 * j)});
    }
  }
  surface.knots_u = {0, 0, 0, 0, 0.3, 0.5, 0.5, 1, 1, 1, 1};
  surface.knots_v = {0, 0, 0, 0, 0.2, 0.7, 1, 1, 1, 1};
  return surface;
}

// The surface point, and S_u x S_v in `normal`, at (u, v).
std::array<double, 3> SurfacePoint(const Surface& surface, double u, double v,
                                   std::array<double, 3>* normal = nullptr,
                                   std::array<double, 6>* partials = nullptr) {
  const std::vector<double> uv = {u, v};
  std::vector<std::vector<double>> buffers(3, std::vector<double>(3));
  std::vector<absl::Span<double>> output(buffers.begin(), buffers.end());
  EXPECT_TRUE(
      EvaluateSurface(surface, SurfaceSamples::Pairs(uv), output, {}).ok());
  const std::vector<double>& a = buffers[1];
  const std::vector<double>& b = buffers[2];
  if (normal != nullptr) {
    *normal = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
               a[0] * b[1] - a[1] * b[0]};
  }
  if (partials != nullptr) *partials = {a[0], a[1], a[2], b[0], b[1], b[2]};
  return {buffers[0][0], buffers[0][1], buffers[0][2]};
}

// A point's distance to a surface, at least the true one.
using DistanceBound = std::function<double(
    const Surface& surface, const double* point, double u, double v)>;

// GaussNewtonBound bounds the distance from `point` to `surface` by the
// nearest of the surface points met by Gauss-Newton iterations on
// |S(u, v) - point|^2 from (u, v), kept inside the domain, stopping once a
// point is within `near_enough`.
DistanceBound GaussNewtonBound(std::function<bool(double, double)> inside,
                               double near_enough = 0.0) {
  return [inside, near_enough](const Surface& surface, const double* point,
                               double u, double v) {
    double best = INFINITY;
    for (int iteration = 0; iteration < 6 && best > near_enough; ++iteration) {
      std::array<double, 6> d;
      const std::array<double, 3> s = SurfacePoint(surface, u, v, nullptr, &d);
      const double r[3] = {s[0] - point[0], s[1] - point[1], s[2] - point[2]};
      best = std::min(best, std::hypot(r[0], r[1], r[2]));
      const double a = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      const double b = d[0] * d[3] + d[1] * d[4] + d[2] * d[5];
      const double c = d[3] * d[3] + d[4] * d[4] + d[5] * d[5];
      const double gu = d[0] * r[0] + d[1] * r[1] + d[2] * r[2];
      const double gv = d[3] * r[0] + d[4] * r[1] + d[5] * r[2];
      const double det = a * c - b * b;
      if (!(det > 1e-300)) break;
      const double nu = u - (c * gu - b * gv) / det;
      const double nv = v - (a * gv - b * gu) / det;
      if (!inside(nu, nv)) break;
      u = nu;
      v = nv;
    }
    return best;
  };
}

struct MeshFigures {
  size_t boundary_edges = 0;
  size_t misoriented_edges = 0;
  size_t overused_edges = 0;
  double worst_error = 0.0;
  double longest_edge = 0.0;
};

// CheckMesh checks a mesh of `surfaces`: vertices and triangle corners on
// their surfaces to 1e-12, unit normals, 7 points of every triangle within
// `tolerance` by `distance`, triangles counter-clockwise in parameters and
// about S_u x S_v, every edge used by at most two triangles (consistently
// oriented when two), boundary edges only where `on_boundary` says the
// surfaces have an open side, no vertex inside a boundary edge, and no two
// vertices at the same place.
MeshFigures CheckMesh(const std::vector<Surface>& surfaces, const Mesh& mesh,
                      double tolerance, const DistanceBound& distance,
                      const std::function<bool(uint32_t, const double*,
                                               const double*)>& on_boundary) {
  const size_t vertex_count = mesh.vertices.size() / 3;
  EXPECT_EQ(mesh.normals.size(), 3 * vertex_count);
  EXPECT_EQ(mesh.patch.size(), vertex_count);
  EXPECT_EQ(mesh.uv.size(), 2 * vertex_count);
  const size_t triangle_count = mesh.triangles.size() / 3;
  EXPECT_EQ(mesh.triangle_patch.size(), triangle_count);
  EXPECT_EQ(mesh.corner_uv.size(), 6 * triangle_count);
  for (size_t r = 0; r < vertex_count; ++r) {
    const auto p = SurfacePoint(surfaces[mesh.patch[r]], mesh.uv[2 * r],
                                mesh.uv[2 * r + 1]);
    EXPECT_LE(Distance(p.data(), &mesh.vertices[3 * r]), 1e-12) << r;
    EXPECT_NEAR(std::hypot(mesh.normals[3 * r], mesh.normals[3 * r + 1],
                           mesh.normals[3 * r + 2]),
                1.0, 1e-12)
        << r;
  }
  MeshFigures figures;
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  std::map<std::pair<uint32_t, uint32_t>, std::vector<size_t>> edges;
  const std::array<double, 3> weights[] = {{1 / 3.0, 1 / 3.0, 1 / 3.0},
                                           {0.5, 0.5, 0},
                                           {0, 0.5, 0.5},
                                           {0.5, 0, 0.5},
                                           {2 / 3.0, 1 / 6.0, 1 / 6.0},
                                           {1 / 6.0, 2 / 3.0, 1 / 6.0},
                                           {1 / 6.0, 1 / 6.0, 2 / 3.0}};
  for (size_t t = 0; t < triangle_count; ++t) {
    const Surface& surface = surfaces[mesh.triangle_patch[t]];
    const uint32_t* corner = &mesh.triangles[3 * t];
    const double* uv = &mesh.corner_uv[6 * t];
    for (int k = 0; k < 3; ++k) {
      const auto p = SurfacePoint(surface, uv[2 * k], uv[2 * k + 1]);
      EXPECT_LE(Distance(p.data(), &mesh.vertices[3 * corner[k]]), 1e-12);
      ++directed[{corner[k], corner[(k + 1) % 3]}];
      edges[std::minmax(corner[k], corner[(k + 1) % 3])].push_back(t);
      figures.longest_edge =
          std::max(figures.longest_edge,
                   Distance(&mesh.vertices[3 * corner[k]],
                            &mesh.vertices[3 * corner[(k + 1) % 3]]));
    }
    for (const auto& w : weights) {
      double mesh_point[3] = {0, 0, 0};
      double u = 0, v = 0;
      for (int k = 0; k < 3; ++k) {
        for (int x = 0; x < 3; ++x) {
          mesh_point[x] += w[k] * mesh.vertices[3 * corner[k] + x];
        }
        u += w[k] * uv[2 * k];
        v += w[k] * uv[2 * k + 1];
      }
      figures.worst_error =
          std::max(figures.worst_error, distance(surface, mesh_point, u, v));
    }
    const double area_uv =
        (uv[2] - uv[0]) * (uv[5] - uv[1]) - (uv[4] - uv[0]) * (uv[3] - uv[1]);
    EXPECT_GT(area_uv, 0.0) << t;
    std::array<double, 3> n;
    SurfacePoint(surface, (uv[0] + uv[2] + uv[4]) / 3,
                 (uv[1] + uv[3] + uv[5]) / 3, &n);
    const double* a = &mesh.vertices[3 * corner[0]];
    const double* b = &mesh.vertices[3 * corner[1]];
    const double* c = &mesh.vertices[3 * corner[2]];
    const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double g[3] = {e1[1] * e2[2] - e1[2] * e2[1],
                         e1[2] * e2[0] - e1[0] * e2[2],
                         e1[0] * e2[1] - e1[1] * e2[0]};
    EXPECT_GT(g[0] * n[0] + g[1] * n[1] + g[2] * n[2], 0.0) << t;
  }
  EXPECT_LE(figures.worst_error, tolerance * (1 + 1e-9));
  std::vector<std::pair<uint32_t, uint32_t>> boundary;
  for (const auto& [edge, used] : edges) {
    if (used.size() > 2) ++figures.overused_edges;
    if (used.size() == 2 && directed[edge] != 1) ++figures.misoriented_edges;
    if (used.size() != 1) continue;
    ++figures.boundary_edges;
    const size_t t = used[0];
    const double* uv = &mesh.corner_uv[6 * t];
    int ka = 0, kb = 0;
    for (int k = 0; k < 3; ++k) {
      if (mesh.triangles[3 * t + k] == edge.first) ka = k;
      if (mesh.triangles[3 * t + k] == edge.second) kb = k;
    }
    EXPECT_TRUE(on_boundary(mesh.triangle_patch[t], uv + 2 * ka, uv + 2 * kb))
        << "boundary edge inside a surface or along a shared side, triangle "
        << t << " at (" << uv[2 * ka] << ", " << uv[2 * ka + 1] << ") - ("
        << uv[2 * kb] << ", " << uv[2 * kb + 1] << ")";
    boundary.push_back(edge);
  }
  // No T-junction: no vertex strictly inside a boundary edge. A vertex
  // there would end boundary edges itself (the crack), so only boundary
  // vertices are tested.
  std::vector<uint32_t> boundary_vertices;
  for (const auto& [first, second] : boundary) {
    boundary_vertices.push_back(first);
    boundary_vertices.push_back(second);
  }
  std::sort(boundary_vertices.begin(), boundary_vertices.end());
  boundary_vertices.erase(
      std::unique(boundary_vertices.begin(), boundary_vertices.end()),
      boundary_vertices.end());
  for (const auto& edge : boundary) {
    const double* a = &mesh.vertices[3 * edge.first];
    const double* b = &mesh.vertices[3 * edge.second];
    const double length = Distance(a, b);
    for (const uint32_t r : boundary_vertices) {
      const double* p = &mesh.vertices[3 * r];
      if (Distance(p, a) < 1e-9 * length || Distance(p, b) < 1e-9 * length) {
        continue;
      }
      double ab[3], ap[3];
      for (int x = 0; x < 3; ++x) {
        ab[x] = b[x] - a[x];
        ap[x] = p[x] - a[x];
      }
      const double along = std::clamp(
          (ab[0] * ap[0] + ab[1] * ap[1] + ab[2] * ap[2]) / (length * length),
          0.0, 1.0);
      double off = 0;
      for (int x = 0; x < 3; ++x) {
        off += (ap[x] - along * ab[x]) * (ap[x] - along * ab[x]);
      }
      EXPECT_GT(std::sqrt(off), 1e-9 * length) << r;
    }
  }
  EXPECT_EQ(figures.overused_edges, 0u);
  EXPECT_EQ(figures.misoriented_edges, 0u);
  std::vector<std::array<double, 3>> sorted;
  for (size_t r = 0; r < vertex_count; ++r) {
    sorted.push_back({mesh.vertices[3 * r], mesh.vertices[3 * r + 1],
                      mesh.vertices[3 * r + 2]});
  }
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end());
  return figures;
}

bool InUnitSquare(double u, double v) {
  return u >= 0 && u <= 1 && v >= 0 && v <= 1;
}

// OnSquareSide says whether both (u, v) lie on one side of [0, 1]^2.
bool OnSquareSide(const double* a, const double* b) {
  return (a[0] == b[0] && (a[0] == 0 || a[0] == 1)) ||
         (a[1] == b[1] && (a[1] == 0 || a[1] == 1));
}

absl::StatusOr<Mesh> MeshOf(const std::vector<Surface>& surfaces,
                            double tolerance, double max_edge_length = 0,
                            double max_normal_angle = 0) {
  return TessellateSurfaces(surfaces, {.tolerance = tolerance,
                                       .max_edge_length = max_edge_length,
                                       .max_normal_angle = max_normal_angle,
                                       .max_vertices = 1 << 22});
}

// ExpectPlanBounds checks that the plan of `options` (with a cap of 2^22
// vertices) bounds the mesh, not loosely.
void ExpectPlanBounds(const std::vector<Surface>& surfaces, MeshOptions options,
                      const Mesh& mesh) {
  options.max_vertices = 1 << 22;
  absl::StatusOr<std::shared_ptr<const MeshPlan>> plan =
      PlanMesh(surfaces, options);
  ASSERT_TRUE(plan.ok()) << plan.status();
  const MeshSize size = PlannedMeshSize(**plan);
  EXPECT_GE(size.vertices, mesh.vertices.size() / 3);
  EXPECT_LE(size.vertices, 3 * mesh.vertices.size() / 3);
  EXPECT_GE(size.triangles, mesh.triangles.size() / 3);
  EXPECT_LE(size.triangles, 3 * mesh.triangles.size() / 3);
}

// ExpectClosedMeshes meshes the closed surface `shapes` at each tolerance
// and checks every mesh (CheckMesh with the exact `distance`), that it has
// no boundary edge and the Euler characteristic V - E + F = `euler` (E = 3F
// / 2 when every edge has two triangles), and its plan.
void ExpectClosedMeshes(const Shapes& shapes,
                        std::initializer_list<double> tolerances,
                        const DistanceBound& distance, long euler) {
  for (const double tolerance : tolerances) {
    const absl::StatusOr<Mesh> mesh = MeshOf(shapes.surfaces, tolerance);
    ASSERT_TRUE(mesh.ok()) << mesh.status();
    const MeshFigures figures =
        CheckMesh(shapes.surfaces, *mesh, tolerance, distance,
                  [](uint32_t, const double*, const double*) { return false; });
    EXPECT_EQ(figures.boundary_edges, 0u);
    const long v = static_cast<long>(mesh->vertices.size() / 3);
    const long f = static_cast<long>(mesh->triangles.size() / 3);
    EXPECT_EQ(v - 3 * f / 2 + f, euler);
    ExpectPlanBounds(shapes.surfaces, {.tolerance = tolerance}, *mesh);
    std::printf("closed mesh at %g: %ld vertices, %ld triangles, worst %.3g\n",
                tolerance, v, f, figures.worst_error);
  }
}

TEST(MeshTest, NurbsSphereIsClosedAndWithinTolerance) {
  constexpr double kRadius = 2.0;
  Shapes shapes;
  shapes.AddBSpline(NurbsSphere(kRadius));
  // Genus 0.
  ExpectClosedMeshes(
      shapes, {1e-2, 1e-3},
      [](const Surface&, const double* p, double, double) {
        return std::fabs(std::hypot(p[0], p[1], p[2]) - kRadius);
      },
      2);
}

TEST(MeshTest, NurbsTorusHasNoBoundaryEdge) {
  constexpr double kMajor = 3.0, kMinor = 1.0;
  Shapes shapes;
  shapes.AddBSpline(NurbsTorus(kMajor, kMinor));
  // Genus 1.
  ExpectClosedMeshes(
      shapes, {1e-2, 3e-3},
      [](const Surface&, const double* p, double, double) {
        return std::fabs(std::hypot(std::hypot(p[0], p[1]) - kMajor, p[2]) -
                         kMinor);
      },
      0);
}

// MeshesOfOpenSurfaces meshes `shapes` at each tolerance and checks every
// mesh (CheckMesh with Gauss-Newton distances inside `inside`, boundary
// edges where `on_side` says) and its plan; it returns the meshes.
std::vector<Mesh> MeshesOfOpenSurfaces(
    const Shapes& shapes, std::initializer_list<double> tolerances,
    const std::function<bool(double, double)>& inside,
    const std::function<bool(const double*, const double*)>& on_side) {
  std::vector<Mesh> meshes;
  for (const double tolerance : tolerances) {
    absl::StatusOr<Mesh> mesh = MeshOf(shapes.surfaces, tolerance);
    EXPECT_TRUE(mesh.ok()) << mesh.status();
    if (!mesh.ok()) break;
    const MeshFigures figures =
        CheckMesh(shapes.surfaces, *mesh, tolerance,
                  GaussNewtonBound(inside, tolerance / 2),
                  [&](uint32_t, const double* a, const double* b) {
                    return on_side(a, b);
                  });
    EXPECT_GT(figures.boundary_edges, 0u);
    ExpectPlanBounds(shapes.surfaces, {.tolerance = tolerance}, *mesh);
    meshes.push_back(*std::move(mesh));
  }
  return meshes;
}

bool InTriangle(double u, double v) { return u >= 0 && v >= 0 && u + v <= 1; }

TEST(MeshTest, RationalBezierPatchWithinTolerance) {
  Shapes shapes;
  shapes.AddBezier(RationalBezierPatch());
  EXPECT_EQ(
      MeshesOfOpenSurfaces(shapes, {1e-2, 1e-3}, InUnitSquare, OnSquareSide)
          .size(),
      2u);
}

// A cubic triangular patch over a wavy height field, and a rational
// quadratic one.
Shapes TriangularPatches() {
  Shapes shapes;
  shapes.AddTriangular(3, [](int i, int j) -> std::array<double, 4> {
    return {i / 3.0, j / 3.0, 0.5 * std::sin(2.0 * i - j), 1.0};
  });
  shapes.AddTriangular(2, [](int i, int j) -> std::array<double, 4> {
    return {2.0 + i / 2.0, j / 2.0, 0.3 * i * j, i + j == 1 ? 0.6 : 1.4};
  });
  return shapes;
}

// OnTriangleSide says whether both barycentric (u, v) lie on one side of
// the domain triangle u = 0, v = 0 or u + v = 1.
bool OnTriangleSide(const double* a, const double* b) {
  const auto side = [](const double* p, int k) {
    return k == 0   ? p[0] == 0
           : k == 1 ? p[1] == 0
                    : std::fabs(p[0] + p[1] - 1) < 1e-15;
  };
  for (int k = 0; k < 3; ++k) {
    if (side(a, k) && side(b, k)) return true;
  }
  return false;
}

TEST(MeshTest, TriangularPatchesWithinTolerance) {
  EXPECT_EQ(MeshesOfOpenSurfaces(TriangularPatches(), {1e-2, 1e-3}, InTriangle,
                                 OnTriangleSide)
                .size(),
            2u);
}

TEST(MeshTest, BSplineSurfaceWithDoubleKnot) {
  Shapes shapes;
  shapes.AddBSpline(DoubleKnotSurface());
  const std::vector<Mesh> meshes =
      MeshesOfOpenSurfaces(shapes, {1e-2, 1e-3}, InUnitSquare, OnSquareSide);
  ASSERT_EQ(meshes.size(), 2u);
  for (const Mesh& mesh : meshes) {
    // The crease u = 0.5 is meshed: vertices lie on it.
    size_t on_crease = 0;
    for (size_t r = 0; r < mesh.uv.size() / 2; ++r) {
      on_crease += mesh.uv[2 * r] == 0.5;
    }
    EXPECT_GE(on_crease, 3u);
  }
}

// Every kind in one request: two triangular patches, a B-spline surface
// with a double knot, a rational Bezier patch and a NURBS sphere.
Shapes EveryKind() {
  Shapes shapes = TriangularPatches();
  shapes.AddBSpline(DoubleKnotSurface());
  shapes.AddBezier(RationalBezierPatch());
  shapes.AddBSpline(NurbsSphere(1.0));
  return shapes;
}

// EveryKindDistance is GaussNewtonBound inside the domain of each surface
// of EveryKind `shapes`.
DistanceBound EveryKindDistance(const Shapes& shapes, double tolerance) {
  return [&shapes, tolerance](const Surface& surface, const double* p, double u,
                              double v) {
    const size_t index = static_cast<size_t>(&surface - &shapes.surfaces[0]);
    return GaussNewtonBound(index < 2 ? InTriangle : InUnitSquare,
                            tolerance / 2)(surface, p, u, v);
  };
}

// EveryKindOnBoundary says whether (u, v) a and b lie on an open side of a
// surface of EveryKind.
bool EveryKindOnBoundary(uint32_t surface, const double* a, const double* b) {
  return surface < 2 ? OnTriangleSide(a, b) : surface < 4 && OnSquareSide(a, b);
}

TEST(MeshTest, EveryKindInOneRequest) {
  const Shapes shapes = EveryKind();
  constexpr double kTolerance = 2e-3;
  const absl::StatusOr<Mesh> mesh = MeshOf(shapes.surfaces, kTolerance);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  const MeshFigures figures =
      CheckMesh(shapes.surfaces, *mesh, kTolerance,
                EveryKindDistance(shapes, kTolerance), EveryKindOnBoundary);
  EXPECT_GT(figures.boundary_edges, 0u);
  std::vector<size_t> vertices_of(shapes.surfaces.size());
  for (const uint32_t surface : mesh->patch) ++vertices_of[surface];
  for (const size_t count : vertices_of) EXPECT_GT(count, 0u);
}

TEST(MeshTest, LongestEdgeLimit) {
  Shapes shapes;
  shapes.AddBSpline(DoubleKnotSurface());
  shapes.AddBSpline(NurbsSphere(1.0));
  for (const double longest : {0.5, 0.25}) {
    const absl::StatusOr<Mesh> mesh = MeshOf(shapes.surfaces, 1e-2, longest);
    ASSERT_TRUE(mesh.ok()) << mesh.status();
    const MeshFigures figures = CheckMesh(
        shapes.surfaces, *mesh, 1e-2, GaussNewtonBound(InUnitSquare, 5e-3),
        [](uint32_t surface, const double* a, const double* b) {
          return surface == 0 && OnSquareSide(a, b);
        });
    EXPECT_LE(figures.longest_edge, longest);
    EXPECT_GT(figures.longest_edge, longest / 4);
  }
}

// The Utah teapot's 32 patches and the sides no other patch shares.
struct Teapot {
  Patches patches;
  Shapes shapes;
  // Every side's control points (the lesser direction), and their uses.
  std::map<std::pair<uint32_t, int>, std::vector<double>> keys;
  std::map<std::vector<double>, int> uses;

  // OnUnsharedSide says whether (u, v) a and b lie on one side of patch
  // `patch` that no other patch shares, in either direction.
  bool OnUnsharedSide(uint32_t patch, const double* a, const double* b) const {
    const int side = a[1] == 0 && b[1] == 0   ? 0
                     : a[0] == 1 && b[0] == 1 ? 1
                     : a[1] == 1 && b[1] == 1 ? 2
                     : a[0] == 0 && b[0] == 0 ? 3
                                              : -1;
    return side >= 0 && uses.at(keys.at({patch, side})) == 1;
  }
};

Teapot MakeTeapot() {
  Teapot teapot{.patches = ReadTeapot()};
  EXPECT_EQ(teapot.patches.nets.size(), 32u);
  for (const BezierSurfaceView& view : teapot.patches.Views()) {
    absl::StatusOr<BezierSurface> made = BezierSurface::Create(view);
    EXPECT_TRUE(made.ok());
    if (made.ok()) teapot.shapes.surfaces.push_back(*made);
  }
  for (uint32_t i = 0; i < teapot.patches.nets.size(); ++i) {
    for (int side = 0; side < 4; ++side) {
      std::vector<std::array<double, 3>> points;
      for (int k = 0; k < 4; ++k) {
        const int row = side == 0 || side == 2 ? k : side == 1 ? 3 : 0;
        const int col = side == 1 || side == 3 ? k : side == 2 ? 3 : 0;
        const double* p = &teapot.patches.nets[i][3 * (row * 4 + col)];
        points.push_back({p[0], p[1], p[2]});
      }
      std::vector<std::array<double, 3>> reversed(points.rbegin(),
                                                  points.rend());
      std::vector<double> flat;
      for (const auto& p : std::min(points, reversed)) {
        flat.insert(flat.end(), p.begin(), p.end());
      }
      ++teapot.uses[flat];
      teapot.keys[{i, side}] = flat;
    }
  }
  return teapot;
}

// The distance from a mesh point to the teapot patch point at its
// parameters.
double TeapotDistance(const Surface& surface, const double* p, double u,
                      double v) {
  const auto s = SurfacePoint(surface, u, v);
  return Distance(s.data(), p);
}

TEST(MeshTest, UtahTeapotIsWatertightAndWithinTolerance) {
  const Teapot teapot = MakeTeapot();
  const Shapes& shapes = teapot.shapes;
  ASSERT_EQ(shapes.surfaces.size(), 32u);
  const auto unshared_side = [&](uint32_t patch, const double* a,
                                 const double* b) {
    return teapot.OnUnsharedSide(patch, a, b);
  };
  constexpr double kTolerance = 1e-3;
  const absl::StatusOr<Mesh> mesh = MeshOf(shapes.surfaces, kTolerance);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  const MeshFigures figures = CheckMesh(shapes.surfaces, *mesh, kTolerance,
                                        TeapotDistance, unshared_side);
  EXPECT_GT(figures.boundary_edges, 0u);  // rim, spout and handle ends
  const size_t coarse = MeshOf(shapes.surfaces, 1e-2)->vertices.size();
  EXPECT_LT(coarse, mesh->vertices.size());
  ExpectPlanBounds(shapes.surfaces, {.tolerance = kTolerance}, *mesh);
  EXPECT_EQ(
      PlanMesh(shapes.surfaces, {.tolerance = kTolerance, .max_vertices = 100})
          .status()
          .code(),
      absl::StatusCode::kResourceExhausted);
}

// The error of CornerNormals against the exact corner normals.
constexpr double kAngleSlack = 1e-6;

// Angle returns the angle between the non-zero vectors a and b.
double Angle(const double* a, const double* b) {
  const double cross[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                           a[0] * b[1] - a[1] * b[0]};
  return std::atan2(std::hypot(cross[0], cross[1], cross[2]),
                    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

// CornerNormals returns S_u x S_v of the surface of triangle t at its
// corners; where it vanishes relative to |S_u|^2 + |S_v|^2 (a collapsed
// side), the normal a millionth of the way from the corner to the
// triangle's centroid in parameters, near the limit from inside the
// triangle.
std::array<std::array<double, 3>, 3> CornerNormals(
    const std::vector<Surface>& surfaces, const Mesh& mesh, size_t t) {
  const Surface& surface = surfaces[mesh.triangle_patch[t]];
  const double* uv = &mesh.corner_uv[6 * t];
  const double centre[2] = {(uv[0] + uv[2] + uv[4]) / 3,
                            (uv[1] + uv[3] + uv[5]) / 3};
  std::array<std::array<double, 3>, 3> normals;
  for (int k = 0; k < 3; ++k) {
    std::array<double, 6> d;
    std::array<double, 3>& n = normals[k];
    SurfacePoint(surface, uv[2 * k], uv[2 * k + 1], &n, &d);
    const double scale = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + d[3] * d[3] +
                         d[4] * d[4] + d[5] * d[5];
    if (std::hypot(n[0], n[1], n[2]) > 1e-8 * scale) continue;
    SurfacePoint(surface, uv[2 * k] + 1e-6 * (centre[0] - uv[2 * k]),
                 uv[2 * k + 1] + 1e-6 * (centre[1] - uv[2 * k + 1]), &n);
  }
  return normals;
}

// The normal angles of a mesh's edges.
struct AngleFigures {
  // The largest angle between the normals of a triangle's surface at the
  // two ends of one of its edges (CornerNormals).
  double worst = 0.0;
  // The largest angle between the vertex normals (Mesh::normals) at the
  // two ends of a triangle edge where they are the triangle's corner
  // normals, and the corners where they are not (on a crease).
  double worst_vertex = 0.0;
  size_t other_corners = 0;
};

AngleFigures EdgeNormalAngles(const std::vector<Surface>& surfaces,
                              const Mesh& mesh) {
  AngleFigures figures;
  for (size_t t = 0; t < mesh.triangle_patch.size(); ++t) {
    const auto corner = CornerNormals(surfaces, mesh, t);
    std::array<const double*, 3> vertex;
    std::array<bool, 3> agrees;
    for (int k = 0; k < 3; ++k) {
      vertex[k] = &mesh.normals[3 * mesh.triangles[3 * t + k]];
      agrees[k] = Angle(vertex[k], corner[k].data()) <= kAngleSlack;
      figures.other_corners += !agrees[k];
    }
    for (int k = 0; k < 3; ++k) {
      const int l = (k + 1) % 3;
      figures.worst =
          std::max(figures.worst, Angle(corner[k].data(), corner[l].data()));
      if (agrees[k] && agrees[l]) {
        figures.worst_vertex =
            std::max(figures.worst_vertex, Angle(vertex[k], vertex[l]));
      }
    }
  }
  return figures;
}

// A mesh made with a normal-angle limit (0: none) and its figures.
struct LimitedMesh {
  double limit = 0.0;
  Mesh mesh;
  MeshFigures figures;
  AngleFigures angles;
};

// MeshesWithNormalAngles meshes `shapes` within `tolerance` without a
// normal-angle limit and then with each of the decreasing `limits`, checks
// every mesh (CheckMesh with `distance` and `on_boundary`) and that its
// plan bounds it, and for a limit that every triangle's corner normals are
// within it, as are the vertex normals where they are the corners', and
// that the vertices do not decrease as the limit shrinks. Returns the
// meshes, the unlimited one first.
std::vector<LimitedMesh> MeshesWithNormalAngles(
    const Shapes& shapes, double tolerance,
    std::initializer_list<double> limits, const DistanceBound& distance,
    const std::function<bool(uint32_t, const double*, const double*)>&
        on_boundary) {
  std::vector<double> all = {0.0};
  all.insert(all.end(), limits);
  std::vector<LimitedMesh> meshes;
  for (const double limit : all) {
    absl::StatusOr<Mesh> mesh = MeshOf(shapes.surfaces, tolerance, 0.0, limit);
    EXPECT_TRUE(mesh.ok()) << limit << ": " << mesh.status();
    if (!mesh.ok()) break;
    LimitedMesh& result = meshes.emplace_back();
    result.limit = limit;
    result.mesh = *std::move(mesh);
    result.figures = CheckMesh(shapes.surfaces, result.mesh, tolerance,
                               distance, on_boundary);
    ExpectPlanBounds(shapes.surfaces,
                     {.tolerance = tolerance, .max_normal_angle = limit},
                     result.mesh);
    result.angles = EdgeNormalAngles(shapes.surfaces, result.mesh);
    std::printf(
        "normal angle limit %g: %zu vertices, worst corner normal angle %.4g "
        "(vertex normals %.4g, %zu other corners)\n",
        limit, result.mesh.vertices.size() / 3, result.angles.worst,
        result.angles.worst_vertex, result.angles.other_corners);
    if (limit == 0.0) continue;
    EXPECT_LE(result.angles.worst, limit + kAngleSlack);
    EXPECT_LE(result.angles.worst_vertex, limit + kAngleSlack);
    EXPECT_GE(result.mesh.vertices.size(),
              meshes[meshes.size() - 2].mesh.vertices.size());
  }
  return meshes;
}

// ExpectSameMesh checks that two meshes are the same, bit for bit.
void ExpectSameMesh(const Mesh& a, const Mesh& b) {
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.patch, b.patch);
  EXPECT_EQ(a.uv, b.uv);
  EXPECT_EQ(a.triangle_patch, b.triangle_patch);
  EXPECT_EQ(a.corner_uv, b.corner_uv);
}

using NormalField = std::function<std::array<double, 3>(const double*)>;

// ExactEdgeAngle checks that the vertex normals of `mesh` are the exact
// unit normals `normal` of its surface (up to one orientation, to 1e-9) and
// returns the largest angle between the exact normals at the two ends of an
// edge.
double ExactEdgeAngle(const Mesh& mesh, const NormalField& normal) {
  const size_t count = mesh.vertices.size() / 3;
  std::vector<std::array<double, 3>> exact(count);
  double sign = 0.0;
  for (size_t r = 0; r < count; ++r) {
    exact[r] = normal(&mesh.vertices[3 * r]);
    const double* n = &mesh.normals[3 * r];
    if (sign == 0.0) {
      sign = n[0] * exact[r][0] + n[1] * exact[r][1] + n[2] * exact[r][2] > 0
                 ? 1.0
                 : -1.0;
    }
    const double oriented[3] = {sign * exact[r][0], sign * exact[r][1],
                                sign * exact[r][2]};
    EXPECT_LE(Angle(n, oriented), 1e-9) << r;
  }
  double worst = 0.0;
  for (size_t t = 0; 3 * t < mesh.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      worst = std::max(
          worst, Angle(exact[mesh.triangles[3 * t + k]].data(),
                       exact[mesh.triangles[3 * t + (k + 1) % 3]].data()));
    }
  }
  return worst;
}

// The outward unit normal of the sphere about the origin at p.
std::array<double, 3> SphereNormal(const double* p) {
  const double r = std::hypot(p[0], p[1], p[2]);
  return {p[0] / r, p[1] / r, p[2] / r};
}

// The outward unit normal at p of the torus about z with major radius
// `major`: from the centre of the tube circle through p.
std::array<double, 3> TorusNormal(double major, const double* p) {
  const double rho = std::hypot(p[0], p[1]);
  const double d[3] = {p[0] - major * p[0] / rho, p[1] - major * p[1] / rho,
                       p[2]};
  const double length = std::hypot(d[0], d[1], d[2]);
  return {d[0] / length, d[1] / length, d[2] / length};
}

TEST(MeshTest, NormalAngleLimitOnSphereAndTorus) {
  constexpr double kRadius = 2.0, kMajor = 3.0, kMinor = 1.0;
  struct Closed {
    SurfaceData data;
    DistanceBound distance;
    NormalField normal;
    long euler;
  };
  const Closed cases[] = {
      {NurbsSphere(kRadius),
       [](const Surface&, const double* p, double, double) {
         return std::fabs(std::hypot(p[0], p[1], p[2]) - kRadius);
       },
       SphereNormal, 2},
      {NurbsTorus(kMajor, kMinor),
       [](const Surface&, const double* p, double, double) {
         return std::fabs(std::hypot(std::hypot(p[0], p[1]) - kMajor, p[2]) -
                          kMinor);
       },
       [](const double* p) { return TorusNormal(kMajor, p); }, 0}};
  for (const Closed& closed : cases) {
    Shapes shapes;
    shapes.AddBSpline(closed.data);
    const std::vector<LimitedMesh> meshes = MeshesWithNormalAngles(
        shapes, 1e-2, {0.1, 0.05}, closed.distance,
        [](uint32_t, const double*, const double*) { return false; });
    ASSERT_EQ(meshes.size(), 3u);
    for (const LimitedMesh& limited : meshes) {
      EXPECT_EQ(limited.figures.boundary_edges, 0u);
      const long v = static_cast<long>(limited.mesh.vertices.size() / 3);
      const long f = static_cast<long>(limited.mesh.triangles.size() / 3);
      EXPECT_EQ(v - 3 * f / 2 + f, closed.euler);
      // Smooth surfaces: every vertex has one normal, at the poles too.
      EXPECT_EQ(limited.angles.other_corners, 0u);
      const double worst = ExactEdgeAngle(limited.mesh, closed.normal);
      if (limited.limit > 0.0) {
        EXPECT_LE(worst, limited.limit + 1e-9);
      }
    }
    // Within 1e-2 every edge already holds 0.1, so the limit changes
    // nothing; 0.05 needs more vertices, and is not held loosely.
    ExpectSameMesh(meshes[1].mesh, meshes[0].mesh);
    EXPECT_GT(meshes[2].mesh.vertices.size(), meshes[1].mesh.vertices.size());
    EXPECT_GT(meshes[2].angles.worst, 0.05 / 2);
  }
}

TEST(MeshTest, NormalAngleLimitOnTeapot) {
  const Teapot teapot = MakeTeapot();
  const std::vector<LimitedMesh> meshes = MeshesWithNormalAngles(
      teapot.shapes, 1e-2, {0.3, 0.2}, TeapotDistance,
      [&](uint32_t patch, const double* a, const double* b) {
        return teapot.OnUnsharedSide(patch, a, b);
      });
  ASSERT_EQ(meshes.size(), 3u);
  for (size_t k = 1; k < meshes.size(); ++k) {
    EXPECT_GT(meshes[k].mesh.vertices.size(),
              meshes[k - 1].mesh.vertices.size());
    EXPECT_GT(meshes[k].angles.worst, meshes[k].limit / 2);
    // The handle's lower end touches the body at a corner point, where a
    // vertex carries the normal of one surface only.
    EXPECT_GT(meshes[k].angles.other_corners, 0u);
  }
}

TEST(MeshTest, NormalAngleLimitOnEveryKind) {
  const Shapes shapes = EveryKind();
  constexpr double kTolerance = 1e-2;
  const std::vector<LimitedMesh> meshes = MeshesWithNormalAngles(
      shapes, kTolerance, {0.2, 0.1}, EveryKindDistance(shapes, kTolerance),
      EveryKindOnBoundary);
  ASSERT_EQ(meshes.size(), 3u);
  EXPECT_GT(meshes[2].mesh.vertices.size(), meshes[0].mesh.vertices.size());
}

// The normal-angle refinement polls the token and respects the vertex cap,
// naming the limit.
TEST(MeshTest, NormalAngleLimitCapAndCancellation) {
  Shapes shapes;
  shapes.AddBSpline(NurbsSphere(2.0));
  const MeshOptions plain = {.tolerance = 1e-2, .max_vertices = 1 << 22};
  MeshOptions limited = plain;
  limited.max_normal_angle = 0.05;
  const auto size_of = [&](const MeshOptions& options) {
    absl::StatusOr<std::shared_ptr<const MeshPlan>> plan =
        PlanMesh(shapes.surfaces, options);
    EXPECT_TRUE(plan.ok()) << plan.status();
    return plan.ok() ? PlannedMeshSize(**plan).vertices : 0;
  };
  const size_t plain_size = size_of(plain);
  limited.max_vertices = size_of(limited);
  ASSERT_GT(limited.max_vertices, plain_size);
  EXPECT_TRUE(PlanMesh(shapes.surfaces, limited).ok());
  limited.max_vertices = plain_size;
  EXPECT_EQ(FieldPathOf(PlanMesh(shapes.surfaces, limited).status()),
            "max_normal_angle");
  limited.max_vertices = plain_size - 1;
  EXPECT_EQ(FieldPathOf(PlanMesh(shapes.surfaces, limited).status()),
            "tolerance");
  limited.max_vertices = 1 << 22;
  // Count the polls of a plan without and with the limit, then cancel at
  // the last one.
  const auto polls_of = [&](const MeshOptions& options, int cancel_at) {
    int polls = 0;
    CancellationToken token;
    token.SetPoll([&] { return ++polls == cancel_at; });
    const absl::Status status =
        PlanMesh(shapes.surfaces, options, &token).status();
    EXPECT_EQ(status.code(), cancel_at > 0 ? absl::StatusCode::kCancelled
                                           : absl::StatusCode::kOk);
    return polls;
  };
  const int plain_polls = polls_of(plain, 0);
  const int limited_polls = polls_of(limited, 0);
  EXPECT_GT(limited_polls, plain_polls + 1);
  polls_of(limited, limited_polls);
}

// Two patches of different degrees sharing a side in opposite directions:
// A's side v = 1 is B's side u = 0 reversed.
Patches TwoPatches() {
  Patches patches;
  std::vector<double> a;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      a.insert(a.end(), {static_cast<double>(i), static_cast<double>(j),
                         0.3 * std::sin(i * 1.3 + j * 0.7)});
    }
  }
  std::vector<double> b;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) {
      if (i == 0) {
        const double* p = &a[3 * ((3 - j) * 4 + 3)];
        b.insert(b.end(), p, p + 3);
      } else {
        b.insert(b.end(), {3.0 - j, 3.0 + 1.5 * i, 0.8 * std::cos(i + j)});
      }
    }
  }
  patches.nets = {a, b};
  patches.counts = {{4, 4}, {3, 4}};
  return patches;
}

// Without the corner attributes the mesh is the same mesh, bit for bit,
// with empty triangle_patch and corner_uv; its planned memory is smaller by
// at least those arrays (52 bytes per planned triangle).
TEST(MeshTest, SkippingCornerAttributesKeepsTheMesh) {
  const Shapes shapes = EveryKind();
  for (const double max_normal_angle : {0.0, 0.3}) {
    absl::StatusOr<std::shared_ptr<const MeshPlan>> plan =
        PlanMesh(shapes.surfaces, {.tolerance = 2e-3,
                                   .max_normal_angle = max_normal_angle,
                                   .max_vertices = 1 << 22});
    ASSERT_TRUE(plan.ok()) << plan.status();
    const absl::StatusOr<Mesh> full = TessellatePlanned(**plan);
    const absl::StatusOr<Mesh> lean =
        TessellatePlanned(**plan, nullptr, CornerAttributes::kSkip);
    ASSERT_TRUE(full.ok()) << full.status();
    ASSERT_TRUE(lean.ok()) << lean.status();
    EXPECT_FALSE(full->corner_uv.empty());
    Mesh expected = *full;
    expected.triangle_patch.clear();
    expected.corner_uv.clear();
    ExpectSameMesh(*lean, expected);
    const MeshMemory with = PlannedMeshMemory(**plan, CornerAttributes::kMake);
    const MeshMemory without =
        PlannedMeshMemory(**plan, CornerAttributes::kSkip);
    const uint64_t attributes = PlannedMeshSize(**plan).triangles * 52;
    EXPECT_EQ(with.plan, without.plan);
    EXPECT_EQ(with.mesh, without.mesh + attributes);
    EXPECT_GE(with.tessellation, without.tessellation + attributes);
    // The mesh's own arrays are within what the plan says it takes.
    const uint64_t made =
        8 * (lean->vertices.size() + lean->normals.size() + lean->uv.size()) +
        4 * (lean->patch.size() + lean->triangles.size());
    EXPECT_LE(made, without.mesh);
    EXPECT_LE(without.mesh, without.tessellation);
  }
}

TEST(MeshTest, SharedReversedSideIsWelded) {
  const Patches patches = TwoPatches();
  Shapes shapes;
  for (const BezierSurfaceView& view : patches.Views()) {
    absl::StatusOr<BezierSurface> made = BezierSurface::Create(view);
    ASSERT_TRUE(made.ok());
    shapes.surfaces.push_back(*made);
  }
  for (double tolerance : {1e-1, 1e-3, 1e-4}) {
    const absl::StatusOr<Mesh> mesh = MeshOf(shapes.surfaces, tolerance);
    ASSERT_TRUE(mesh.ok()) << mesh.status();
    CheckMesh(shapes.surfaces, *mesh, tolerance,
              GaussNewtonBound(InUnitSquare, tolerance / 2),
              [](uint32_t patch, const double* a, const double* b) {
                // Every side but A's v = 1 and B's u = 0.
                return OnSquareSide(a, b) &&
                       !(patch == 0 && a[1] == 1 && b[1] == 1) &&
                       !(patch == 1 && a[0] == 0 && b[0] == 0);
              });
    // Vertices on the shared curve appear once and are used by both.
    std::map<uint32_t, std::array<bool, 2>> on_shared;
    for (size_t t = 0; t < mesh->triangle_patch.size(); ++t) {
      const uint32_t patch = mesh->triangle_patch[t];
      for (int k = 0; k < 3; ++k) {
        const double* uv = &mesh->corner_uv[6 * t + 2 * k];
        if ((patch == 0 && uv[1] == 1) || (patch == 1 && uv[0] == 0)) {
          on_shared[mesh->triangles[3 * t + k]][patch] = true;
        }
      }
    }
    ASSERT_GE(on_shared.size(), 2u);
    for (const auto& [vertex, used] : on_shared) {
      EXPECT_TRUE(used[0] && used[1]) << vertex;
    }
  }
}

// docs/references.md, 'Meshing surfaces within a tolerance': the bicubic
// bump has M_uu = M_vv = 6 and M_uv = 9, so at tolerance 0.01 its grid has
// ceil(sqrt(15 / 0.04)) = 20 cells each way: 21 x 21 vertices.
TEST(MeshTest, BumpWorkedExample) {
  SurfaceData bump{
      .degree_u = 3, .degree_v = 3, .dimension = 3, .count_u = 4, .count_v = 4};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const bool inner = i % 3 != 0 && j % 3 != 0;
      bump.coordinates.insert(bump.coordinates.end(),
                              {1.0 * i, 1.0 * j, inner ? 1.0 : 0.0});
    }
  }
  Shapes shapes;
  shapes.AddBezier(bump);
  absl::StatusOr<std::shared_ptr<const MeshPlan>> plan =
      PlanMesh(shapes.surfaces, {.tolerance = 0.01, .max_vertices = 1000});
  ASSERT_TRUE(plan.ok()) << plan.status();
  EXPECT_EQ(PlannedMeshSize(**plan).vertices, 441u);
  const absl::StatusOr<Mesh> mesh = TessellatePlanned(**plan);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  EXPECT_EQ(mesh->vertices.size(), 3u * 441);
  EXPECT_EQ(mesh->triangles.size(), 3u * 2 * 20 * 20);
  // 20 cells need 441 vertices: a cap of 440 is refused, naming the
  // tolerance.
  EXPECT_EQ(FieldPathOf(PlanMesh(shapes.surfaces,
                                 {.tolerance = 0.01, .max_vertices = 440})
                            .status()),
            "tolerance");
}

TEST(MeshTest, Errors) {
  Shapes shapes;
  shapes.AddBezier(RationalBezierPatch());
  SurfaceData negative = DoubleKnotSurface();
  negative.weights.assign(42, 1.0);
  negative.weights[8] = 0.0;
  shapes.AddBSpline(negative);
  EXPECT_EQ(FieldPathOf(MeshOf(shapes.surfaces, 1e-3).status()),
            "surfaces[1].bspline.weights[8]");
  shapes.surfaces.pop_back();
  EXPECT_EQ(FieldPathOf(MeshOf(shapes.surfaces, 0.0).status()), "tolerance");
  EXPECT_EQ(FieldPathOf(MeshOf(shapes.surfaces, 1e-3, -1.0).status()),
            "max_edge_length");
  EXPECT_EQ(FieldPathOf(MeshOf(shapes.surfaces, 1e-3, NAN).status()),
            "max_edge_length");
  for (const double angle :
       {-0.1, std::numbers::pi, 4.0, std::numeric_limits<double>::quiet_NaN(),
        std::numeric_limits<double>::infinity()}) {
    EXPECT_EQ(FieldPathOf(MeshOf(shapes.surfaces, 1e-3, 0.0, angle).status()),
              "max_normal_angle")
        << angle;
  }
  EXPECT_TRUE(MeshOf(shapes.surfaces, 1e-2, 0.0, 3.14).ok());
  EXPECT_EQ(FieldPathOf(MeshOf(shapes.surfaces, 1e-300).status()), "tolerance");
  EXPECT_EQ(MeshOf(shapes.surfaces, 1e-9).status().code(),
            absl::StatusCode::kResourceExhausted);
  SurfaceData flat = DoubleKnotSurface();
  flat.dimension = 2;
  flat.coordinates.resize(2 * 42);
  shapes.AddBSpline(flat);
  EXPECT_EQ(FieldPathOf(MeshOf(shapes.surfaces, 1e-3).status()),
            "surfaces[1].bspline.control_net.dimension");
  shapes.surfaces.pop_back();
  CancellationToken token;
  token.Cancel();
  EXPECT_EQ(
      TessellateSurfaces(shapes.surfaces,
                         {.tolerance = 1e-3, .max_vertices = 1 << 20}, &token)
          .status()
          .code(),
      absl::StatusCode::kCancelled);
}

}  // namespace
}  // namespace freeform
