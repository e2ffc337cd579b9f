// FaceService through the in-process server: the area of a plane square
// with a circular hole against 1 - pi r^2, locations at known distances
// from the circle, evaluation with the face's orientation, and every
// refusal naming its field.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "freeform/v1/face_service.grpc.pb.h"
#include "in_process_server.h"

namespace freeform::server {
namespace {

constexpr double kRadius = 0.25;
constexpr double kCentre = 0.5;

class FaceServiceTest : public InProcessServerTest {};

// The unit square S(u, v) = (u, v, 0) as a bilinear Bezier patch.
void SetPlane(v1::Surface* surface) {
  v1::ControlNet* net = surface->mutable_bezier()->mutable_control_net();
  net->set_dimension(3);
  net->set_count_u(2);
  net->set_count_v(2);
  Append(net->mutable_coordinates(), {0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0});
}

// The NURBS circle of radius r about (cu, cv): nine rational quadratic
// control points, counter-clockwise or (reversed) clockwise.
void SetCircle(v1::Curve* curve, double cu, double cv, double r,
               bool clockwise) {
  const double s = std::numbers::sqrt2 / 2;
  const double unit[9][3] = {{1, 0, 1},  {1, 1, s},  {0, 1, 1},
                             {-1, 1, s}, {-1, 0, 1}, {-1, -1, s},
                             {0, -1, 1}, {1, -1, s}, {1, 0, 1}};
  v1::BSplineCurve* spline = curve->mutable_bspline();
  spline->set_degree(2);
  spline->mutable_control_points()->set_dimension(2);
  for (int k = 0; k < 9; ++k) {
    const double* p = unit[clockwise ? 8 - k : k];
    Append(spline->mutable_control_points()->mutable_coordinates(),
           {cu + r * p[0], cv + r * p[1]});
    spline->add_weights(p[2]);
  }
  Append(spline->mutable_knots(),
         {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1});
}

// A straight 2D segment as a linear Bezier curve.
void SetSegment(v1::Curve* curve, double u0, double v0, double u1, double v1_) {
  v1::Points* points = curve->mutable_bezier()->mutable_control_points();
  points->set_dimension(2);
  Append(points->mutable_coordinates(), {u0, v0, u1, v1_});
}

// The square with a clockwise circular hole of radius kRadius.
v1::TrimmedSurface SquareWithHole() {
  v1::TrimmedSurface face;
  SetPlane(face.mutable_surface());
  SetCircle(face.add_holes()->add_curves(), kCentre, kCentre, kRadius, true);
  return face;
}

void AddPoints(v1::SurfaceParameters* parameters,
               std::initializer_list<double> uv) {
  Append(parameters->mutable_points()->mutable_uv(), uv);
}

TEST_F(FaceServiceTest, AreaOfTheSquareWithACircularHoleIsOneMinusPiRSquared) {
  v1::FaceAreaRequest request;
  *request.mutable_face() = SquareWithHole();
  request.set_tolerance(1e-13);
  absl::StatusOr<v1::FaceAreaResponse> area = client_->FaceArea(request);
  ASSERT_TRUE(area.ok()) << area.status();
  const double exact = 1.0 - std::numbers::pi * kRadius * kRadius;
  EXPECT_NEAR(area->area(), exact, 1e-12);
  EXPECT_TRUE(area->converged());
  EXPECT_LE(area->error_bound(), 1e-13);
  EXPECT_GE(area->error_bound() + 1e-15, std::abs(area->area() - exact));
}

TEST_F(FaceServiceTest, AnAreaToleranceTheWorkCannotReachIsRefused) {
  // A square of side 1e77 at the default absolute tolerance 1e-9: double
  // precision resolves nothing near 1e-9 of an area of 1e154.
  v1::FaceAreaRequest request;
  *request.mutable_face() = SquareWithHole();
  for (double& x : *request.mutable_face()
                        ->mutable_surface()
                        ->mutable_bezier()
                        ->mutable_control_net()
                        ->mutable_coordinates()) {
    x *= 1e77;
  }
  const absl::Status status = client_->FaceArea(request).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kResourceExhausted) << status;
  const std::vector<FieldViolation> violations = FieldViolationsOf(status);
  ASSERT_EQ(violations.size(), 1u) << status;
  EXPECT_EQ(violations[0].field, "tolerance");
}

TEST_F(FaceServiceTest, AWholeDomainFaceHasTheSurfacesArea) {
  v1::FaceAreaRequest request;
  SetPlane(request.mutable_face()->mutable_surface());
  absl::StatusOr<v1::FaceAreaResponse> area = client_->FaceArea(request);
  ASSERT_TRUE(area.ok()) << area.status();
  EXPECT_NEAR(area->area(), 1.0, 1e-12);
}

TEST_F(FaceServiceTest, ClassifiesPointsAtKnownDistancesFromTheHole) {
  v1::ClassifyFacePointsRequest request;
  *request.mutable_face() = SquareWithHole();
  request.set_boundary_tolerance(1e-9);
  const double rim = kCentre + kRadius;
  AddPoints(request.mutable_parameters(),
            {kCentre, kCentre,        // the hole's centre
             0.1, 0.1,                // far inside the face
             rim, kCentre,            // on the circle
             rim + 1e-6, kCentre,     // just outside the hole
             rim - 1e-6, kCentre,     // just inside the hole
             kCentre, rim + 1e-10});  // within the boundary tolerance
  absl::StatusOr<v1::ClassifyFacePointsResponse> answer =
      client_->ClassifyFacePoints(request);
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_THAT(answer->locations(),
              ::testing::ElementsAre(
                  v1::FACE_POINT_OUTSIDE, v1::FACE_POINT_INSIDE,
                  v1::FACE_POINT_ON_BOUNDARY, v1::FACE_POINT_INSIDE,
                  v1::FACE_POINT_OUTSIDE, v1::FACE_POINT_ON_BOUNDARY));
}

TEST_F(FaceServiceTest, AGridIsClassifiedUMajorByTheCirclesEquation) {
  v1::ClassifyFacePointsRequest request;
  *request.mutable_face() = SquareWithHole();
  const int count = 20;
  for (v1::Parameters* axis :
       {request.mutable_parameters()->mutable_grid()->mutable_u(),
        request.mutable_parameters()->mutable_grid()->mutable_v()}) {
    axis->mutable_range()->set_count(count);
  }
  absl::StatusOr<v1::ClassifyFacePointsResponse> answer =
      client_->ClassifyFacePoints(request);
  ASSERT_TRUE(answer.ok()) << answer.status();
  ASSERT_EQ(answer->locations_size(), count * count);
  for (int i = 0; i < count; ++i) {
    for (int j = 0; j < count; ++j) {
      const double u = i / (count - 1.0), v = j / (count - 1.0);
      const double distance = std::hypot(u - kCentre, v - kCentre);
      // No grid point lies within 1e-4 of the circle; the grid's sides lie
      // on the parameter rectangle's edge, the boundary of a face without
      // an outer loop.
      ASSERT_GT(std::abs(distance - kRadius), 1e-4);
      const bool on_edge = i == 0 || j == 0 || i == count - 1 || j == count - 1;
      EXPECT_EQ(answer->locations(i * count + j),
                on_edge              ? v1::FACE_POINT_ON_BOUNDARY
                : distance < kRadius ? v1::FACE_POINT_OUTSIDE
                                     : v1::FACE_POINT_INSIDE)
          << u << ", " << v;
    }
  }
}

TEST_F(FaceServiceTest, EvaluateGivesPointsNormalsOfTheFacesSideAndLocations) {
  for (const bool reversed : {false, true}) {
    v1::EvaluateFaceRequest request;
    *request.mutable_face() = SquareWithHole();
    request.mutable_face()->set_reversed(reversed);
    request.set_normals(true);
    request.set_derivative_order(1);
    AddPoints(request.mutable_parameters(), {0.1, 0.2, 0.5, 0.5});
    absl::StatusOr<v1::EvaluateFaceResponse> answer =
        client_->EvaluateFace(request);
    ASSERT_TRUE(answer.ok()) << answer.status();
    const v1::EvaluateSurfaceResponse& values = answer->values();
    ASSERT_EQ(values.partials_size(), 3);
    const auto near = [](double x) { return ::testing::DoubleNear(x, 1e-15); };
    EXPECT_THAT(values.partials(0).values().coordinates(),
                ::testing::ElementsAre(near(0.1), near(0.2), near(0.0),
                                       near(0.5), near(0.5), near(0.0)));
    const double z = reversed ? -1.0 : 1.0;
    EXPECT_THAT(values.normals().coordinates(),
                ::testing::ElementsAre(0.0, 0.0, z, 0.0, 0.0, z));
    EXPECT_THAT(
        answer->locations(),
        ::testing::ElementsAre(v1::FACE_POINT_INSIDE, v1::FACE_POINT_OUTSIDE));
  }
}

TEST_F(FaceServiceTest, TheMeshOfTheSquareWithAHoleKeepsToTheFace) {
  v1::TessellateFaceRequest request;
  *request.mutable_face() = SquareWithHole();
  request.set_tolerance(1e-4);
  absl::StatusOr<v1::TessellateFaceResponse> mesh =
      client_->TessellateFace(request);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  const auto& xyz = mesh->vertices().coordinates();
  const auto& uv = mesh->uv().coordinates();
  const int vertices = mesh->vertices().coordinates_size() / 3;
  ASSERT_GT(vertices, 20);
  ASSERT_EQ(uv.size(), 2 * vertices);
  ASSERT_EQ(mesh->normals().coordinates_size(), 3 * vertices);
  for (int k = 0; k < vertices; ++k) {
    // S(u, v) = (u, v, 0), normal +z, nothing inside the hole.
    EXPECT_NEAR(xyz[3 * k], uv[2 * k], 1e-15);
    EXPECT_NEAR(xyz[3 * k + 1], uv[2 * k + 1], 1e-15);
    EXPECT_EQ(xyz[3 * k + 2], 0.0);
    EXPECT_NEAR(mesh->normals().coordinates(3 * k + 2), 1.0, 1e-15);
    EXPECT_GE(std::hypot(uv[2 * k] - kCentre, uv[2 * k + 1] - kCentre),
              kRadius - 1e-12);
  }
  // Counter-clockwise in (u, v) (the normal's side), every edge used at
  // most twice, V - E + F = 0 for a square with one hole, and the area
  // between the inscribed polygon's and the square's minus the disk.
  ASSERT_EQ(mesh->triangles_size() % 3, 0);
  std::map<std::pair<uint32_t, uint32_t>, int> edges;
  double area = 0.0;
  for (int t = 0; t < mesh->triangles_size(); t += 3) {
    const uint32_t a = mesh->triangles(t), b = mesh->triangles(t + 1),
                   c = mesh->triangles(t + 2);
    const double signed_area =
        0.5 * ((uv[2 * b] - uv[2 * a]) * (uv[2 * c + 1] - uv[2 * a + 1]) -
               (uv[2 * c] - uv[2 * a]) * (uv[2 * b + 1] - uv[2 * a + 1]));
    EXPECT_GT(signed_area, 0.0);
    area += signed_area;
    for (auto [p, q] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
      ++edges[{std::min(p, q), std::max(p, q)}];
    }
  }
  for (const auto& [edge, uses] : edges) EXPECT_LE(uses, 2);
  const int faces = mesh->triangles_size() / 3;
  EXPECT_EQ(vertices - static_cast<int>(edges.size()) + faces, 0);
  const double exact = 1.0 - std::numbers::pi * kRadius * kRadius;
  EXPECT_GE(area, exact - 1e-12);
  EXPECT_LE(area, exact + 2 * std::numbers::pi * kRadius * 1e-4);
  EXPECT_LE(mesh->deviation_bound(), 1e-4);
  EXPECT_GT(mesh->min_angle_degrees(), 0.0);
}

TEST_F(FaceServiceTest, TessellateRefusesABadToleranceAndATinyCap) {
  v1::TessellateFaceRequest request;
  *request.mutable_face() = SquareWithHole();
  ExpectInvalid(client_->TessellateFace(request).status(), "tolerance");
  request.set_tolerance(1e-4);
  request.set_max_vertices(10);
  const absl::Status status = client_->TessellateFace(request).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kResourceExhausted) << status;
  EXPECT_THAT(std::string(status.message()),
              ::testing::HasSubstr("max_vertices"));
}

