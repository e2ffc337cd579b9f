// Tests of the query oracles (query_oracles.h) on answers whose values
// follow from the geometry: a right answer passes, and each kind of wrong
// answer (a point off its geometry, a distance that is not reached, a
// missed closer point, a vertex off the plane, a length outside its
// bounds, a box that leaves the curve out) is a finding.
#include "query_oracles.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "freeform/v1/curve_service.pb.h"
#include "freeform/v1/surface_service.pb.h"
#include "google/protobuf/descriptor.h"
#include "parse_text.h"
#include "service_limits.h"

namespace freeform::fuzz {
namespace {

using ::testing::HasSubstr;

std::optional<std::string> Check(const std::string& method,
                                 const google::protobuf::Message& request,
                                 const google::protobuf::Message& answer) {
  const google::protobuf::MethodDescriptor* descriptor =
      google::protobuf::DescriptorPool::generated_pool()->FindMethodByName(
          "freeform.v1." + method);
  EXPECT_NE(descriptor, nullptr) << method;
  return CheckQueryAnswer(*descriptor, request, answer,
                          server::ServiceLimits{});
}

// The segment from (-1, 0) to (1, 0) and the query (0, 2): the closest
// point is (0, 0) at t = 1/2, at distance 2.
constexpr char kSegmentQuery[] = R"pb(
  curve {
    bezier {
      control_points {
        dimension: 2
        coordinates: [ -1, 0, 1, 0 ]
      }
    }
  }
  queries {
    dimension: 2
    coordinates: [ 0, 2 ]
  })pb";

v1::ClosestPointResponse SegmentAnswer() {
  return ParseText<v1::ClosestPointResponse>(R"pb(
    parameter_count: 1
    distances: 2
    lower_bounds: 1.9999999995
    minima_counts: 1
    complete: true
    parameters: 0.5
    points {
      dimension: 2
      coordinates: [ 0, 0 ]
    })pb");
}

TEST(QueryOraclesTest, ClosestPointOfASegment) {
  const auto request = ParseText<v1::CurveClosestPointRequest>(kSegmentQuery);
  EXPECT_EQ(Check("CurveService.ClosestPoint", request, SegmentAnswer()),
            std::nullopt);

  v1::ClosestPointResponse nearer = SegmentAnswer();
  nearer.set_distances(0, 1.5);
  nearer.set_lower_bounds(0, 1.5);
  EXPECT_THAT(Check("CurveService.ClosestPoint", request, nearer).value_or(""),
              HasSubstr("not within the tolerance above the distance"));

  v1::ClosestPointResponse moved = SegmentAnswer();
  moved.mutable_points()->set_coordinates(0, 0.25);
  EXPECT_THAT(Check("CurveService.ClosestPoint", request, moved).value_or(""),
              HasSubstr("and there the geometry is (0, 0)"));

  // The end (1, 0) at distance sqrt(5) with a lower bound of 2.2: the
  // curve's point (0, 0) is at 2.
  v1::ClosestPointResponse missed = SegmentAnswer();
  missed.set_distances(0, std::sqrt(5.0));
  missed.set_lower_bounds(0, 2.2);
  missed.set_parameters(0, 1.0);
  missed.mutable_points()->set_coordinates(0, 1.0);
  missed.set_complete(0, false);
  EXPECT_THAT(Check("CurveService.ClosestPoint", request, missed).value_or(""),
              HasSubstr("below the certified lower bound"));

  v1::ClosestPointResponse loose = SegmentAnswer();
  loose.set_lower_bounds(0, 1.5);
  EXPECT_THAT(Check("CurveService.ClosestPoint", request, loose).value_or(""),
              HasSubstr("complete, but the lower bound"));
  loose.set_complete(0, false);
  EXPECT_EQ(Check("CurveService.ClosestPoint", request, loose), std::nullopt);
}

// The unit square S(u, v) = (u, v, 0) as a bilinear Bezier patch.
constexpr char kSquare[] = R"pb(
  bezier {
    control_net {
      dimension: 3
      count_u: 2
      count_v: 2
      coordinates: [ 0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0 ]
    }
  })pb";

