// TessellateFace (face_mesh.h) against the mathematics: a plane square with
// a round hole (area, trims, topology), a quarter cylinder with a window
// and a round hole (every sampled mesh point within the tolerance of the
// exact cylinder, inside the trimmed region), a paraboloid across knot
// lines (where the bound is exact) and the full NURBS cylinder across its
// C0 knot lines.
#include "freeform/core/face_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <utility>
#include <vector>

#include "freeform/core/cancellation.h"
#include "freeform/core/status.h"
#include "freeform/core/surface.h"
#include "freeform/core/trimmed_surface.h"
#include "trim_shapes.h"

namespace freeform {
namespace {

using trim_testing::ClockwiseCircle;
using trim_testing::LoopOf;
using trim_testing::Square;

constexpr double kPi = std::numbers::pi;
constexpr double kRadius = 1.5;  // of the cylinder
constexpr double kHeight = 2.0;

// ArcParameter returns the u of the quarter arc at angle theta in
// [0, pi / 2] (its angle grows with u: bisection).
double ArcParameter(double theta) {
  const double w = std::sqrt(0.5);
  double lo = 0.0, hi = 1.0;
  for (int k = 0; k < 80; ++k) {
    const double u = 0.5 * (lo + hi);
    const double b0 = (1 - u) * (1 - u), b1 = 2 * w * u * (1 - u), b2 = u * u;
    const double angle = std::atan2(b1 + b2, b0 + b1);
    (angle < theta ? lo : hi) = u;
  }
  return 0.5 * (lo + hi);
}

const double* Vertex(const FaceMesh& mesh, uint32_t v) {
  return &mesh.vertices[3 * static_cast<size_t>(v)];
}

double TriangleArea(const double* a, const double* b, const double* c) {
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  return 0.5 * std::hypot(ab[1] * ac[2] - ab[2] * ac[1],
                          ab[2] * ac[0] - ab[0] * ac[2],
                          ab[0] * ac[1] - ab[1] * ac[0]);
}

double UvCross(const FaceMesh& mesh, size_t t) {
  const auto uv = [&](int k) {
    return &mesh.uv[2 * static_cast<size_t>(mesh.triangles[t + k])];
  };
  return (uv(1)[0] - uv(0)[0]) * (uv(2)[1] - uv(0)[1]) -
         (uv(1)[1] - uv(0)[1]) * (uv(2)[0] - uv(0)[0]);
}

// Edges counts the triangles of every undirected edge.
std::map<std::pair<uint32_t, uint32_t>, int> Edges(const FaceMesh& mesh) {
  std::map<std::pair<uint32_t, uint32_t>, int> edges;
  for (size_t t = 0; t < mesh.triangles.size(); t += 3) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = mesh.triangles[t + k];
      const uint32_t b = mesh.triangles[t + (k + 1) % 3];
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  }
  return edges;
}

// The sample points of a triangle: its edges' midpoints, its centroid and
// the three points of barycentric (2/3, 1/6, 1/6).
std::vector<std::array<double, 3>> TriangleSamples(const double* p[3]) {
  const std::array<std::array<double, 3>, 7> weights = {
      {{0.5, 0.5, 0},
       {0, 0.5, 0.5},
       {0.5, 0, 0.5},
       {1.0 / 3, 1.0 / 3, 1.0 / 3},
       {2.0 / 3, 1.0 / 6, 1.0 / 6},
       {1.0 / 6, 2.0 / 3, 1.0 / 6},
       {1.0 / 6, 1.0 / 6, 2.0 / 3}}};
  std::vector<std::array<double, 3>> samples;
  for (const auto& l : weights) {
    std::array<double, 3> q{};
    for (int x = 0; x < 3; ++x) {
      q[x] = l[0] * p[0][x] + l[1] * p[1][x] + l[2] * p[2][x];
    }
    samples.push_back(q);
  }
  return samples;
}

TEST(TessellateFace, PlaneSquareWithHoleHasTheAreaTrimsAndTopology) {
  constexpr double r = 0.25;
  const trim_testing::PlaneWithHole shape(r, 0.5, 0.5);
  ASSERT_TRUE(shape.face.ok()) << shape.face.status();
  const double tolerance = 1e-4;
  absl::StatusOr<FaceMesh> mesh =
      TessellateFace(*shape.face, {.tolerance = tolerance});
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  const size_t vertex_count = mesh->uv.size() / 2;
  ASSERT_GT(vertex_count, 3u);
  // Every vertex inside or on the trims; the hole's vertices on the circle.
  absl::StatusOr<std::vector<PointLocation>> where =
      ClassifyPoints(*shape.face, mesh->uv, 1e-12);
  ASSERT_TRUE(where.ok()) << where.status();
  size_t on_circle = 0;
  for (size_t v = 0; v < vertex_count; ++v) {
    EXPECT_NE((*where)[v], PointLocation::kOutside) << v;
    const double u = mesh->uv[2 * v], w = mesh->uv[2 * v + 1];
    const double distance = std::hypot(u - 0.5, w - 0.5);
    if (distance < 0.3) {
      EXPECT_NEAR(distance, r, 1e-12) << v;
      ++on_circle;
    }
    // The plane: S(u, v) = (u, v, 0) exactly.
    EXPECT_NEAR(mesh->vertices[3 * v], u, 1e-15);
    EXPECT_NEAR(mesh->vertices[3 * v + 1], w, 1e-15);
    EXPECT_EQ(mesh->vertices[3 * v + 2], 0.0);
  }
  // Chords of the circle within tolerance / 2: at least pi / acos(1 - t/2r).
  EXPECT_GE(on_circle,
            static_cast<size_t>(kPi / std::acos(1 - tolerance / (2 * r))));
  // The area: the polygon's lies between the face's and the face's plus
  // the sagittas' (the circle's length times tolerance / 2).
  double area = 0.0;
  for (size_t t = 0; t < mesh->triangles.size(); t += 3) {
    EXPECT_GT(UvCross(*mesh, t), 0.0) << t;
    area += TriangleArea(Vertex(*mesh, mesh->triangles[t]),
                         Vertex(*mesh, mesh->triangles[t + 1]),
                         Vertex(*mesh, mesh->triangles[t + 2]));
  }
  const double exact = 1 - kPi * r * r;
  EXPECT_GE(area, exact - 1e-12);
  EXPECT_LE(area, exact + 2 * kPi * r * tolerance / 2);
  // Each edge at most twice; those used once are the boundary: the square's
  // sides and the circle's chords, two per boundary vertex.
  const std::map<std::pair<uint32_t, uint32_t>, int> edges = Edges(*mesh);
  std::map<uint32_t, int> boundary_degree;
  for (const auto& [edge, uses] : edges) {
    EXPECT_LE(uses, 2);
    if (uses == 1) {
      ++boundary_degree[edge.first];
      ++boundary_degree[edge.second];
      const double* a = &mesh->uv[2 * edge.first];
      const double* b = &mesh->uv[2 * edge.second];
      const bool on_square = (a[0] == b[0] && (a[0] == 0 || a[0] == 1)) ||
                             (a[1] == b[1] && (a[1] == 0 || a[1] == 1));
      const bool on_hole =
          std::abs(std::hypot(a[0] - 0.5, a[1] - 0.5) - r) < 1e-12 &&
          std::abs(std::hypot(b[0] - 0.5, b[1] - 0.5) - r) < 1e-12;
      EXPECT_TRUE(on_square || on_hole) << a[0] << " " << a[1];
    }
  }
  for (const auto& [vertex, degree] : boundary_degree) {
    EXPECT_EQ(degree, 2) << vertex;
  }
  // Euler: a disk with one hole.
  const int64_t euler = static_cast<int64_t>(vertex_count) -
                        static_cast<int64_t>(edges.size()) +
                        static_cast<int64_t>(mesh->triangles.size() / 3);
  EXPECT_EQ(euler, 0);
  EXPECT_LE(mesh->deviation_bound, tolerance);
  EXPECT_GT(mesh->min_angle_degrees, 0.0);
}

// A quarter cylinder trimmed to a window with a round hole.
struct CylinderFace {
  explicit CylinderFace(bool reversed = false)
      : data(trim_testing::QuarterCylinder(kRadius, kHeight)),
        surface(*BezierSurface::Create(data.bezier_view())),
        window(Square(0.1, 0.05, 0.9, 0.95)),
        hole(ClockwiseCircle(0.15, 0.5, 0.5)),
        face(TrimmedSurface::Create({.surface = surface,
                                     .outer = LoopOf(window),
                                     .holes = {LoopOf(hole)},
                                     .reversed = reversed},
                                    1e-9)) {}
  SurfaceData data;
  Surface surface;
  std::vector<BezierCurveData> window;
  BSplineCurveData hole;
  absl::StatusOr<TrimmedSurface> face;
};

// LargestDeviation returns the largest distance to the cylinder of the
// triangles' samples, checking that each sample's nearest cylinder point
// and each centroid are in the face.
using NearestUv = std::array<double, 2> (*)(const std::array<double, 3>&);

// QuarterUv returns the (u, v) of the quarter cylinder's point nearest q.
std::array<double, 2> QuarterUv(const std::array<double, 3>& q) {
  return {ArcParameter(std::atan2(q[1], q[0])), q[2] / kHeight};
}

double LargestDeviation(const TrimmedSurface& face, const FaceMesh& mesh,
                        double tolerance, NearestUv nearest = QuarterUv) {
  double largest = 0.0;
  std::vector<double> nearest_uv;
  std::vector<double> centroids;
  for (size_t t = 0; t < mesh.triangles.size(); t += 3) {
    const double* p[3];
    for (int k = 0; k < 3; ++k) p[k] = Vertex(mesh, mesh.triangles[t + k]);
    for (const std::array<double, 3>& q : TriangleSamples(p)) {
      largest = std::max(largest, std::abs(std::hypot(q[0], q[1]) - kRadius));
      const std::array<double, 2> uv = nearest(q);
      nearest_uv.insert(nearest_uv.end(), {uv[0], uv[1]});
    }
    double u = 0, v = 0;
    for (int k = 0; k < 3; ++k) {
      u += mesh.uv[2 * mesh.triangles[t + k]] / 3;
      v += mesh.uv[2 * mesh.triangles[t + k] + 1] / 3;
    }
    centroids.insert(centroids.end(), {u, v});
  }
  // The parametrization moves at least kRadius / 2 per unit of u and
  // kHeight per unit of v: a 3D tolerance is at most 2 / kRadius of it in
  // (u, v).
  for (const std::vector<double>* uv : {&nearest_uv, &centroids}) {
    absl::StatusOr<std::vector<PointLocation>> where =
        ClassifyPoints(face, *uv, 2 * tolerance / kRadius);
    EXPECT_TRUE(where.ok()) << where.status();
    if (!where.ok()) continue;
    for (size_t k = 0; k < where->size(); ++k) {
      EXPECT_NE((*where)[k], PointLocation::kOutside)
          << (*uv)[2 * k] << " " << (*uv)[2 * k + 1];
    }
  }
  return largest;
}

TEST(TessellateFace, CylinderWindowWithHoleStaysWithinTolerance) {
  const CylinderFace shape;
  ASSERT_TRUE(shape.face.ok()) << shape.face.status();
  size_t previous_vertices = 0;
  for (const double tolerance : {1e-2, 1e-3, 1e-4}) {
    absl::StatusOr<FaceMesh> mesh =
        TessellateFace(*shape.face, {.tolerance = tolerance});
    ASSERT_TRUE(mesh.ok()) << mesh.status();
    const size_t vertex_count = mesh->uv.size() / 2;
    for (size_t v = 0; v < vertex_count; ++v) {
      const double* p = Vertex(*mesh, static_cast<uint32_t>(v));
      EXPECT_NEAR(std::hypot(p[0], p[1]), kRadius, 1e-12) << v;
      // Outward unit normals (S_u x S_v, the face not reversed).
      const double* n = &mesh->normals[3 * v];
      EXPECT_NEAR((n[0] * p[0] + n[1] * p[1]) / kRadius, 1.0, 1e-12);
      EXPECT_NEAR(n[2], 0.0, 1e-12);
    }
    for (size_t t = 0; t < mesh->triangles.size(); t += 3) {
      EXPECT_GT(UvCross(*mesh, t), 0.0) << t;
    }
    // A disk with one hole: each edge at most twice, V - E + F = 0.
    const std::map<std::pair<uint32_t, uint32_t>, int> edges = Edges(*mesh);
    for (const auto& [edge, uses] : edges) EXPECT_LE(uses, 2);
    EXPECT_EQ(static_cast<int64_t>(vertex_count) -
                  static_cast<int64_t>(edges.size()) +
                  static_cast<int64_t>(mesh->triangles.size() / 3),
              0);
    const double deviation = LargestDeviation(*shape.face, *mesh, tolerance);
    EXPECT_LE(deviation, tolerance);
    EXPECT_LE(mesh->deviation_bound, tolerance);
    EXPECT_GT(vertex_count, previous_vertices);
    previous_vertices = vertex_count;
    std::cout << "tolerance " << tolerance << ": " << vertex_count
              << " vertices, " << mesh->triangles.size() / 3
              << " triangles, measured deviation " << deviation << ", bound "
              << mesh->deviation_bound << ", min angle "
              << mesh->min_angle_degrees << " degrees\n";
  }
}

TEST(TessellateFace, ReversedFlipsNormalsAndWinding) {
  const CylinderFace forward(false), backward(true);
  ASSERT_TRUE(forward.face.ok() && backward.face.ok());
  absl::StatusOr<FaceMesh> a =
      TessellateFace(*forward.face, {.tolerance = 1e-3});
  absl::StatusOr<FaceMesh> b =
      TessellateFace(*backward.face, {.tolerance = 1e-3});
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_EQ(a->uv, b->uv);
  ASSERT_EQ(a->triangles.size(), b->triangles.size());
  for (size_t k = 0; k < a->normals.size(); ++k) {
    EXPECT_EQ(b->normals[k], -a->normals[k]);
  }
  for (size_t t = 0; t < a->triangles.size(); t += 3) {
    EXPECT_EQ(b->triangles[t], a->triangles[t]);
    EXPECT_EQ(b->triangles[t + 1], a->triangles[t + 2]);
    EXPECT_EQ(b->triangles[t + 2], a->triangles[t + 1]);
    // Counter-clockwise about the face's normal in 3D.
    const double* p[3];
    for (int k = 0; k < 3; ++k) p[k] = Vertex(*b, b->triangles[t + k]);
    const double e1[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1],
                          p[1][2] - p[0][2]};
    const double e2[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1],
                          p[2][2] - p[0][2]};
    const double cross[3] = {e1[1] * e2[2] - e1[2] * e2[1],
                             e1[2] * e2[0] - e1[0] * e2[2],
                             e1[0] * e2[1] - e1[1] * e2[0]};
    const double* n = &b->normals[3 * b->triangles[t]];
    EXPECT_GT(cross[0] * n[0] + cross[1] * n[1] + cross[2] * n[2], 0.0);
  }
}

