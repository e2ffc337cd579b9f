// Enum fields with numbers outside their enum (proto3 keeps unknown
// numbers) are refused with the field's full path, never run as some other
// value.
#include <gtest/gtest.h>

#include "in_process_server.h"

namespace freeform::server {
namespace {

class EnumTest : public InProcessServerTest {};

// Five points on a parabola: enough for every interpolation method.
void SetPoints(v1::Points* points) {
  points->set_dimension(2);
  Append(points->mutable_coordinates(), {0, 0, 1, 1, 2, 4, 3, 9, 4, 16});
}

TEST_F(EnumTest, BezierAlgorithm) {
  v1::EvaluateCurveRequest request;
  v1::Points* points =
      request.mutable_curve()->mutable_bezier()->mutable_control_points();
  points->set_dimension(1);
  Append(points->mutable_coordinates(), {0, 1, 2});
  request.mutable_parameters()->mutable_list()->add_values(0.5);
  request.set_bezier_algorithm(static_cast<v1::BezierAlgorithm>(99));
  ExpectInvalid(client_->EvaluateCurve(request).status(), "bezier_algorithm");
}

TEST_F(EnumTest, InterpolationMethods) {
  v1::InterpolateCurveRequest request;
  SetPoints(request.mutable_points());
  request.mutable_bspline()->set_degree(3);
  request.mutable_bspline()->set_parameterization(
      static_cast<v1::Parameterization>(99));
  ExpectInvalid(client_->InterpolateCurve(request).status(),
                "bspline.parameterization");
  request.mutable_bspline()->set_parameterization(
      v1::PARAMETERIZATION_CENTRIPETAL);
  request.mutable_bspline()->set_knot_rule(static_cast<v1::KnotRule>(-7));
  ExpectInvalid(client_->InterpolateCurve(request).status(),
                "bspline.knot_rule");

  request.mutable_cubic_spline()->set_end_condition(
      static_cast<v1::SplineEndCondition>(5));
  ExpectInvalid(client_->InterpolateCurve(request).status(),
                "cubic_spline.end_condition");

  request.mutable_least_squares()->set_degree(2);
  request.mutable_least_squares()->set_control_point_count(4);
  request.mutable_least_squares()->set_parameterization(
      static_cast<v1::Parameterization>(5));
  ExpectInvalid(client_->InterpolateCurve(request).status(),
                "least_squares.parameterization");
  // The same request with a real value works.
  request.mutable_least_squares()->set_parameterization(
      v1::PARAMETERIZATION_UNIFORM);
  EXPECT_TRUE(client_->InterpolateCurve(request).ok());
}

TEST_F(EnumTest, SurfaceInterpolationParameterization) {
  v1::InterpolateSurfaceRequest request;
  v1::ControlNet* net = request.mutable_points();
  net->set_dimension(1);
  net->set_count_u(3);
  net->set_count_v(3);
  Append(net->mutable_coordinates(), {0, 1, 0, 1, 2, 1, 0, 1, 0});
  request.set_degree_u(2);
  request.set_degree_v(2);
  request.set_parameterization(static_cast<v1::Parameterization>(99));
  ExpectInvalid(client_->InterpolateSurface(request).status(),
                "parameterization");
}

TEST_F(EnumTest, SubdivisionSchemeAndSurfaceDirection) {
  v1::SubdivideRequest subdivide;
  SetPoints(subdivide.mutable_polygon());
  subdivide.set_levels(1);
  subdivide.set_scheme(static_cast<v1::SubdivisionScheme>(99));
  ExpectInvalid(client_->SubdividePolygon(subdivide).status(), "scheme");

  v1::SplitSurfaceRequest split;
  v1::ControlNet* net =
      split.mutable_surface()->mutable_bezier()->mutable_control_net();
  net->set_dimension(1);
  net->set_count_u(2);
  net->set_count_v(2);
  Append(net->mutable_coordinates(), {0, 1, 1, 2});
  split.set_parameter(0.5);
  split.set_direction(static_cast<v1::SurfaceDirection>(99));
  ExpectInvalid(client_->SplitSurface(split).status(), "direction");
}

}  // namespace
}  // namespace freeform::server
