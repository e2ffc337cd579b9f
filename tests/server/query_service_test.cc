// The query RPCs of CurveService and SurfaceService through a real server:
// worked examples with known answers (the NURBS circle, the twisted cubic, a
// sphere patch, lines and planes), and bad input named by its field path.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "../core/shapes.h"
#include "freeform/v1/curve_service.grpc.pb.h"
#include "freeform/v1/surface_service.grpc.pb.h"
#include "in_process_server.h"

namespace freeform::server {
namespace {

using ::testing::DoubleNear;
using ::testing::ElementsAre;
using ::testing::Pointwise;
using testing_util::NurbsCircle;
using testing_util::SpherePatch;
using testing_util::TwistedCubic;

constexpr double kPi = std::numbers::pi;

v1::Curve CircleMessage(double radius, double cx, double cy) {
  const BSplineCurveData data = NurbsCircle(radius, cx, cy);
  v1::Curve curve;
  v1::BSplineCurve& bspline = *curve.mutable_bspline();
  bspline.set_degree(static_cast<uint32_t>(data.degree));
  bspline.mutable_control_points()->set_dimension(2);
  bspline.mutable_control_points()->mutable_coordinates()->Add(
      data.coordinates.begin(), data.coordinates.end());
  bspline.mutable_knots()->Add(data.knots.begin(), data.knots.end());
  bspline.mutable_weights()->Add(data.weights.begin(), data.weights.end());
  return curve;
}

v1::Curve BezierMessage(int dimension, std::initializer_list<double> points) {
  v1::Curve curve;
  v1::Points& control = *curve.mutable_bezier()->mutable_control_points();
  control.set_dimension(static_cast<uint32_t>(dimension));
  Append(control.mutable_coordinates(), points);
  return curve;
}

v1::Surface SphereMessage(double radius) {
  const SurfaceData data = SpherePatch(radius);
  v1::Surface surface;
  v1::BezierSurface& bezier = *surface.mutable_bezier();
  v1::ControlNet& net = *bezier.mutable_control_net();
  net.set_dimension(3);
  net.set_count_u(3);
  net.set_count_v(3);
  net.mutable_coordinates()->Add(data.coordinates.begin(),
                                 data.coordinates.end());
  bezier.mutable_weights()->Add(data.weights.begin(), data.weights.end());
  return surface;
}

// The unit square of the plane z = 0 as a bilinear patch: S(u, v) =
// (u, v, 0).
v1::Surface UnitSquareMessage() {
  v1::Surface surface;
  v1::ControlNet& net = *surface.mutable_bezier()->mutable_control_net();
  net.set_dimension(3);
  net.set_count_u(2);
  net.set_count_v(2);
  Append(net.mutable_coordinates(), {0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0});
  return surface;
}

using QueryServiceTest = InProcessServerTest;

// The circle of radius 2 about (1, -1): from q = (4, 3) the nearest point is
// (1, -1) + 2 (3, 4) / 5 = (2.2, 0.6) at distance 5 - 2 = 3; from the
// centre every point is at distance 2 (a stretch: incomplete, max_minima
// points); a point on the circle inverts to its own parameter.
TEST_F(QueryServiceTest, ClosestPointsOnTheNurbsCircle) {
  v1::CurveClosestPointRequest request;
  *request.mutable_curve() = CircleMessage(2.0, 1.0, -1.0);
  request.mutable_queries()->set_dimension(2);
  // (3, -1) is the circle's point at t = 0.
  Append(request.mutable_queries()->mutable_coordinates(),
         {4, 3, 1, -1, 3, -1});
  request.mutable_options()->set_max_minima(4);
  absl::StatusOr<v1::ClosestPointResponse> answer = client_->Unary(
      client_->curves(), &v1::CurveService::Stub::ClosestPoint, request);
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_EQ(answer->parameter_count(), 1u);
  EXPECT_THAT(answer->distances(),
              Pointwise(DoubleNear(1e-9), std::vector<double>{3, 2, 0}));
  EXPECT_THAT(answer->minima_counts(), ElementsAre(1, 4, 2));
  EXPECT_THAT(answer->complete(), ElementsAre(true, false, true));
  // Certified: the lower bound is within the tolerance of the distance
  // when the answer is complete (the centre's search stops at its piece
  // budget, with a looser bound).
  for (int r = 0; r < 3; ++r) {
    EXPECT_LE(answer->lower_bounds(r), answer->distances(r));
    if (answer->complete(r)) {
      EXPECT_GE(answer->lower_bounds(r), answer->distances(r) - 1e-9);
    }
  }
  const auto& points = answer->points().coordinates();
  ASSERT_EQ(points.size(), 2 * (1 + 4 + 2));
  EXPECT_NEAR(points[0], 2.2, 1e-9);
  EXPECT_NEAR(points[1], 0.6, 1e-9);
  for (int k = 1; k < 5; ++k) {  // on the circle, 2 from the centre
    EXPECT_NEAR(std::hypot(points[2 * k] - 1, points[2 * k + 1] + 1), 2.0,
                1e-9);
  }
  // (3, -1) is the seam: parameters 0 and 1 are both minima.
  EXPECT_THAT(
      std::vector<double>({answer->parameters(5), answer->parameters(6)}),
      ::testing::UnorderedElementsAre(DoubleNear(0.0, 1e-9),
                                      DoubleNear(1.0, 1e-9)));
}

TEST_F(QueryServiceTest, ClosestPointOnASurfaceInsideAndOnItsBoundary) {
  v1::SurfaceClosestPointRequest request;
  *request.mutable_surface() = UnitSquareMessage();
  request.mutable_queries()->set_dimension(3);
  Append(request.mutable_queries()->mutable_coordinates(),
         {0.3, 0.4, 5, 2, 0.5, 0, -1, -1, 1});
  absl::StatusOr<v1::ClosestPointResponse> answer = client_->Unary(
      client_->surfaces(), &v1::SurfaceService::Stub::ClosestPoint, request);
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_EQ(answer->parameter_count(), 2u);
  EXPECT_THAT(
      answer->distances(),
      Pointwise(DoubleNear(1e-9), std::vector<double>{5, 1, std::sqrt(3.0)}));
  EXPECT_THAT(answer->minima_counts(), ElementsAre(1, 1, 1));
  EXPECT_THAT(
      answer->parameters(),
      Pointwise(DoubleNear(1e-9), std::vector<double>{0.3, 0.4, 1, 0.5, 0, 0}));
}

TEST_F(QueryServiceTest, ClosestPointOnTheSpherePatchIsRadiallyBelow) {
  v1::SurfaceClosestPointRequest request;
  *request.mutable_surface() = SphereMessage(2.0);
  request.mutable_queries()->set_dimension(3);
  // Along the direction (1, 2, 2) / 3, at distance 6 from the centre.
  Append(request.mutable_queries()->mutable_coordinates(), {2, 4, 4});
  absl::StatusOr<v1::ClosestPointResponse> answer = client_->Unary(
      client_->surfaces(), &v1::SurfaceService::Stub::ClosestPoint, request);
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_NEAR(answer->distances(0), 4.0, 1e-9);
  EXPECT_THAT(answer->points().coordinates(),
              Pointwise(DoubleNear(1e-9),
                        std::vector<double>{2.0 / 3, 4.0 / 3, 4.0 / 3}));
}

TEST_F(QueryServiceTest, ClosestPointErrorsNameTheirField) {
  v1::CurveClosestPointRequest request;
  *request.mutable_curve() = CircleMessage(1.0, 0.0, 0.0);
  request.mutable_queries()->set_dimension(3);
  Append(request.mutable_queries()->mutable_coordinates(), {1, 2, 3});
  auto call = [&] {
    return client_
        ->Unary(client_->curves(), &v1::CurveService::Stub::ClosestPoint,
                request)
        .status();
  };
  ExpectInvalid(call(), "queries.dimension");
  request.mutable_queries()->set_dimension(2);
  request.mutable_queries()->mutable_coordinates()->Clear();
  ExpectInvalid(call(), "queries.coordinates", true);
  Append(request.mutable_queries()->mutable_coordinates(), {1, 2});
  request.mutable_options()->set_tolerance(0.0);
  ExpectInvalid(call(), "options.tolerance");
  request.mutable_options()->set_tolerance(-1e-3);
  ExpectInvalid(call(), "options.tolerance");
  request.mutable_options()->clear_tolerance();
  request.mutable_options()->set_separation(NAN);
  ExpectInvalid(call(), "options.separation");
  request.mutable_options()->clear_separation();
  request.mutable_options()->set_max_minima(1025);
  ExpectInvalid(call(), "options.max_minima");
}

// Two lines crossing at their middles, the circle of radius 1 crossed by a
// diameter at t = 1/4 and 3/4 of the line, and a pair that does not meet.
TEST_F(QueryServiceTest, IntersectionsOfCurves) {
  v1::IntersectCurvesRequest request;
  *request.mutable_first() = BezierMessage(2, {0, 0, 2, 2});
  *request.mutable_second() = BezierMessage(2, {0, 2, 2, 0});
  auto call = [&] {
    return client_->Unary(client_->curves(), &v1::CurveService::Stub::Intersect,
                          request);
  };
  absl::StatusOr<v1::IntersectCurvesResponse> answer = call();
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_THAT(answer->first_parameters(), ElementsAre(DoubleNear(0.5, 1e-10)));
  EXPECT_THAT(answer->second_parameters(), ElementsAre(DoubleNear(0.5, 1e-10)));
  EXPECT_THAT(answer->points().coordinates(),
              ElementsAre(DoubleNear(1, 1e-10), DoubleNear(1, 1e-10)));
  EXPECT_TRUE(answer->first_intervals().empty());

  *request.mutable_first() = BezierMessage(2, {-2, 0, 2, 0});
  *request.mutable_second() = CircleMessage(1.0, 0.0, 0.0);
  answer = call();
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_THAT(answer->first_parameters(),
              ElementsAre(DoubleNear(0.25, 1e-10), DoubleNear(0.75, 1e-10)));
  EXPECT_THAT(answer->points().coordinates(),
              Pointwise(DoubleNear(1e-10), std::vector<double>{-1, 0, 1, 0}));

  *request.mutable_first() = BezierMessage(2, {-2, 3, 2, 3});
  answer = call();
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_TRUE(answer->first_parameters().empty());

  *request.mutable_first() = BezierMessage(3, {-2, 0, 0, 2, 0, 0});
  ExpectInvalid(call().status(), "second");
  *request.mutable_first() = BezierMessage(2, {-2, 0, 2, 0});
  request.mutable_options()->set_tolerance(0.0);
  ExpectInvalid(call().status(), "options.tolerance");
}

// The overlap of two pieces of one line comes back as one pair of
// intervals, not as points.
TEST_F(QueryServiceTest, OverlappingCurvesGiveAnInterval) {
  v1::IntersectCurvesRequest request;
  *request.mutable_first() = BezierMessage(2, {0, 0, 2, 0});
  *request.mutable_second() = BezierMessage(2, {1, 0, 3, 0});
  absl::StatusOr<v1::IntersectCurvesResponse> answer = client_->Unary(
      client_->curves(), &v1::CurveService::Stub::Intersect, request);
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_TRUE(answer->first_parameters().empty());
  EXPECT_THAT(answer->first_intervals(),
              Pointwise(DoubleNear(1e-9), std::vector<double>{0.5, 1.0}));
  EXPECT_THAT(answer->second_intervals(),
              Pointwise(DoubleNear(1e-9), std::vector<double>{0.0, 0.5}));
}

TEST_F(QueryServiceTest, LineThroughAPlaneAndASphere) {
  v1::IntersectCurveSurfaceRequest request;
  *request.mutable_curve() = BezierMessage(3, {0.3, 0.4, -1, 0.3, 0.4, 3});
  *request.mutable_surface() = UnitSquareMessage();
  auto call = [&] {
    return client_->Unary(client_->surfaces(),
                          &v1::SurfaceService::Stub::IntersectCurve, request);
  };
  absl::StatusOr<v1::IntersectCurveSurfaceResponse> answer = call();
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_THAT(answer->curve_parameters(), ElementsAre(DoubleNear(0.25, 1e-10)));
  EXPECT_THAT(answer->surface_parameters(),
              ElementsAre(DoubleNear(0.3, 1e-10), DoubleNear(0.4, 1e-10)));
  // The diagonal ray from the origin meets the sphere of radius 2 at
  // 2 (1, 1, 1) / sqrt(3).
  *request.mutable_curve() = BezierMessage(3, {0, 0, 0, 3, 3, 3});
  *request.mutable_surface() = SphereMessage(2.0);
  answer = call();
  ASSERT_TRUE(answer.ok()) << answer.status();
  const double c = 2.0 / std::sqrt(3.0);
  EXPECT_THAT(answer->curve_parameters(),
              ElementsAre(DoubleNear(c / 3, 1e-10)));
  EXPECT_THAT(answer->points().coordinates(),
              Pointwise(DoubleNear(1e-10), std::vector<double>{c, c, c}));
  *request.mutable_curve() = BezierMessage(2, {0, 0, 3, 3});
  ExpectInvalid(call().status(), "surface");
}

// A tolerance below what double precision resolves on the inputs (2^-48 of
// their largest coordinate) is refused at once, naming it.
TEST_F(QueryServiceTest, IntersectionToleranceBelowTheResolutionIsRefused) {
  v1::IntersectCurvesRequest curves;
  *curves.mutable_first() = CircleMessage(1.0, 0.0, 0.0);
  *curves.mutable_second() = CircleMessage(1.0, 0.0, 0.0);
  curves.mutable_options()->set_tolerance(5e-324);
  ExpectInvalid(
      client_
          ->Unary(client_->curves(), &v1::CurveService::Stub::Intersect, curves)
          .status(),
      "options.tolerance");
  v1::IntersectCurveSurfaceRequest surface;
  *surface.mutable_curve() = BezierMessage(3, {0.25, 0.5, -1, 0.25, 0.5, 1});
  *surface.mutable_surface() = UnitSquareMessage();
  surface.mutable_options()->set_tolerance(1e-17);
  auto call = [&] {
    return client_->Unary(client_->surfaces(),
                          &v1::SurfaceService::Stub::IntersectCurve, surface);
  };
  ExpectInvalid(call().status(), "options.tolerance");
  // Twice the resolution finds the crossing at the curve's middle.
  surface.mutable_options()->set_tolerance(std::ldexp(1.0, -47));
  absl::StatusOr<v1::IntersectCurveSurfaceResponse> answer = call();
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_THAT(answer->curve_parameters(), ElementsAre(DoubleNear(0.5, 1e-14)));
  EXPECT_THAT(answer->surface_parameters(),
              ElementsAre(DoubleNear(0.25, 1e-14), DoubleNear(0.5, 1e-14)));
}

// The parabola B-spline of degree 2 on knots 0, 0, 0, 1/2, 1, 1, 1 through
// (-1, 1), (-1/2, 0), (1/2, 0), (1, 1) is (2s - 1, (2s - 1)^2) on both
// pieces; it touches the line (-2 + 4t, 0) at its knot. One point comes
// back, where the two are within the tolerance.
TEST_F(QueryServiceTest, TangencyOnAKnotIsOnePoint) {
  v1::IntersectCurvesRequest request;
  v1::BSplineCurve& parabola = *request.mutable_first()->mutable_bspline();
  parabola.set_degree(2);
  parabola.mutable_control_points()->set_dimension(2);
  Append(parabola.mutable_control_points()->mutable_coordinates(),
         {-1, 1, -0.5, 0, 0.5, 0, 1, 1});
  Append(parabola.mutable_knots(), {0, 0, 0, 0.5, 1, 1, 1});
  *request.mutable_second() = BezierMessage(2, {-2, 0, 2, 0});
  for (const double tolerance : {1e-6, 1e-9, 1e-12}) {
    request.mutable_options()->set_tolerance(tolerance);
    absl::StatusOr<v1::IntersectCurvesResponse> answer = client_->Unary(
        client_->curves(), &v1::CurveService::Stub::Intersect, request);
    ASSERT_TRUE(answer.ok()) << answer.status();
    ASSERT_EQ(answer->first_parameters_size(), 1) << tolerance;
    EXPECT_TRUE(answer->first_intervals().empty());
    const double x = 2 * answer->first_parameters(0) - 1;
    const double line_x = -2 + 4 * answer->second_parameters(0);
    EXPECT_LE(std::hypot(x - line_x, x * x), tolerance);
  }
}

// A stretch of a curve lying in the surface is an overlap: a segment in the
// unit square, and (t, 1/2, (1 - 2t)^16), the Bezier curve of control
// points (i / 16, 1/2, (-1)^i), along [1/2 - r, 1/2 + r] with
// (2r)^16 = 1e-9, where it is within 1e-9 of the square.
TEST_F(QueryServiceTest, CurveLyingInASurfaceIsAnOverlap) {
  v1::IntersectCurveSurfaceRequest request;
  *request.mutable_curve() = BezierMessage(3, {0.1, 0.2, 0, 0.8, 0.7, 0});
  *request.mutable_surface() = UnitSquareMessage();
  request.mutable_options()->set_tolerance(1e-3);
  auto call = [&] {
    return client_->Unary(client_->surfaces(),
                          &v1::SurfaceService::Stub::IntersectCurve, request);
  };
  absl::StatusOr<v1::IntersectCurveSurfaceResponse> answer = call();
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_TRUE(answer->curve_parameters().empty());
  EXPECT_THAT(answer->curve_intervals(),
              ElementsAre(DoubleNear(0, 1e-12), DoubleNear(1, 1e-12)));
  v1::Points& zigzag =
      *request.mutable_curve()->mutable_bezier()->mutable_control_points();
  zigzag.clear_coordinates();
  for (int i = 0; i <= 16; ++i) {
    Append(zigzag.mutable_coordinates(), {i / 16.0, 0.5, i % 2 ? -1.0 : 1.0});
  }
  request.mutable_options()->set_tolerance(1e-9);
  answer = call();
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_TRUE(answer->curve_parameters().empty());
  const double r = 0.5 * std::pow(1e-9, 1.0 / 16);
  EXPECT_THAT(
      answer->curve_intervals(),
      ElementsAre(DoubleNear(0.5 - r, 1e-9), DoubleNear(0.5 + r, 1e-9)));
}

// Planes z = h cut the sphere patch of radius 2 in quarter circles of radius
// sqrt(4 - h^2).
TEST_F(QueryServiceTest, PlaneSectionsOfASpherePatchAreCircles) {
  v1::SectionSurfaceRequest request;
  *request.mutable_surface() = SphereMessage(2.0);
  Append(request.mutable_plane_normal(), {0, 0, 1});
  request.set_tolerance(1e-7);
  for (const double h : {0.5, 1.0, 1.7}) {
    request.clear_plane_point();
    Append(request.mutable_plane_point(), {0, 0, h});
    absl::StatusOr<v1::SectionSurfaceResponse> answer = client_->Unary(
        client_->surfaces(), &v1::SurfaceService::Stub::Section, request);
    ASSERT_TRUE(answer.ok()) << answer.status();
    ASSERT_EQ(answer->polylines_size(), 1) << "h = " << h;
    const v1::SectionPolyline& polyline = answer->polylines(0);
    EXPECT_FALSE(polyline.closed());
    const auto& points = polyline.points().coordinates();
    ASSERT_GE(points.size(), 3 * 3);
    for (int k = 0; k < points.size(); k += 3) {
      EXPECT_NEAR(std::hypot(points[k], points[k + 1]), std::sqrt(4 - h * h),
                  1e-9);
      EXPECT_NEAR(points[k + 2], h, 1e-9);
    }
  }
  // Fitted: the cubic B-spline of the z = 1 section stays within the fit
  // tolerance of the circle of radius sqrt(3) (between the vertices too).
  request.clear_plane_point();
  Append(request.mutable_plane_point(), {0, 0, 1});
  request.set_fit_tolerance(1e-6);
  absl::StatusOr<v1::SectionSurfaceResponse> fitted = client_->Unary(
      client_->surfaces(), &v1::SurfaceService::Stub::Section, request);
  ASSERT_TRUE(fitted.ok()) << fitted.status();
  ASSERT_EQ(fitted->polylines_size(), 1);
  v1::EvaluateCurveRequest evaluate;
  *evaluate.mutable_curve() = fitted->polylines(0).curve();
  EXPECT_EQ(evaluate.curve().bspline().degree(), 3u);
  evaluate.mutable_parameters()->mutable_range()->set_count(1001);
  absl::StatusOr<CurveSamples> samples = client_->EvaluateCurve(evaluate);
  ASSERT_TRUE(samples.ok()) << samples.status();
  for (size_t k = 0; k < samples->count; ++k) {
    const absl::Span<const double> p = samples->Point(0, k);
    EXPECT_NEAR(std::hypot(p[0], p[1]), std::sqrt(3.0), 2e-6);
    EXPECT_NEAR(p[2], 1.0, 2e-6);
  }
  request.clear_fit_tolerance();

  request.clear_plane_normal();
  Append(request.mutable_plane_normal(), {0, 0, 0});
  ExpectInvalid(client_
                    ->Unary(client_->surfaces(),
                            &v1::SurfaceService::Stub::Section, request)
                    .status(),
                "plane_normal");
}

// A plane holding the unit square is one region, its parameter square; one
// holding a boundary edge gives that edge, on every side; a normal of any
// scale cuts the same line x + y = 1/2.
TEST_F(QueryServiceTest, SectionsInThePlaneAndAtAnyScale) {
  v1::SectionSurfaceRequest request;
  *request.mutable_surface() = UnitSquareMessage();
  auto cut = [&](std::initializer_list<double> point,
                 std::initializer_list<double> normal) {
    request.clear_plane_point();
    request.clear_plane_normal();
    Append(request.mutable_plane_point(), point);
    Append(request.mutable_plane_normal(), normal);
    return client_->Unary(client_->surfaces(),
                          &v1::SurfaceService::Stub::Section, request);
  };
  absl::StatusOr<v1::SectionSurfaceResponse> answer = cut({0, 0, 0}, {0, 0, 1});
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_EQ(answer->polylines_size(), 0);
  ASSERT_EQ(answer->regions_size(), 1);
  EXPECT_THAT(answer->regions(0).parameters(),
              ElementsAre(0, 0, 1, 0, 1, 1, 0, 1));
  for (const double x : {0.0, 1.0}) {
    for (const double sign : {1.0, -1.0}) {
      answer = cut({x, 0, 0}, {sign, 0, 0});
      ASSERT_TRUE(answer.ok()) << answer.status();
      ASSERT_EQ(answer->polylines_size(), 1) << "x = " << x;
      EXPECT_EQ(answer->regions_size(), 0);
      const auto& points = answer->polylines(0).points().coordinates();
      for (int k = 0; k < points.size(); k += 3) EXPECT_EQ(points[k], x);
    }
  }
  for (const double scale : {1e155, 1e-160}) {
    answer = cut({0.5, 0, 0}, {scale, scale, 0});
    ASSERT_TRUE(answer.ok()) << answer.status();
    ASSERT_EQ(answer->polylines_size(), 1) << scale;
    const auto& points = answer->polylines(0).points().coordinates();
    for (int k = 0; k < points.size(); k += 3) {
      EXPECT_NEAR(points[k] + points[k + 1], 0.5, 1e-15);
    }
  }
}

// Weights of 1e20 make the surface jump between neighbouring parameters:
// refused naming the surface, not vertices 0.5 off the plane; a tolerance
// below the resolution is refused naming it.
TEST_F(QueryServiceTest, SectionsThatDoublesCannotResolveAreRefused) {
  v1::SectionSurfaceRequest request;
  v1::BezierSurface& bezier = *request.mutable_surface()->mutable_bezier();
  v1::ControlNet& net = *bezier.mutable_control_net();
  net.set_dimension(3);
  net.set_count_u(3);
  net.set_count_v(3);
  Append(net.mutable_coordinates(),
         {0, 0,   0, 0, 0.5, 0, 0, 1, 0,   0.5, 0, 0, 0.5, 0.5,
          1, 0.5, 1, 0, 1,   0, 0, 1, 0.5, 0,   1, 1, 0});
  Append(bezier.mutable_weights(), {1, 1, 1, 1, 1e20, 1, 1, 1, 1});
  Append(request.mutable_plane_point(), {0, 0, 0.5});
  Append(request.mutable_plane_normal(), {0, 0, 1});
  Client& client = *client_;
  const auto section = &v1::SurfaceService::Stub::Section;
  ExpectInvalid(client.Unary(client.surfaces(), section, request).status(),
                "surface");
  bezier.mutable_weights()->Set(4, 2.0);
  EXPECT_TRUE(client.Unary(client.surfaces(), section, request).ok());
  request.set_tolerance(1e-20);
  ExpectInvalid(client.Unary(client.surfaces(), section, request).status(),
                "tolerance");
}

// Every query cap holds exactly: max_points of a section (the cut x = 1/2
// of the square is 3 vertices: its ends and its middle), max_results of an
// intersection (the zigzag crosses the axis 5 times) and max_minima of a
// closest point (from the circle's centre every point is nearest).
TEST_F(QueryServiceTest, QueryCapsAreExact) {
  v1::SectionSurfaceRequest section;
  *section.mutable_surface() = UnitSquareMessage();
  Append(section.mutable_plane_point(), {0.5, 0, 0});
  Append(section.mutable_plane_normal(), {1, 0, 0});
  for (const uint32_t cap : {1u, 2u, 3u}) {
    section.set_max_points(cap);
    absl::StatusOr<v1::SectionSurfaceResponse> answer = client_->Unary(
        client_->surfaces(), &v1::SurfaceService::Stub::Section, section);
    if (cap < 3) {
      ASSERT_EQ(answer.status().code(), absl::StatusCode::kResourceExhausted)
          << cap;
      EXPECT_EQ(FieldViolationsOf(answer.status()).at(0).field, "max_points");
    } else {
      ASSERT_TRUE(answer.ok()) << answer.status();
      EXPECT_EQ(answer->polylines(0).points().coordinates_size(), 3 * 3);
    }
  }
  v1::IntersectCurvesRequest intersect;
  v1::BSplineCurve& zigzag = *intersect.mutable_first()->mutable_bspline();
  zigzag.set_degree(1);
  zigzag.mutable_control_points()->set_dimension(2);
  Append(zigzag.mutable_control_points()->mutable_coordinates(),
         {0, -1, 1, 1, 2, -1, 3, 1, 4, -1, 5, 1});
  Append(zigzag.mutable_knots(), {0, 0, 1, 2, 3, 4, 5, 5});
  *intersect.mutable_second() = BezierMessage(2, {-1, 0, 6, 0});
  for (const uint32_t cap : {4u, 5u}) {
    intersect.mutable_options()->set_max_results(cap);
    absl::StatusOr<v1::IntersectCurvesResponse> answer = client_->Unary(
        client_->curves(), &v1::CurveService::Stub::Intersect, intersect);
    if (cap < 5) {
      ASSERT_EQ(answer.status().code(), absl::StatusCode::kResourceExhausted);
      EXPECT_EQ(FieldViolationsOf(answer.status()).at(0).field,
                "options.max_results");
    } else {
      ASSERT_TRUE(answer.ok()) << answer.status();
      EXPECT_EQ(answer->first_parameters_size(), 5);
    }
  }
  v1::CurveClosestPointRequest closest;
  *closest.mutable_curve() = CircleMessage(2.0, 1.0, -1.0);
  closest.mutable_queries()->set_dimension(2);
  Append(closest.mutable_queries()->mutable_coordinates(), {1, -1});
  for (const uint32_t cap : {1u, 2u, 3u}) {
    closest.mutable_options()->set_max_minima(cap);
    absl::StatusOr<v1::ClosestPointResponse> answer = client_->Unary(
        client_->curves(), &v1::CurveService::Stub::ClosestPoint, closest);
    ASSERT_TRUE(answer.ok()) << answer.status();
    EXPECT_THAT(answer->minima_counts(), ElementsAre(cap));
    EXPECT_EQ(answer->points().coordinates_size(), static_cast<int>(2 * cap));
  }
}

TEST_F(QueryServiceTest, ArcLengthsOfTheCircle) {
  v1::ArcLengthRequest request;
  *request.mutable_curve() = CircleMessage(2.0, 1.0, 1.0);
  request.set_tolerance(1e-13);
  auto call = [&] {
    return client_->Unary(client_->curves(), &v1::CurveService::Stub::ArcLength,
                          request);
  };
  absl::StatusOr<v1::ArcLengthResponse> answer = call();
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_THAT(answer->lengths(), ElementsAre(DoubleNear(4 * kPi, 1e-12)));
  v1::ParameterInterval* quarter = request.add_intervals();
  quarter->set_end(0.25);
  v1::ParameterInterval* rest = request.add_intervals();
  rest->set_start(0.25);
  answer = call();
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_THAT(answer->lengths(),
              ElementsAre(DoubleNear(kPi, 1e-12), DoubleNear(3 * kPi, 1e-12)));
  rest->set_end(0.2);
  ExpectInvalid(call().status(), "intervals[1].end");
  rest->set_end(1.5);
  ExpectInvalid(call().status(), "intervals[1].end");
  request.set_tolerance(0);
  ExpectInvalid(call().status(), "tolerance");
}

// The quadratic Bezier (0, 0), (1, 0), (3, 0) runs along [0, 3] at uneven
// speed; samples at equal arc length are at x = 0, 1, 2, 3, and the length
// 1.5 is reached at x = 1.5.
TEST_F(QueryServiceTest, EqualArcLengthSamplesOfAnUnevenLine) {
  v1::SampleByArcLengthRequest request;
  *request.mutable_curve() = BezierMessage(2, {0, 0, 1, 0, 3, 0});
  request.set_count(4);
  absl::StatusOr<v1::SampleByArcLengthResponse> answer = client_->Unary(
      client_->curves(), &v1::CurveService::Stub::SampleByArcLength, request);
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_THAT(
      answer->points().coordinates(),
      Pointwise(DoubleNear(1e-9), std::vector<double>{0, 0, 1, 0, 2, 0, 3, 0}));
  request.set_count(1);
  ExpectInvalid(client_
                    ->Unary(client_->curves(),
                            &v1::CurveService::Stub::SampleByArcLength, request)
                    .status(),
                "count");

  v1::ParametersAtArcLengthRequest at;
  *at.mutable_curve() = request.curve();
  Append(at.mutable_lengths(), {1.5, 0.0, 3.0});
  absl::StatusOr<v1::ParametersAtArcLengthResponse> found = client_->Unary(
      client_->curves(), &v1::CurveService::Stub::ParametersAtArcLength, at);
  ASSERT_TRUE(found.ok()) << found.status();
  // x(t) = 2t + t^2 (from B-form 0, 1, 3), so x = 1.5 at t = sqrt(2.5) - 1.
  EXPECT_THAT(found->parameters(),
              Pointwise(DoubleNear(1e-9),
                        std::vector<double>{std::sqrt(2.5) - 1, 0, 1}));
  EXPECT_THAT(
      found->points().coordinates(),
      Pointwise(DoubleNear(1e-9), std::vector<double>{1.5, 0, 0, 0, 3, 0}));
  at.add_lengths(3.5);
  ExpectInvalid(client_
                    ->Unary(client_->curves(),
                            &v1::CurveService::Stub::ParametersAtArcLength, at)
                    .status(),
                "lengths[3]");
}

// The ends of the arc-length queries' intervals, and ParametersAtArcLength's
// start, are checked with the request's paths: finite, within the domain
// [0, 1] and in order; an omitted end is the domain's.
TEST_F(QueryServiceTest, ArcLengthEndsNameTheRequestsFields) {
  const v1::Curve line = BezierMessage(2, {0, 0, 1, 0, 3, 0});
  v1::SampleByArcLengthRequest sample;
  *sample.mutable_curve() = line;
  sample.set_count(3);
  auto sample_call = [&] {
    return client_
        ->Unary(client_->curves(), &v1::CurveService::Stub::SampleByArcLength,
                sample)
        .status();
  };
  sample.mutable_interval()->set_end(0.5);
  EXPECT_TRUE(sample_call().ok());
  sample.mutable_interval()->set_start(-0.5);
  ExpectInvalid(sample_call(), "interval.start");
  EXPECT_EQ(sample_call().message(),
            "interval.start: -0.5 is not in the domain [0, 1]");
  sample.mutable_interval()->set_start(0.75);
  ExpectInvalid(sample_call(), "interval.end");
  EXPECT_EQ(sample_call().message(), "interval.end: must not be below start");
  sample.mutable_interval()->clear_start();
  sample.mutable_interval()->set_end(NAN);
  ExpectInvalid(sample_call(), "interval.end");
  EXPECT_EQ(sample_call().message(),
            "interval.end: nan is not in the domain [0, 1]");

  v1::ArcLengthRequest lengths;
  *lengths.mutable_curve() = line;
  lengths.add_intervals()->set_start(0.5);
  lengths.add_intervals()->set_start(INFINITY);
  const absl::Status status =
      client_
          ->Unary(client_->curves(), &v1::CurveService::Stub::ArcLength,
                  lengths)
          .status();
  ExpectInvalid(status, "intervals[1].start");
  EXPECT_EQ(status.message(),
            "intervals[1].start: inf is not in the domain [0, 1]");

  v1::ParametersAtArcLengthRequest at;
  *at.mutable_curve() = line;
  Append(at.mutable_lengths(), {0.5});
  at.set_start(2.0);
  const absl::Status start =
      client_
          ->Unary(client_->curves(),
                  &v1::CurveService::Stub::ParametersAtArcLength, at)
          .status();
  ExpectInvalid(start, "start");
  EXPECT_EQ(start.message(), "start: 2 is not in the domain [0, 1]");
  at.set_start(0.5);
  EXPECT_TRUE(client_
                  ->Unary(client_->curves(),
                          &v1::CurveService::Stub::ParametersAtArcLength, at)
                  .ok());
}

// The circle of radius 2 has curvature 1/2 everywhere; the twisted cubic
// (t, t^2, t^3) has torsion 3 / (9 t^4 + 9 t^2 + 1).
TEST_F(QueryServiceTest, CurvatureOfTheCircleAndTorsionOfTheTwistedCubic) {
  v1::CurveCurvatureRequest request;
  *request.mutable_curve() = CircleMessage(2.0, 0.0, 0.0);
  request.mutable_parameters()->mutable_range()->set_count(9);
  absl::StatusOr<v1::CurveCurvatureResponse> answer = client_->Unary(
      client_->curves(), &v1::CurveService::Stub::Curvature, request);
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_THAT(answer->curvatures(),
              Pointwise(DoubleNear(1e-12), std::vector<double>(9, 0.5)));
  EXPECT_TRUE(answer->torsions().empty());
  EXPECT_EQ(answer->tangents().dimension(), 2u);

  const BezierCurveData cubic = TwistedCubic();
  request.mutable_curve()->mutable_bezier()->mutable_control_points()->Clear();
  v1::Points& control =
      *request.mutable_curve()->mutable_bezier()->mutable_control_points();
  control.set_dimension(3);
  control.mutable_coordinates()->Add(cubic.coordinates.begin(),
                                     cubic.coordinates.end());
  answer = client_->Unary(client_->curves(), &v1::CurveService::Stub::Curvature,
                          request);
  ASSERT_TRUE(answer.ok()) << answer.status();
  ASSERT_EQ(answer->torsions_size(), 9);
  for (int i = 0; i < 9; ++i) {
    const double t = i / 8.0;
    EXPECT_NEAR(answer->torsions(i), 3 / (9 * t * t * t * t + 9 * t * t + 1),
                1e-12)
        << "t = " << t;
    EXPECT_EQ(answer->statuses(i), v1::CURVE_POINT_STATUS_REGULAR);
  }
}

// Along a plane curve the rotation-minimizing frame started from the
// plane's normal keeps it.
TEST_F(QueryServiceTest, RotationMinimizingFrameOfAPlaneCurveKeepsItsNormal) {
  v1::RotationMinimizingFramesRequest request;
  *request.mutable_curve() =
      BezierMessage(3, {0, 0, 0, 1, 2, 0, 3, -1, 0, 4, 1, 0});
  request.mutable_parameters()->mutable_range()->set_count(50);
  Append(request.mutable_initial_reference(), {0, 0, 1});
  absl::StatusOr<v1::RotationMinimizingFramesResponse> answer = client_->Unary(
      client_->curves(), &v1::CurveService::Stub::RotationMinimizingFrames,
      request);
  ASSERT_TRUE(answer.ok()) << answer.status();
  const auto& references = answer->references().coordinates();
  ASSERT_EQ(references.size(), 150);
  for (int k = 0; k < 150; k += 3) {
    EXPECT_NEAR(references[k], 0, 1e-12);
    EXPECT_NEAR(references[k + 1], 0, 1e-12);
    EXPECT_NEAR(references[k + 2], 1, 1e-12);
  }
  request.clear_initial_reference();
  Append(request.mutable_initial_reference(), {1, 2, 0});  // along T(0)
  ExpectInvalid(
      client_
          ->Unary(client_->curves(),
                  &v1::CurveService::Stub::RotationMinimizingFrames, request)
          .status(),
      "initial_reference");
}

// The sphere patch of radius 2: K = 1/4 everywhere and, with S_u x S_v
// pointing inwards, H = 1/2 (query.proto's convention).
TEST_F(QueryServiceTest, SpherePatchCurvatures) {
  v1::SurfaceCurvatureRequest request;
  *request.mutable_surface() = SphereMessage(2.0);
  v1::SurfaceGrid& grid = *request.mutable_parameters()->mutable_grid();
  grid.mutable_u()->mutable_range()->set_start(0.0);
  grid.mutable_u()->mutable_range()->set_end(0.9);
  grid.mutable_u()->mutable_range()->set_count(4);
  grid.mutable_v()->mutable_range()->set_count(4);
  absl::StatusOr<v1::SurfaceCurvatureResponse> answer = client_->Unary(
      client_->surfaces(), &v1::SurfaceService::Stub::Curvature, request);
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_THAT(answer->gaussian(),
              Pointwise(DoubleNear(1e-12), std::vector<double>(16, 0.25)));
  EXPECT_THAT(answer->mean(),
              Pointwise(DoubleNear(1e-12), std::vector<double>(16, 0.5)));
  for (const int status : answer->statuses()) {
    EXPECT_EQ(status, v1::SURFACE_POINT_STATUS_UMBILIC);
  }
  v1::ControlNet& net =
      *request.mutable_surface()->mutable_bezier()->mutable_control_net();
  net.set_dimension(2);
  net.mutable_coordinates()->Truncate(18);
  ExpectInvalid(client_
                    ->Unary(client_->surfaces(),
                            &v1::SurfaceService::Stub::Curvature, request)
                    .status(),
                "surface");
  EXPECT_EQ(client_
                ->Unary(client_->surfaces(),
                        &v1::SurfaceService::Stub::Curvature, request)
                .status()
                .message(),
            "surface: curvatures need a 3D surface, this one is 2D");
}

// The cubic (0, 0), (1, 3), (2, 3), (3, 0) peaks at y = 9/4 (t = 1/2) while
// its control polygon reaches 3; the circle of radius 2 about (1, -1) has
// the box [-1, 3] x [-3, 1] and the sphere patch of radius 2 [0, 2]^3.
TEST_F(QueryServiceTest, TightBoundingBoxes) {
  v1::CurveBoundingBoxRequest request;
  *request.mutable_curve() = BezierMessage(2, {0, 0, 1, 3, 2, 3, 3, 0});
  absl::StatusOr<v1::BoundingBoxResponse> answer = client_->Unary(
      client_->curves(), &v1::CurveService::Stub::BoundingBox, request);
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_THAT(answer->lower(),
              Pointwise(DoubleNear(1e-9), std::vector<double>{0, 0}));
  EXPECT_THAT(answer->upper(),
              Pointwise(DoubleNear(1e-9), std::vector<double>{3, 2.25}));
  *request.mutable_curve() = CircleMessage(2.0, 1.0, -1.0);
  answer = client_->Unary(client_->curves(),
                          &v1::CurveService::Stub::BoundingBox, request);
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_THAT(answer->lower(),
              Pointwise(DoubleNear(1e-9), std::vector<double>{-1, -3}));
  EXPECT_THAT(answer->upper(),
              Pointwise(DoubleNear(1e-9), std::vector<double>{3, 1}));
  request.set_tolerance(-1);
  ExpectInvalid(client_
                    ->Unary(client_->curves(),
                            &v1::CurveService::Stub::BoundingBox, request)
                    .status(),
                "tolerance");

  v1::SurfaceBoundingBoxRequest surface;
  *surface.mutable_surface() = SphereMessage(2.0);
  absl::StatusOr<v1::BoundingBoxResponse> box = client_->Unary(
      client_->surfaces(), &v1::SurfaceService::Stub::BoundingBox, surface);
  ASSERT_TRUE(box.ok()) << box.status();
  EXPECT_THAT(box->lower(),
              Pointwise(DoubleNear(1e-9), std::vector<double>{0, 0, 0}));
  EXPECT_THAT(box->upper(),
              Pointwise(DoubleNear(1e-9), std::vector<double>{2, 2, 2}));
}

}  // namespace
}  // namespace freeform::server