TEST(QueryOraclesTest, ClosestPointOfASquare) {
  v1::SurfaceClosestPointRequest request;
  *request.mutable_surface() = ParseText<v1::Surface>(kSquare);
  request.mutable_queries()->set_dimension(3);
  for (double x : {0.5, 0.5, 1.0})
    request.mutable_queries()->add_coordinates(x);
  auto answer = ParseText<v1::ClosestPointResponse>(R"pb(
    parameter_count: 2
    distances: 1
    lower_bounds: 1
    minima_counts: 1
    complete: true
    parameters: [ 0.5, 0.5 ]
    points {
      dimension: 3
      coordinates: [ 0.5, 0.5, 0 ]
    })pb");
  EXPECT_EQ(Check("SurfaceService.ClosestPoint", request, answer),
            std::nullopt);
  // The corner (0, 0, 0) at sqrt(1.5), certified 1.2: (0.5, 0.5, 0) is at 1.
  answer.set_distances(0, std::sqrt(1.5));
  answer.set_lower_bounds(0, 1.2);
  answer.set_parameters(0, 0.0);
  answer.set_parameters(1, 0.0);
  answer.mutable_points()->set_coordinates(0, 0.0);
  answer.mutable_points()->set_coordinates(1, 0.0);
  answer.set_complete(0, false);
  EXPECT_THAT(
      Check("SurfaceService.ClosestPoint", request, answer).value_or(""),
      HasSubstr("below the certified lower bound"));
}

TEST(QueryOraclesTest, IntersectionOfTwoDiagonals) {
  // (-1, -1)-(1, 1) and (-1, 1)-(1, -1) cross at (0, 0), both at t = 1/2.
  const auto request = ParseText<v1::IntersectCurvesRequest>(R"pb(
    first {
      bezier {
        control_points {
          dimension: 2
          coordinates: [ -1, -1, 1, 1 ]
        }
      }
    }
    second {
      bezier {
        control_points {
          dimension: 2
          coordinates: [ -1, 1, 1, -1 ]
        }
      }
    })pb");
  auto answer = ParseText<v1::IntersectCurvesResponse>(R"pb(
    dimension: 2
    first_parameters: 0.5
    second_parameters: 0.5
    points {
      dimension: 2
      coordinates: [ 0, 0 ]
    })pb");
  EXPECT_EQ(Check("CurveService.Intersect", request, answer), std::nullopt);
  answer.set_second_parameters(0, 0.6);  // (0.2, -0.2): 0.28 away
  EXPECT_THAT(Check("CurveService.Intersect", request, answer).value_or(""),
              HasSubstr("apart, over the tolerance"));
  // An overlap whose ends are not on each other.
  answer = ParseText<v1::IntersectCurvesResponse>(R"pb(
    dimension: 2
    first_intervals: [ 0, 1 ]
    second_intervals: [ 0, 1 ])pb");
  EXPECT_THAT(Check("CurveService.Intersect", request, answer).value_or(""),
              HasSubstr("overlap 0 start"));
}

TEST(QueryOraclesTest, IntersectionOfASegmentAndTheSquare) {
  v1::IntersectCurveSurfaceRequest request;
  *request.mutable_curve() = ParseText<v1::Curve>(R"pb(
    bezier {
      control_points {
        dimension: 3
        coordinates: [ 0.5, 0.5, -1, 0.5, 0.5, 1 ]
      }
    })pb");
  *request.mutable_surface() = ParseText<v1::Surface>(kSquare);
  auto answer = ParseText<v1::IntersectCurveSurfaceResponse>(R"pb(
    dimension: 3
    curve_parameters: 0.5
    surface_parameters: [ 0.5, 0.5 ]
    points {
      dimension: 3
      coordinates: [ 0.5, 0.5, 0 ]
    })pb");
  EXPECT_EQ(Check("SurfaceService.IntersectCurve", request, answer),
            std::nullopt);
  answer.set_surface_parameters(0, 0.4);
  EXPECT_THAT(
      Check("SurfaceService.IntersectCurve", request, answer).value_or(""),
      HasSubstr("apart, over the tolerance"));
}

TEST(QueryOraclesTest, SectionOfTheSquareByThePlaneXHalf) {
  v1::SectionSurfaceRequest request;
  *request.mutable_surface() = ParseText<v1::Surface>(kSquare);
  for (double x : {0.5, 0.0, 0.0}) request.add_plane_point(x);
  for (double x : {2.0, 0.0, 0.0}) request.add_plane_normal(x);
  auto answer = ParseText<v1::SectionSurfaceResponse>(R"pb(
    polylines {
      points {
        dimension: 3
        coordinates: [ 0.5, 0, 0, 0.5, 1, 0 ]
      }
      parameters: [ 0.5, 0, 0.5, 1 ]
    })pb");
  EXPECT_EQ(Check("SurfaceService.Section", request, answer), std::nullopt);

  request.set_max_points(1);
  EXPECT_THAT(Check("SurfaceService.Section", request, answer).value_or(""),
              HasSubstr("2 vertices, over max_points 1"));
  request.set_max_points(0);

  // (0.6, 0.5, 0) is on the square at (0.6, 0.5), 0.1 off the plane.
  v1::SectionSurfaceResponse off = answer;
  off.mutable_polylines(0)->mutable_points()->set_coordinates(3, 0.6);
  off.mutable_polylines(0)->mutable_points()->set_coordinates(4, 0.5);
  off.mutable_polylines(0)->set_parameters(2, 0.6);
  off.mutable_polylines(0)->set_parameters(3, 0.5);
  EXPECT_THAT(Check("SurfaceService.Section", request, off).value_or(""),
              HasSubstr("off the plane"));

  // On the plane, but the square at (0.5, 0.5) is (0.5, 0.5, 0), not
  // (0.5, 1, 0).
  v1::SectionSurfaceResponse elsewhere = answer;
  elsewhere.mutable_polylines(0)->set_parameters(3, 0.5);
  EXPECT_THAT(Check("SurfaceService.Section", request, elsewhere).value_or(""),
              HasSubstr("the surface there is"));
}

