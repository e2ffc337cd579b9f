// Split, knot insertion, decomposition, subdivision and tessellation
// through the in-process server.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <map>
#include <memory>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "../core/shapes.h"
#include "../core/test_util.h"
#include "geometry_out.h"
#include "in_process_server.h"
#include "teapot.h"

namespace freeform::server {
namespace {

using ::testing::DoubleNear;
using ::testing::Pointwise;
using ::testing::StartsWith;

std::vector<double> Values(const google::protobuf::RepeatedField<double>& f) {
  return {f.begin(), f.end()};
}

class RefinementTest : public InProcessServerTest {};

// Splitting at t gives P_0^0..P_0^n on the left and P_0^n..P_n^0 on the
// right (docs/references.md, 'de Casteljau evaluation and subdivision').
TEST_F(RefinementTest, SplitsTheWorkedCubic) {
  v1::SplitCurveRequest request;
  v1::Points* points =
      request.mutable_curve()->mutable_bezier()->mutable_control_points();
  points->set_dimension(2);
  Append(points->mutable_coordinates(), {0, 0, 1, 2, 3, 2, 4, 0});
  request.add_parameters(0.5);
  absl::StatusOr<v1::SplitCurveResponse> split = client_->SplitCurve(request);
  ASSERT_TRUE(split.ok()) << split.status();
  ASSERT_EQ(split->pieces_size(), 2);
  EXPECT_THAT(Values(split->pieces(0).bezier().control_points().coordinates()),
              Pointwise(DoubleNear(1e-15),
                        std::vector<double>{0, 0, 0.5, 1, 1.25, 1.5, 2, 1.5}));
  EXPECT_THAT(Values(split->pieces(1).bezier().control_points().coordinates()),
              Pointwise(DoubleNear(1e-15),
                        std::vector<double>{2, 1.5, 2.75, 1.5, 3.5, 1, 4, 0}));
  request.set_parameters(0, 1.5);
  ExpectInvalid(client_->SplitCurve(request).status(), "parameters[0]", true);
}

// The half circle with knot 1/2 inserted: points (1,0), (1,1), (-1,1),
// (-1,0) with weights 1, 1/2, 1/2, 1 (Q_0^w = P_0^w keeps the weight 1;
// docs/references.md, 'Worked example: the half circle with a point at
// infinity').
TEST_F(RefinementTest, InsertsAKnotIntoTheHalfCircle) {
  v1::InsertKnotsRequest request;
  v1::BSplineCurve* bspline = request.mutable_curve()->mutable_bspline();
  bspline->set_degree(2);
  bspline->mutable_control_points()->set_dimension(2);
  Append(bspline->mutable_control_points()->mutable_coordinates(),
         {1, 0, 0, 1, -1, 0});
  Append(bspline->mutable_knots(), {0, 0, 0, 1, 1, 1});
  Append(bspline->mutable_weights(), {1, 0, 1});
  request.add_knots(0.5);
  absl::StatusOr<v1::InsertKnotsResponse> refined =
      client_->InsertCurveKnots(request);
  ASSERT_TRUE(refined.ok()) << refined.status();
  EXPECT_THAT(Values(refined->curve().bspline().control_points().coordinates()),
              Pointwise(DoubleNear(1e-15),
                        std::vector<double>{1, 0, 1, 1, -1, 1, -1, 0}));
  EXPECT_THAT(
      Values(refined->curve().bspline().weights()),
      Pointwise(DoubleNear(1e-15), std::vector<double>{1, 0.5, 0.5, 1}));
  EXPECT_THAT(
      Values(refined->curve().bspline().knots()),
      Pointwise(DoubleNear(0), std::vector<double>{0, 0, 0, 0.5, 1, 1, 1}));
  // Beyond the degree's multiplicity, or outside the domain: refused.
  Append(request.mutable_knots(), {0.5, 0.5});
  ExpectInvalid(client_->InsertCurveKnots(request).status(), "knots[", true);
  request.clear_knots();
  request.add_knots(2.0);
  ExpectInvalid(client_->InsertCurveKnots(request).status(), "knots[0]", true);
}

TEST_F(RefinementTest, DecomposesTheNurbsCircle) {
  v1::DecomposeCurveRequest request;
  v1::BSplineCurve* bspline = request.mutable_curve()->mutable_bspline();
  bspline->set_degree(2);
  bspline->mutable_control_points()->set_dimension(2);
  Append(bspline->mutable_control_points()->mutable_coordinates(),
         {1, 0, 1, 1, 0, 1, -1, 1, -1, 0, -1, -1, 0, -1, 1, -1, 1, 0});
  Append(bspline->mutable_knots(),
         {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1});
  const double h = std::numbers::sqrt2 / 2;
  Append(bspline->mutable_weights(), {1, h, 1, h, 1, h, 1, h, 1});
  absl::StatusOr<v1::DecomposeCurveResponse> pieces =
      client_->DecomposeCurve(request);
  ASSERT_TRUE(pieces.ok()) << pieces.status();
  ASSERT_EQ(pieces->segments_size(), 4);
  EXPECT_THAT(
      Values(pieces->breakpoints()),
      Pointwise(DoubleNear(0), std::vector<double>{0, 0.25, 0.5, 0.75, 1}));
  for (const v1::Curve& segment : pieces->segments()) {
    v1::EvaluateCurveRequest evaluate;
    *evaluate.mutable_curve() = segment;
    evaluate.mutable_parameters()->mutable_range()->set_count(101);
    absl::StatusOr<CurveSamples> samples = client_->EvaluateCurve(evaluate);
    ASSERT_TRUE(samples.ok()) << samples.status();
    for (size_t r = 0; r < samples->count; ++r) {
      const auto p = samples->Point(0, r);
      EXPECT_NEAR(std::hypot(p[0], p[1]), 1.0, 1e-14);
    }
  }
}

TEST_F(RefinementTest, ChaikinCutsCorners) {
  v1::SubdivideRequest request;
  request.mutable_polygon()->set_dimension(2);
  Append(request.mutable_polygon()->mutable_coordinates(),
         {0, 0, 4, 0, 4, 4, 0, 4});
  request.set_closed(true);
  request.set_scheme(v1::SUBDIVISION_SCHEME_CHAIKIN);
  request.set_levels(1);
  absl::StatusOr<v1::SubdivideResponse> result =
      client_->SubdividePolygon(request);
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_THAT(Values(result->polygon().coordinates()),
              Pointwise(DoubleNear(1e-15),
                        std::vector<double>{1, 0, 3, 0, 4, 1, 4, 3, 3, 4, 1, 4,
                                            0, 3, 0, 1}));
  request.set_levels(0);
  ExpectInvalid(client_->SubdividePolygon(request).status(), "levels", true);
}

TEST_F(RefinementTest, TessellatesCurvesWithinTolerance) {
  v1::TessellateCurveRequest request;
  v1::Points* points =
      request.mutable_curve()->mutable_bezier()->mutable_control_points();
  points->set_dimension(2);
  Append(points->mutable_coordinates(), {0, 0, 1, 2, 3, 2, 4, 0});
  request.set_tolerance(1e-4);
  absl::StatusOr<v1::TessellateCurveResponse> polyline =
      client_->TessellateCurve(request);
  ASSERT_TRUE(polyline.ok()) << polyline.status();
  ASSERT_GT(polyline->parameters_size(), 10);
  EXPECT_EQ(polyline->parameters(0), 0.0);
  EXPECT_EQ(polyline->parameters(polyline->parameters_size() - 1), 1.0);
  request.set_max_points(5);
  EXPECT_EQ(client_->TessellateCurve(request).status().code(),
            absl::StatusCode::kResourceExhausted);
  request.set_tolerance(0);
  ExpectInvalid(client_->TessellateCurve(request).status(), "tolerance", true);
  EXPECT_EQ(client_->TessellateCurve(request).status().message(),
            "tolerance: must be positive and finite, got 0");
  request.set_tolerance(-INFINITY);
  EXPECT_EQ(client_->TessellateCurve(request).status().message(),
            "tolerance: must be positive and finite, got -inf");
}

TEST_F(RefinementTest, SplitsPatches) {
  v1::SplitSurfaceRequest request;
  v1::ControlNet* net =
      request.mutable_surface()->mutable_bezier()->mutable_control_net();
  net->set_dimension(3);
  net->set_count_u(3);
  net->set_count_v(3);
  Append(net->mutable_coordinates(), {0, 0, 0, 2, 0, 0, 4, 0, 0,  //
                                      0, 2, 0, 2, 2, 0, 4, 2, 2,  //
                                      0, 4, 0, 2, 4, 4, 4, 4, 4});
  request.set_direction(v1::SURFACE_DIRECTION_U);
  request.set_parameter(0.5);
  absl::StatusOr<v1::SplitSurfaceResponse> pieces =
      client_->SplitSurface(request);
  ASSERT_TRUE(pieces.ok()) << pieces.status();
  ASSERT_EQ(pieces->pieces_size(), 2);
  // The bi-quadratic patch's S(1/2, 1/2) = (2, 2, 1) (docs/references.md,
  // 'Worked example: the bi-quadratic patch at (1/2, 1/2)') is the first
  // piece's S(1, 1/2).
  v1::EvaluateSurfaceRequest evaluate;
  *evaluate.mutable_surface() = pieces->pieces(0);
  Append(evaluate.mutable_parameters()->mutable_points()->mutable_uv(),
         {1.0, 0.5});
  absl::StatusOr<SurfaceEvaluation> at = client_->EvaluateSurface(evaluate);
  ASSERT_TRUE(at.ok()) << at.status();
  EXPECT_THAT(at->partials[0].values,
              Pointwise(DoubleNear(1e-15), std::vector<double>{2, 2, 1}));
  request.set_direction(v1::SURFACE_DIRECTION_UNSPECIFIED);
  ExpectInvalid(client_->SplitSurface(request).status(), "direction", true);
}

// The teapot meshed by the server: stream and unary agree, and the welded
// mesh has no edge used by more than two triangles.
TEST_F(RefinementTest, TessellatesTheTeapot) {
  v1::TessellateSurfaceRequest request = TeapotRequest();
  ASSERT_EQ(request.surfaces_size(), 32);
  request.set_tolerance(1e-3);
  request.set_normals(true);
  absl::StatusOr<v1::TessellateSurfaceResponse> mesh =
      client_->TessellateSurfaces(request);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  const size_t vertices = mesh->vertices().coordinates_size() / 3;
  EXPECT_GT(vertices, 1000u);
  std::map<std::pair<uint32_t, uint32_t>, int> edges;
  for (int t = 0; t < mesh->triangles_size(); t += 3) {
    for (int e = 0; e < 3; ++e) {
      const uint32_t a = mesh->triangles(t + e);
      const uint32_t b = mesh->triangles(t + (e + 1) % 3);
      ASSERT_LT(a, vertices);
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  }
  for (const auto& [edge, uses] : edges) EXPECT_LE(uses, 2);
  for (int i = 0; i < mesh->normals().coordinates_size(); i += 3) {
    const auto& n = mesh->normals().coordinates();
    EXPECT_NEAR(std::hypot(n[i], n[i + 1], n[i + 2]), 1.0, 1e-12);
  }
  request.set_tolerance(-1);
  ExpectInvalid(client_->TessellateSurfaces(request).status(), "tolerance",
                true);
}

// Lagrange and Hermite curves are tessellated through their Bezier pieces:
// a Lagrange curve through (t, t^2) is the parabola y = x^2 and a Hermite
// curve with the values and slopes of (t, t^3) is y = x^3, so the distance
// to a point of it bounds the distance from every polyline point to it.
TEST_F(RefinementTest, TessellatesLagrangeAndHermiteCurves) {
  constexpr double kTolerance = 1e-4;
  v1::TessellateCurveRequest lagrange;
  v1::LagrangeCurve* parabola = lagrange.mutable_curve()->mutable_lagrange();
  parabola->mutable_points()->set_dimension(2);
  for (const double t : {-1.0, -0.2, 0.5, 1.0}) {
    Append(parabola->mutable_points()->mutable_coordinates(), {t, t * t});
    parabola->add_nodes(t);
  }
  lagrange.set_tolerance(kTolerance);
  v1::TessellateCurveRequest hermite;
  v1::HermiteCurve* cubic = hermite.mutable_curve()->mutable_hermite();
  cubic->mutable_points()->set_dimension(2);
  cubic->mutable_tangents()->set_dimension(2);
  for (const double t : {-1.0, 0.0, 0.3, 1.0}) {
    Append(cubic->mutable_points()->mutable_coordinates(), {t, t * t * t});
    Append(cubic->mutable_tangents()->mutable_coordinates(), {1.0, 3 * t * t});
    cubic->add_nodes(t);
  }
  hermite.set_tolerance(kTolerance);
  const std::pair<v1::TessellateCurveRequest*, int> cases[] = {{&lagrange, 2},
                                                               {&hermite, 3}};
  for (const auto& [request, power] : cases) {
    absl::StatusOr<v1::TessellateCurveResponse> polyline =
        client_->TessellateCurve(*request);
    ASSERT_TRUE(polyline.ok()) << polyline.status();
    const auto& xy = polyline->points().coordinates();
    ASSERT_GT(polyline->parameters_size(), 10);
    EXPECT_EQ(polyline->parameters(0), -1.0);
    EXPECT_EQ(polyline->parameters(polyline->parameters_size() - 1), 1.0);
    for (int k = 0; k < polyline->parameters_size(); ++k) {
      // Each vertex is the curve point at its parameter, (t, t^power).
      const double t = polyline->parameters(k);
      EXPECT_NEAR(xy[2 * k], t, 1e-15);
      EXPECT_NEAR(xy[2 * k + 1], std::pow(t, power), 1e-14);
      if (k == 0) continue;
      EXPECT_GT(t, polyline->parameters(k - 1));
      for (const double f : {0.25, 0.5, 0.75}) {
        const double x = (1 - f) * xy[2 * k - 2] + f * xy[2 * k];
        const double y = (1 - f) * xy[2 * k - 1] + f * xy[2 * k + 1];
        EXPECT_LE(testing_util::DistanceToPowerCurve(x, y, power), kTolerance)
            << k;
      }
    }
  }
}

// A request to mesh one surface (NurbsTorus, NurbsSphere of
// tests/core/shapes.h).
v1::TessellateSurfaceRequest MeshRequestOf(const SurfaceData& surface) {
  v1::TessellateSurfaceRequest request;
  ToProto(surface, *request.add_surfaces());
  return request;
}

// The torus meshed by the server: every vertex on the torus, and the mesh
// closed, every edge used by exactly two triangles.
TEST_F(RefinementTest, TessellatesAClosedNurbsTorus) {
  v1::TessellateSurfaceRequest request =
      MeshRequestOf(testing_util::NurbsTorus(3.0, 1.0));
  request.set_tolerance(1e-3);
  request.set_normals(true);
  absl::StatusOr<v1::TessellateSurfaceResponse> mesh =
      client_->TessellateSurfaces(request);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  const auto& xyz = mesh->vertices().coordinates();
  const size_t vertices = static_cast<size_t>(xyz.size() / 3);
  ASSERT_EQ(mesh->uv_size(), static_cast<int>(2 * vertices));
  for (size_t r = 0; r < vertices; ++r) {
    const double* p = &xyz[static_cast<int>(3 * r)];
    EXPECT_NEAR(std::hypot(std::hypot(p[0], p[1]) - 3.0, p[2]), 1.0, 1e-12);
  }
  std::map<std::pair<uint32_t, uint32_t>, int> edges;
  for (int t = 0; t < mesh->triangles_size(); t += 3) {
    for (int e = 0; e < 3; ++e) {
      const uint32_t a = mesh->triangles(t + e);
      const uint32_t b = mesh->triangles(t + (e + 1) % 3);
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  }
  for (const auto& [edge, uses] : edges) EXPECT_EQ(uses, 2);
  // Closed and of genus 1: V - E + F = 0.
  EXPECT_EQ(static_cast<long>(vertices) - static_cast<long>(edges.size()) +
                mesh->triangles_size() / 3,
            0);

  request.set_max_edge_length(0.5);
  absl::StatusOr<v1::TessellateSurfaceResponse> limited =
      client_->TessellateSurfaces(request);
  ASSERT_TRUE(limited.ok()) << limited.status();
  const auto& lxyz = limited->vertices().coordinates();
  for (int t = 0; t < limited->triangles_size(); t += 3) {
    for (int e = 0; e < 3; ++e) {
      const int a = 3 * static_cast<int>(limited->triangles(t + e));
      const int b = 3 * static_cast<int>(limited->triangles(t + (e + 1) % 3));
      EXPECT_LE(std::hypot(lxyz[a] - lxyz[b], lxyz[a + 1] - lxyz[b + 1],
                           lxyz[a + 2] - lxyz[b + 2]),
                0.5);
    }
  }
  request.set_max_edge_length(0);
  ExpectInvalid(client_->TessellateSurfaces(request).status(),
                "max_edge_length", true);
  request.clear_max_edge_length();
  request.mutable_surfaces(0)->mutable_bspline()->set_weights(40, 0.0);
  ExpectInvalid(client_->TessellateSurfaces(request).status(),
                "surfaces[0].bspline.weights[40]", true);
}

// The angle between the vectors a and b.
double Angle(const double* a, const double* b) {
  const double cross[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                           a[0] * b[1] - a[1] * b[0]};
  return std::atan2(std::hypot(cross[0], cross[1], cross[2]),
                    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

// A sphere meshed within a normal angle by the server: the vertex normals
// are the sphere's exact ones, p / r, and no edge's end normals differ by
// more than the limit; the limit costs vertices, and a cap below them is
// refused naming it.
TEST_F(RefinementTest, TessellatesASphereWithinANormalAngle) {
  constexpr double kRadius = 2.0, kLimit = 0.05;
  v1::TessellateSurfaceRequest request =
      MeshRequestOf(testing_util::NurbsSphere(kRadius));
  request.set_tolerance(1e-2);
  request.set_normals(true);
  absl::StatusOr<v1::TessellateSurfaceResponse> plain =
      client_->TessellateSurfaces(request);
  ASSERT_TRUE(plain.ok()) << plain.status();
  request.set_max_normal_angle(kLimit);
  absl::StatusOr<v1::TessellateSurfaceResponse> mesh =
      client_->TessellateSurfaces(request);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  const auto& xyz = mesh->vertices().coordinates();
  const auto& normals = mesh->normals().coordinates();
  const int vertices = xyz.size() / 3;
  ASSERT_EQ(normals.size(), xyz.size());
  EXPECT_GT(vertices, plain->vertices().coordinates_size() / 3);
  const double sign =
      normals[0] * xyz[0] + normals[1] * xyz[1] + normals[2] * xyz[2] > 0
          ? 1.0
          : -1.0;
  for (int r = 0; r < vertices; ++r) {
    const double* p = &xyz[3 * r];
    EXPECT_NEAR(std::hypot(p[0], p[1], p[2]), kRadius, 1e-12);
    const double outward[3] = {sign * normals[3 * r], sign * normals[3 * r + 1],
                               sign * normals[3 * r + 2]};
    EXPECT_LE(Angle(p, outward), 1e-9) << r;
  }
  double worst = 0.0;
  for (int t = 0; t < mesh->triangles_size(); t += 3) {
    for (int e = 0; e < 3; ++e) {
      const int a = 3 * static_cast<int>(mesh->triangles(t + e));
      const int b = 3 * static_cast<int>(mesh->triangles(t + (e + 1) % 3));
      worst = std::max(worst, Angle(&xyz[a], &xyz[b]));
    }
  }
  EXPECT_LE(worst, kLimit + 1e-9);
  EXPECT_GT(worst, kLimit / 2);

  // Twice the vertices of the plain mesh fit its plan, not the limit's.
  request.set_max_vertices(
      static_cast<uint32_t>(2 * plain->vertices().coordinates_size() / 3));
  const absl::Status capped = client_->TessellateSurfaces(request).status();
  EXPECT_EQ(capped.code(), absl::StatusCode::kResourceExhausted) << capped;
  ASSERT_EQ(FieldViolationsOf(capped).size(), 1u) << capped;
  EXPECT_EQ(FieldViolationsOf(capped)[0].field, "max_normal_angle");
  request.clear_max_vertices();
  for (const double angle : {0.0, -0.1, 4.0, std::nan("")}) {
    request.set_max_normal_angle(angle);
    ExpectInvalid(client_->TessellateSurfaces(request).status(),
                  "max_normal_angle");
  }
}

TEST_F(RefinementTest, TessellatesTriangularAndHermitePatchesTogether) {
  v1::TessellateSurfaceRequest request;
  v1::TriangularBezierPatch* triangle =
      request.add_surfaces()->mutable_triangular_bezier();
  triangle->set_degree(2);
  triangle->mutable_control_points()->set_dimension(3);
  Append(triangle->mutable_control_points()->mutable_coordinates(),
         {0, 0, 0, 1, 0, 1, 2, 0, 0, 0, 1, 1, 1, 1, 1, 0, 2, 0});
  v1::BicubicHermitePatch* hermite =
      request.add_surfaces()->mutable_bicubic_hermite();
  hermite->mutable_positions()->set_dimension(3);
  hermite->mutable_positions()->set_count_u(2);
  hermite->mutable_positions()->set_count_v(2);
  Append(hermite->mutable_positions()->mutable_coordinates(),
         {3, 0, 0, 3, 1, 0, 4, 0, 0, 4, 1, 1});
  for (v1::ControlNet* derivatives :
       {hermite->mutable_derivatives_u(), hermite->mutable_derivatives_v()}) {
    const bool along_u = derivatives == hermite->mutable_derivatives_u();
    derivatives->set_dimension(3);
    derivatives->set_count_u(2);
    derivatives->set_count_v(2);
    for (int k = 0; k < 4; ++k) {
      Append(derivatives->mutable_coordinates(),
             {along_u ? 1.0 : 0.0, along_u ? 0.0 : 1.0, 0.5});
    }
  }
  request.set_tolerance(1e-3);
  absl::StatusOr<v1::TessellateSurfaceResponse> mesh =
      client_->TessellateSurfaces(request);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  std::set<uint32_t> surfaces(mesh->surface_index().begin(),
                              mesh->surface_index().end());
  EXPECT_EQ(surfaces, (std::set<uint32_t>{0, 1}));
  // The triangular patch's vertices have barycentric (u, v) in its domain.
  for (int r = 0; r < mesh->surface_index_size(); ++r) {
    if (mesh->surface_index(r) != 0) continue;
    const double u = mesh->uv(2 * r), v = mesh->uv(2 * r + 1);
    EXPECT_GE(u, 0.0);
    EXPECT_GE(v, 0.0);
    EXPECT_LE(u + v, 1.0 + 1e-15);
  }
  triangle->mutable_control_points()->set_dimension(2);
  triangle->mutable_control_points()->mutable_coordinates()->Truncate(12);
  ExpectInvalid(client_->TessellateSurfaces(request).status(),
                "surfaces[0].triangular_bezier.control_points.dimension", true);
}

}  // namespace
}  // namespace freeform::server
