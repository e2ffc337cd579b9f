// The queries of CurveService and SurfaceService at extreme weights and
// scales through a real server: answers that are right (checked against
// the mathematics) or refusals that name the field at fault, never a wrong
// answer with status OK.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../core/shapes.h"
#include "freeform/v1/curve_service.grpc.pb.h"
#include "freeform/v1/surface_service.grpc.pb.h"
#include "in_process_server.h"

namespace freeform::server {
namespace {

using testing_util::CornerLength;

using ExtremeNumericsTest = InProcessServerTest;

// The rational corner (1,0), (1,1), (0,1) with weights 1, w, 1
// (shapes.h's RationalCorner) as a Bezier curve message.
v1::Curve CornerMessage(double weight) {
  v1::Curve curve;
  v1::BezierCurve& bezier = *curve.mutable_bezier();
  bezier.mutable_control_points()->set_dimension(2);
  Append(bezier.mutable_control_points()->mutable_coordinates(),
         {1, 0, 1, 1, 0, 1});
  Append(bezier.mutable_weights(), {1, weight, 1});
  return curve;
}

// The corner extruded along z: a rational surface with weights 1, w, 1
// across the corner.
v1::Surface SheetMessage(double weight) {
  v1::Surface surface;
  v1::BezierSurface& bezier = *surface.mutable_bezier();
  v1::ControlNet& net = *bezier.mutable_control_net();
  net.set_dimension(3);
  net.set_count_u(3);
  net.set_count_v(2);
  Append(net.mutable_coordinates(),
         {1, 0, 0, 1, 0, 1, 1, 1, 0, 1, 1, 1, 0, 1, 0, 0, 1, 1});
  Append(bezier.mutable_weights(), {1, 1, weight, weight, 1, 1});
  return surface;
}

v1::Curve SegmentMessage(double x0, double y0, double x1, double y1,
                         double knot) {
  v1::Curve curve;
  v1::BSplineCurve& bspline = *curve.mutable_bspline();
  bspline.set_degree(1);
  bspline.mutable_control_points()->set_dimension(2);
  Append(bspline.mutable_control_points()->mutable_coordinates(),
         {x0, y0, x1, y1});
  Append(bspline.mutable_knots(), {0, 0, knot, knot});
  return curve;
}

// The corner with weight 1e10 has length 2 - 8.5e-11 (CornerLength, its
// closed-form speed integrated in long double; the server said 1.5625) and
// with 1e15 2 - 8.5e-16 (it said 1e-12). Its samples at tolerance 1e-9
// would lie on its second leg, within 1e-10 of t = 1, where adjacent
// doubles of t are 1e-8 apart along the curve: refused, naming the weights;
// at 1e-7 they are equally spaced along it.
TEST_F(ExtremeNumericsTest, ArcLengthOfTheRationalCorner) {
  for (const double w : {1e10, 1e15, 1e50}) {
    v1::ArcLengthRequest request;
    *request.mutable_curve() = CornerMessage(w);
    request.set_tolerance(1e-10);
    absl::StatusOr<v1::ArcLengthResponse> answer = client_->Unary(
        client_->curves(), &v1::CurveService::Stub::ArcLength, request);
    ASSERT_TRUE(answer.ok()) << answer.status();
    ASSERT_EQ(answer->lengths_size(), 1);
    EXPECT_NEAR(answer->lengths(0), static_cast<double>(CornerLength(w, 1.0)),
                2e-10)
        << w;
  }
  v1::SampleByArcLengthRequest samples;
  *samples.mutable_curve() = CornerMessage(1e10);
  samples.set_count(11);
  samples.set_tolerance(1e-9);
  ExpectInvalid(client_
                    ->Unary(client_->curves(),
                            &v1::CurveService::Stub::SampleByArcLength, samples)
                    .status(),
                "curve.bezier.weights");
  samples.set_tolerance(1e-7);
  absl::StatusOr<v1::SampleByArcLengthResponse> spaced = client_->Unary(
      client_->curves(), &v1::CurveService::Stub::SampleByArcLength, samples);
  ASSERT_TRUE(spaced.ok()) << spaced.status();
  ASSERT_EQ(spaced->parameters_size(), 11);
  const double spacing = static_cast<double>(CornerLength(1e10, 1.0)) / 10;
  for (int k = 0; k + 1 < 11; ++k) {
    EXPECT_NEAR(
        static_cast<double>(CornerLength(1e10, spaced->parameters(k + 1)) -
                            CornerLength(1e10, spaced->parameters(k))),
        spacing, 2e-7 + 1e-11)
        << k;
  }
}

// A unit segment on knots [0, 0, 1e170, 1e170] has length 1 (the server
// said 0: its speed 1e-170 squared underflowed), and its point at length
// 0.25 is at t = 2.5e169.
TEST_F(ExtremeNumericsTest, ArcLengthOnKnots1e170Apart) {
  v1::ArcLengthRequest request;
  *request.mutable_curve() = SegmentMessage(0, 0, 1, 0, 1e170);
  absl::StatusOr<v1::ArcLengthResponse> answer = client_->Unary(
      client_->curves(), &v1::CurveService::Stub::ArcLength, request);
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_NEAR(answer->lengths(0), 1.0, 1e-12);
  v1::ParametersAtArcLengthRequest at;
  *at.mutable_curve() = SegmentMessage(0, 0, 1, 0, 1e170);
  at.add_lengths(0.25);
  absl::StatusOr<v1::ParametersAtArcLengthResponse> parameter = client_->Unary(
      client_->curves(), &v1::CurveService::Stub::ParametersAtArcLength, at);
  ASSERT_TRUE(parameter.ok()) << parameter.status();
  EXPECT_NEAR(parameter->parameters(0) / 1e170, 0.25, 1e-12);
}

// With weights of 1e50 a query whose nearest point lies on the corner's
// second leg (within 1e-50 of t = 1, no double parameter there) is refused
// naming the weights, on a curve and on a surface (the server reported a
// distance of 1 for a point 1.118 away); one near the first leg gets its
// point, at the distance reported.
TEST_F(ExtremeNumericsTest, ClosestPointsAtWeights1e50) {
  v1::CurveClosestPointRequest request;
  *request.mutable_curve() = CornerMessage(1e50);
  request.mutable_queries()->set_dimension(2);
  Append(request.mutable_queries()->mutable_coordinates(), {2.0, 0.5});
  absl::StatusOr<v1::ClosestPointResponse> answer = client_->Unary(
      client_->curves(), &v1::CurveService::Stub::ClosestPoint, request);
  ASSERT_TRUE(answer.ok()) << answer.status();
  const auto& point = answer->points().coordinates();
  EXPECT_NEAR(answer->distances(0), std::hypot(point[0] - 2.0, point[1] - 0.5),
              1e-15);
  EXPECT_NEAR(answer->distances(0), 1.0, 1e-9);
  request.mutable_queries()->mutable_coordinates()->Clear();
  Append(request.mutable_queries()->mutable_coordinates(), {0.5, 2.0});
  ExpectInvalid(client_
                    ->Unary(client_->curves(),
                            &v1::CurveService::Stub::ClosestPoint, request)
                    .status(),
                "curve.bezier.weights");
  v1::SurfaceClosestPointRequest on_surface;
  *on_surface.mutable_surface() = SheetMessage(1e50);
  on_surface.mutable_queries()->set_dimension(3);
  Append(on_surface.mutable_queries()->mutable_coordinates(), {0.5, 2.0, 0.5});
  ExpectInvalid(client_
                    ->Unary(client_->surfaces(),
                            &v1::SurfaceService::Stub::ClosestPoint, on_surface)
                    .status(),
                "surface.bezier.weights");
}

// A query 1e154 away from a unit segment is answered (its squared distance
// overflowed and the error blamed curve.bspline); one whose distance itself
// exceeds the largest double is refused naming that query's coordinate.
TEST_F(ExtremeNumericsTest, FarQueriesAreAnsweredOrBlamedOnThemselves) {
  v1::CurveClosestPointRequest request;
  *request.mutable_curve() = SegmentMessage(0, 0, 1, 0, 1);
  request.mutable_queries()->set_dimension(2);
  Append(request.mutable_queries()->mutable_coordinates(),
         {0.5, 1e154, 0.5, 1e300});
  absl::StatusOr<v1::ClosestPointResponse> answer = client_->Unary(
      client_->curves(), &v1::CurveService::Stub::ClosestPoint, request);
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_NEAR(answer->distances(0) / 1e154, 1.0, 1e-15);
  EXPECT_NEAR(answer->distances(1) / 1e300, 1.0, 1e-15);
  request.mutable_queries()->mutable_coordinates()->Clear();
  Append(request.mutable_queries()->mutable_coordinates(),
         {0.5, 0.5, 1.5e308, -1.5e308});
  ExpectInvalid(client_
                    ->Unary(client_->curves(),
                            &v1::CurveService::Stub::ClosestPoint, request)
                    .status(),
                "queries.coordinates", true);
}

// A constant curve of degree 1 answers like a degree-0 one: every parameter
// is a minimum, so max_minima (8) of them with complete = false; a constant
// surface gives its one point with complete = false.
TEST_F(ExtremeNumericsTest, ConstantGeometryOfEveryDegree) {
  for (const uint32_t degree : {0u, 1u}) {
    v1::CurveClosestPointRequest request;
    v1::BSplineCurve& bspline = *request.mutable_curve()->mutable_bspline();
    bspline.set_degree(degree);
    bspline.mutable_control_points()->set_dimension(2);
    Append(bspline.mutable_control_points()->mutable_coordinates(),
           {1, 2, 1, 2});
    if (degree == 0) {
      Append(bspline.mutable_knots(), {0, 1, 2});
    } else {
      Append(bspline.mutable_knots(), {0, 0, 1, 1});
    }
    request.mutable_queries()->set_dimension(2);
    Append(request.mutable_queries()->mutable_coordinates(), {4, 6});
    absl::StatusOr<v1::ClosestPointResponse> answer = client_->Unary(
        client_->curves(), &v1::CurveService::Stub::ClosestPoint, request);
    ASSERT_TRUE(answer.ok()) << answer.status();
    EXPECT_EQ(answer->minima_counts(0), 8u) << "degree " << degree;
    EXPECT_FALSE(answer->complete(0)) << "degree " << degree;
    EXPECT_NEAR(answer->distances(0), 5.0, 1e-14);
  }
  v1::SurfaceClosestPointRequest on_surface;
  v1::ControlNet& net =
      *on_surface.mutable_surface()->mutable_bezier()->mutable_control_net();
  net.set_dimension(3);
  net.set_count_u(2);
  net.set_count_v(2);
  Append(net.mutable_coordinates(), {1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0});
  on_surface.mutable_queries()->set_dimension(3);
  Append(on_surface.mutable_queries()->mutable_coordinates(), {4, 6, 0});
  absl::StatusOr<v1::ClosestPointResponse> answer = client_->Unary(
      client_->surfaces(), &v1::SurfaceService::Stub::ClosestPoint, on_surface);
  ASSERT_TRUE(answer.ok()) << answer.status();
  EXPECT_EQ(answer->minima_counts(0), 1u);
  EXPECT_FALSE(answer->complete(0));
  EXPECT_NEAR(answer->distances(0), 5.0, 1e-14);
}

// The circle of radius 1e-200 has curvature 1e200 (the server said
// SINGULAR, 0), and the quarter cylinder of radius 1e80 has principal
// curvatures 1e-80 and 0 (it said UMBILIC, [0, 0]).
TEST_F(ExtremeNumericsTest, CurvaturesAtExtremeScale) {
  const BSplineCurveData data = testing_util::NurbsCircle(1e-200);
  v1::CurveCurvatureRequest request;
  v1::BSplineCurve& bspline = *request.mutable_curve()->mutable_bspline();
  bspline.set_degree(2);
  bspline.mutable_control_points()->set_dimension(2);
  bspline.mutable_control_points()->mutable_coordinates()->Add(
      data.coordinates.begin(), data.coordinates.end());
  bspline.mutable_knots()->Add(data.knots.begin(), data.knots.end());
  bspline.mutable_weights()->Add(data.weights.begin(), data.weights.end());
  Append(request.mutable_parameters()->mutable_list()->mutable_values(),
         {0.1, 0.6});
  absl::StatusOr<v1::CurveCurvatureResponse> curvature = client_->Unary(
      client_->curves(), &v1::CurveService::Stub::Curvature, request);
  ASSERT_TRUE(curvature.ok()) << curvature.status();
  for (int r = 0; r < 2; ++r) {
    EXPECT_EQ(curvature->statuses(r), v1::CURVE_POINT_STATUS_REGULAR);
    EXPECT_NEAR(curvature->curvatures(r) * 1e-200, 1.0, 1e-12);
  }
  const double radius = 1e80;
  const double rho[3] = {radius, radius, radius};
  const double z[3] = {0.0, radius, 2 * radius};
  const SurfaceData cylinder = testing_util::Revolution(rho, z);
  v1::SurfaceCurvatureRequest on_surface;
  v1::BezierSurface& bezier = *on_surface.mutable_surface()->mutable_bezier();
  v1::ControlNet& net = *bezier.mutable_control_net();
  net.set_dimension(3);
  net.set_count_u(3);
  net.set_count_v(3);
  net.mutable_coordinates()->Add(cylinder.coordinates.begin(),
                                 cylinder.coordinates.end());
  bezier.mutable_weights()->Add(cylinder.weights.begin(),
                                cylinder.weights.end());
  Append(on_surface.mutable_parameters()->mutable_points()->mutable_uv(),
         {0.3, 0.6});
  absl::StatusOr<v1::SurfaceCurvatureResponse> principal = client_->Unary(
      client_->surfaces(), &v1::SurfaceService::Stub::Curvature, on_surface);
  ASSERT_TRUE(principal.ok()) << principal.status();
  EXPECT_EQ(principal->statuses(0), v1::SURFACE_POINT_STATUS_REGULAR);
  EXPECT_NEAR(principal->principal_curvatures(0) * radius, 1.0, 1e-12);
  EXPECT_NEAR(principal->principal_curvatures(1) * radius, 0.0, 1e-12);
  EXPECT_NEAR(principal->mean(0) * radius, 0.5, 1e-12);
}

}  // namespace
}  // namespace freeform::server