TEST(TessellateFace, BadOptionsAreNamed) {
  const CylinderFace shape;
  ASSERT_TRUE(shape.face.ok());
  for (const double tolerance :
       {0.0, -1e-3, std::numeric_limits<double>::quiet_NaN()}) {
    const absl::Status status =
        TessellateFace(*shape.face, {.tolerance = tolerance}).status();
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
    EXPECT_EQ(FieldPathOf(status), "tolerance");
  }
  const absl::Status status =
      TessellateFace(*shape.face, {.tolerance = 1e-4, .max_vertices = 50})
          .status();
  EXPECT_EQ(status.code(), absl::StatusCode::kResourceExhausted);
  EXPECT_EQ(FieldPathOf(status), "max_vertices");
}

// The paraboloid S(u, v) = (u, v, u^2 + v^2) as a biquadratic B-spline
// with knots at 1/2 (four pieces, C1 across them): the control points of u
// are the Greville abscissae and those of u^2 the products t_{i+1} t_{i+2}.
SurfaceData Paraboloid() {
  const double greville[4] = {0, 0.25, 0.75, 1};
  const double square[4] = {0, 0, 0.5, 1};
  SurfaceData paraboloid{.degree_u = 2,
                         .degree_v = 2,
                         .dimension = 3,
                         .count_u = 4,
                         .count_v = 4,
                         .knots_u = {0, 0, 0, 0.5, 1, 1, 1},
                         .knots_v = {0, 0, 0, 0.5, 1, 1, 1}};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      paraboloid.coordinates.insert(
          paraboloid.coordinates.end(),
          {greville[i], greville[j], square[i] + square[j]});
    }
  }
  return paraboloid;
}