TEST_F(FaceServiceTest, AnOpenLoopIsRefusedWithItsGap) {
  v1::FaceAreaRequest request;
  SetPlane(request.mutable_face()->mutable_surface());
  v1::TrimLoop* outer = request.mutable_face()->mutable_outer();
  SetSegment(outer->add_curves(), 0.1, 0.1, 0.9, 0.1);
  SetSegment(outer->add_curves(), 0.9, 0.1, 0.9, 0.9);
  SetSegment(outer->add_curves(), 0.9, 0.9, 0.1, 0.8);  // misses (0.1, 0.9)
  SetSegment(outer->add_curves(), 0.1, 0.9, 0.1, 0.1);
  const absl::StatusOr<v1::FaceAreaResponse> area = client_->FaceArea(request);
  ExpectInvalid(area.status(), "face.outer.curves[3]");
}

TEST_F(FaceServiceTest, AHoleRunningCounterClockwiseIsRefused) {
  v1::FaceAreaRequest request;
  SetPlane(request.mutable_face()->mutable_surface());
  SetCircle(request.mutable_face()->add_holes()->add_curves(), kCentre, kCentre,
            kRadius, /*clockwise=*/false);
  ExpectInvalid(client_->FaceArea(request).status(), "face.holes[0]");
}

TEST_F(FaceServiceTest, CrossingHolesAreRefusedNamingACurve) {
  v1::FaceAreaRequest request;
  SetPlane(request.mutable_face()->mutable_surface());
  SetCircle(request.mutable_face()->add_holes()->add_curves(), 0.4, 0.5, 0.2,
            true);
  SetCircle(request.mutable_face()->add_holes()->add_curves(), 0.6, 0.5, 0.2,
            true);
  ExpectInvalid(client_->FaceArea(request).status(), "face.holes[",
                /*prefix_only=*/true);
}