TEST(QueryOraclesTest, ArcLengthOfASegment) {
  const auto request = ParseText<v1::ArcLengthRequest>(R"pb(
    curve {
      bezier {
        control_points {
          dimension: 2
          coordinates: [ 0, 0, 1, 0, 2, 0 ]
        }
      }
    })pb");
  v1::ArcLengthResponse answer;
  answer.add_lengths(2.0);
  EXPECT_EQ(Check("CurveService.ArcLength", request, answer), std::nullopt);
  answer.set_lengths(0, 1.5);
  EXPECT_THAT(Check("CurveService.ArcLength", request, answer).value_or(""),
              HasSubstr("shorter than an inscribed polyline"));
  answer.set_lengths(0, 3.0);
  EXPECT_THAT(Check("CurveService.ArcLength", request, answer).value_or(""),
              HasSubstr("longer than the control polygons"));
}

TEST(QueryOraclesTest, ArcLengthOfARationalCornerWithAHugeWeight) {
  // Issue 30: the corner (1, 0), (1, 1), (0, 1) with weights 1, 1e10, 1
  // hugs its control polygon (length 2.0000000113), answered 1.5625.
  const auto request = ParseText<v1::ArcLengthRequest>(R"pb(
    curve {
      bezier {
        control_points {
          dimension: 2
          coordinates: [ 1, 0, 1, 1, 0, 1 ]
        }
        weights: [ 1, 1e10, 1 ]
      }
    })pb");
  v1::ArcLengthResponse answer;
  answer.add_lengths(2.0000000113);
  EXPECT_EQ(Check("CurveService.ArcLength", request, answer), std::nullopt);
  answer.set_lengths(0, 1.5625);
  EXPECT_THAT(Check("CurveService.ArcLength", request, answer).value_or(""),
              HasSubstr("shorter than an inscribed polyline"));
}

TEST(QueryOraclesTest, APiecewiseConstantCurveHasNoLengthAndTwoValuesAtAKnot) {
  // Degree 0: the point 0 on [0, 0.5), the point 1 on [0.5, 1].
  const std::string curve = R"pb(
    curve {
      bspline {
        degree: 0
        control_points {
          dimension: 1
          coordinates: [ 0, 1 ]
        }
        knots: [ 0, 0.5, 1 ]
      }
    })pb";
  const auto length = ParseText<v1::ArcLengthRequest>(curve);
  v1::ArcLengthResponse answer;
  answer.add_lengths(0.0);
  EXPECT_EQ(Check("CurveService.ArcLength", length, answer), std::nullopt);
  answer.set_lengths(0, 1.0);
  EXPECT_THAT(Check("CurveService.ArcLength", length, answer).value_or(""),
              HasSubstr("longer than the control polygons"));

  // The query 0.25 is nearest to the point 0, at the end 0.5 of its piece
  // (the left-hand limit there).
  auto closest = ParseText<v1::CurveClosestPointRequest>(curve);
  closest.mutable_queries()->set_dimension(1);
  closest.mutable_queries()->add_coordinates(0.25);
  auto minimum = ParseText<v1::ClosestPointResponse>(R"pb(
    parameter_count: 1
    distances: 0.25
    lower_bounds: 0.25
    minima_counts: 1
    complete: true
    parameters: 0.5
    points { dimension: 1 coordinates: 0 })pb");
  EXPECT_EQ(Check("CurveService.ClosestPoint", closest, minimum), std::nullopt);
  minimum.set_parameters(0, 0.75);
  EXPECT_THAT(Check("CurveService.ClosestPoint", closest, minimum).value_or(""),
              HasSubstr("and there the geometry is (1)"));
}