TEST(TessellateFace, ParaboloidAcrossKnotLinesStaysWithinTolerance) {
  // The vertical gap z - (x^2 + y^2) of a point over the surface bounds its
  // distance; linear interpolation's gap is sum_i lambda_i |x_i - x|^2, at
  // most the squared circumradius: the bound is exact here (A = B = 2).
  const SurfaceData data = Paraboloid();
  const Surface surface = *BSplineSurface::Create(data.bspline_view());
  const BSplineCurveData hole = ClockwiseCircle(0.2, 0.5, 0.5);
  absl::StatusOr<TrimmedSurface> face = TrimmedSurface::Create(
      {.surface = surface, .outer = std::nullopt, .holes = {LoopOf(hole)}},
      1e-9);
  ASSERT_TRUE(face.ok()) << face.status();
  for (const double tolerance : {1e-3, 1e-4}) {
    absl::StatusOr<FaceMesh> mesh =
        TessellateFace(*face, {.tolerance = tolerance});
    ASSERT_TRUE(mesh.ok()) << mesh.status();
    double largest = 0.0;
    for (size_t t = 0; t < mesh->triangles.size(); t += 3) {
      const double* p[3];
      for (int k = 0; k < 3; ++k) p[k] = Vertex(*mesh, mesh->triangles[t + k]);
      for (const std::array<double, 3>& q : TriangleSamples(p)) {
        largest = std::max(largest, q[2] - (q[0] * q[0] + q[1] * q[1]));
      }
    }
    for (size_t v = 0; v < mesh->uv.size() / 2; ++v) {
      const double* p = Vertex(*mesh, static_cast<uint32_t>(v));
      EXPECT_NEAR(p[2], p[0] * p[0] + p[1] * p[1], 1e-14);
    }
    EXPECT_LE(largest, tolerance);
    EXPECT_LE(mesh->deviation_bound, tolerance);
    std::cout << "paraboloid, tolerance " << tolerance << ": "
              << mesh->uv.size() / 2 << " vertices, largest gap " << largest
              << ", min angle " << mesh->min_angle_degrees << " degrees\n";
  }
}