TEST_F(FaceServiceTest, ATrimOutsideTheDomainIsRefused) {
  v1::FaceAreaRequest request;
  SetPlane(request.mutable_face()->mutable_surface());
  SetCircle(request.mutable_face()->add_holes()->add_curves(), 0.9, 0.5, 0.2,
            true);
  ExpectInvalid(client_->FaceArea(request).status(), "face.holes[0].curves[0]");
}

TEST_F(FaceServiceTest, ATrimThatIsNot2DIsRefused) {
  v1::ClassifyFacePointsRequest request;
  SetPlane(request.mutable_face()->mutable_surface());
  v1::Points* points = request.mutable_face()
                           ->add_holes()
                           ->add_curves()
                           ->mutable_bezier()
                           ->mutable_control_points();
  points->set_dimension(3);
  Append(points->mutable_coordinates(), {0.2, 0.2, 0, 0.8, 0.2, 0});
  AddPoints(request.mutable_parameters(), {0.5, 0.5});
  ExpectInvalid(client_->ClassifyFacePoints(request).status(),
                "face.holes[0].curves[0]");
}

TEST_F(FaceServiceTest, BadTolerancesAndAMissingSurfaceNameTheirFields) {
  {
    v1::FaceAreaRequest request;
    *request.mutable_face() = SquareWithHole();
    request.mutable_face()->set_tolerance(-1.0);
    ExpectInvalid(client_->FaceArea(request).status(), "face.tolerance");
  }
  {
    v1::FaceAreaRequest request;
    *request.mutable_face() = SquareWithHole();
    request.set_tolerance(std::nan(""));
    ExpectInvalid(client_->FaceArea(request).status(), "tolerance");
  }
  {
    v1::FaceAreaRequest request;
    SetCircle(request.mutable_face()->add_holes()->add_curves(), kCentre,
              kCentre, kRadius, true);
    ExpectInvalid(client_->FaceArea(request).status(), "face.surface");
  }
  {
    v1::ClassifyFacePointsRequest request;
    *request.mutable_face() = SquareWithHole();
    request.set_boundary_tolerance(0.0);
    AddPoints(request.mutable_parameters(), {0.5, 0.5});
    ExpectInvalid(client_->ClassifyFacePoints(request).status(),
                  "boundary_tolerance");
  }
  {
    v1::ClassifyFacePointsRequest request;
    *request.mutable_face() = SquareWithHole();
    AddPoints(request.mutable_parameters(), {0.5, 1.5});
    ExpectInvalid(client_->ClassifyFacePoints(request).status(),
                  "parameters.points.uv[1]");
  }
}

}  // namespace
}  // namespace freeform::server