TEST(QueryOraclesTest, ParametersAndSamplesAlongASegment) {
  // The segment (0, 0)-(2, 0) at unit speed 2: length 1 is at t = 1/2.
  const auto at_length = ParseText<v1::ParametersAtArcLengthRequest>(R"pb(
    curve {
      bezier {
        control_points {
          dimension: 2
          coordinates: [ 0, 0, 2, 0 ]
        }
      }
    }
    lengths: 1)pb");
  auto parameters = ParseText<v1::ParametersAtArcLengthResponse>(R"pb(
    parameters: 0.5
    points {
      dimension: 2
      coordinates: [ 1, 0 ]
    })pb");
  EXPECT_EQ(Check("CurveService.ParametersAtArcLength", at_length, parameters),
            std::nullopt);
  parameters.set_parameters(0, 0.75);
  parameters.mutable_points()->set_coordinates(0, 1.5);
  EXPECT_THAT(Check("CurveService.ParametersAtArcLength", at_length, parameters)
                  .value_or(""),
              HasSubstr("shorter than an inscribed polyline"));

  const auto sample = ParseText<v1::SampleByArcLengthRequest>(R"pb(
    curve {
      bezier {
        control_points {
          dimension: 2
          coordinates: [ 0, 0, 2, 0 ]
        }
      }
    }
    count: 3)pb");
  auto samples = ParseText<v1::SampleByArcLengthResponse>(R"pb(
    parameters: [ 0, 0.5, 1 ]
    points {
      dimension: 2
      coordinates: [ 0, 0, 1, 0, 2, 0 ]
    })pb");
  EXPECT_EQ(Check("CurveService.SampleByArcLength", sample, samples),
            std::nullopt);
  v1::SampleByArcLengthResponse moved = samples;
  moved.mutable_points()->set_coordinates(2, 1.25);
  EXPECT_THAT(
      Check("CurveService.SampleByArcLength", sample, moved).value_or(""),
      HasSubstr("is not the input's point there"));
  v1::SampleByArcLengthResponse short_of_end = samples;
  short_of_end.set_parameters(2, 0.9);
  short_of_end.mutable_points()->set_coordinates(4, 1.8);
  EXPECT_THAT(Check("CurveService.SampleByArcLength", sample, short_of_end)
                  .value_or(""),
              HasSubstr("not from 0 to 1"));
}

TEST(QueryOraclesTest, SamplesMayComeOutOfOrderOnlyWithinTheTolerance) {
  // Four samples of the segment (0, 0)-(2, 0) are 2/3 apart: with a
  // tolerance of 1 (their lengths within 1 of 0, 2/3, 4/3, 2) the middle
  // two may swap, with the default 1e-9 they may not.
  auto request = ParseText<v1::SampleByArcLengthRequest>(R"pb(
    curve {
      bezier {
        control_points {
          dimension: 2
          coordinates: [ 0, 0, 2, 0 ]
        }
      }
    }
    count: 4
    tolerance: 1)pb");
  const auto swapped = ParseText<v1::SampleByArcLengthResponse>(R"pb(
    parameters: [ 0, 0.625, 0.375, 1 ]
    points {
      dimension: 2
      coordinates: [ 0, 0, 1.25, 0, 0.75, 0, 2, 0 ]
    })pb");
  EXPECT_EQ(Check("CurveService.SampleByArcLength", request, swapped),
            std::nullopt);
  request.clear_tolerance();
  EXPECT_THAT(
      Check("CurveService.SampleByArcLength", request, swapped).value_or(""),
      HasSubstr("the parameters decrease"));
}

TEST(QueryOraclesTest, BoundingBoxOfASegment) {
  const auto request = ParseText<v1::CurveBoundingBoxRequest>(R"pb(
    curve {
      bezier {
        control_points {
          dimension: 2
          coordinates: [ 0, 0, 2, 0 ]
        }
      }
    })pb");
  auto box = ParseText<v1::BoundingBoxResponse>(R"pb(dimension: 2
                                                     lower: [ 0, 0 ]
                                                     upper: [ 2, 0 ])pb");
  EXPECT_EQ(Check("CurveService.BoundingBox", request, box), std::nullopt);
  box.set_upper(0, 1.0);
  EXPECT_THAT(Check("CurveService.BoundingBox", request, box).value_or(""),
              HasSubstr("is outside"));
  box.set_upper(0, 2.0);
  box.set_lower(0, -1.0);
  EXPECT_THAT(Check("CurveService.BoundingBox", request, box).value_or(""),
              HasSubstr("beyond the control points' range"));
}

TEST(QueryOraclesTest, MethodsWithoutAnOraclePass) {
  EXPECT_EQ(Check("CurveService.Evaluate",
                  v1::EvaluateCurveRequest::default_instance(),
                  v1::EvaluateCurveResponse::default_instance()),
            std::nullopt);
}

}  // namespace
}  // namespace freeform::fuzz