TEST(TessellateFace, CancelledTokenStopsTheWork) {
  const CylinderFace shape;
  ASSERT_TRUE(shape.face.ok());
  CancellationToken token;
  token.Cancel();
  EXPECT_EQ(
      TessellateFace(*shape.face, {.tolerance = 1e-3}, &token).status().code(),
      absl::StatusCode::kCancelled);
}

// FullCylinderUv returns the (u, v) of the point of testing_util::Revolve's
// cylinder (u along the axis to kHeight, v around it in four quarter arcs)
// nearest q.
std::array<double, 2> FullCylinderUv(const std::array<double, 3>& q) {
  double theta = std::atan2(q[1], q[0]);
  if (theta < 0) theta += 2 * kPi;
  const double quarter = std::min(3.0, std::floor(theta / (kPi / 2)));
  return {q[2] / kHeight,
          (quarter + ArcParameter(theta - quarter * kPi / 2)) / 4};
}

TEST(TessellateFace, FullCylinderAcrossItsC0KnotLinesStaysWithinTolerance) {
  // The 9-point NURBS circle's homogeneous form is only C0 at its double
  // knots v = 1/4, 1/2, 3/4: no triangle may lie across them.
  const SurfaceData cylinder = testing_util::Revolve(
      {{kRadius, 0, 1}, {kRadius, 1, 1}, {kRadius, 2, 1}}, {0, 0, 0, 1, 1, 1});
  const Surface surface = *BSplineSurface::Create(cylinder.bspline_view());
  const trim_testing::WindowWithHole shape(surface);
  const absl::StatusOr<TrimmedSurface>& face = shape.face;
  ASSERT_TRUE(face.ok()) << face.status();
  for (const double tolerance : {1e-2, 1e-3}) {
    absl::StatusOr<FaceMesh> mesh =
        TessellateFace(*face, {.tolerance = tolerance});
    ASSERT_TRUE(mesh.ok()) << mesh.status();
    for (size_t v = 0; v < mesh->uv.size() / 2; ++v) {
      const double* p = Vertex(*mesh, static_cast<uint32_t>(v));
      EXPECT_NEAR(std::hypot(p[0], p[1]), kRadius, 1e-12) << v;
    }
    for (size_t t = 0; t < mesh->triangles.size(); t += 3) {
      double lo = 1, hi = 0;
      for (int k = 0; k < 3; ++k) {
        const double v = mesh->uv[2 * mesh->triangles[t + k] + 1];
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
      for (const double line : {0.25, 0.5, 0.75}) {
        EXPECT_FALSE(lo < line && line < hi) << t;
      }
    }
    const double deviation =
        LargestDeviation(*face, *mesh, tolerance, FullCylinderUv);
    EXPECT_LE(deviation, tolerance);
    EXPECT_LE(mesh->deviation_bound, tolerance);
    std::cout << "full cylinder, tolerance " << tolerance << ": "
              << mesh->uv.size() / 2 << " vertices, measured deviation "
              << deviation << ", min angle " << mesh->min_angle_degrees
              << " degrees\n";
  }
}

}  // namespace
}  // namespace freeform
