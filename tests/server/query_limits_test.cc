// The query RPCs under the server's limits and the caller's deadline: a
// batch or a search larger than the limits is refused before any work,
// naming its field, and work that outlives the deadline stops.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "in_process_server.h"

namespace freeform::server {
namespace {

using QueryLimitsTest = InProcessServerTest;

// A clamped uniform B-spline of `count` points of `dimension` coordinates,
// point i coordinate j at sin(i * (j + 1) * 0.37) * (1 + j): a wiggly curve
// whose pieces overlap in every direction.
v1::Curve WigglySpline(int count, int dimension, int degree) {
  v1::Curve curve;
  v1::BSplineCurve& bspline = *curve.mutable_bspline();
  bspline.set_degree(static_cast<uint32_t>(degree));
  bspline.mutable_control_points()->set_dimension(
      static_cast<uint32_t>(dimension));
  for (int i = 0; i < count; ++i) {
    for (int j = 0; j < dimension; ++j) {
      bspline.mutable_control_points()->add_coordinates(
          std::sin(i * (j + 1) * 0.37) * (1 + j));
    }
  }
  for (int k = 0; k < count + degree + 1; ++k) {
    bspline.add_knots(std::clamp(k - degree, 0, count - degree));
  }
  return curve;
}

// 10^5 queries on a degree-9 spline of 20,000 points in 8-D: seconds of
// work for a 6 MB request; with a 300 ms deadline the server stops soon
// after it.
TEST_F(QueryLimitsTest, ClosestPointBatchStopsAtTheDeadline) {
  v1::CurveClosestPointRequest request;
  *request.mutable_curve() = WigglySpline(20'000, 8, 9);
  request.mutable_queries()->set_dimension(8);
  for (int i = 0; i < 8 * 100'000; ++i) {
    request.mutable_queries()->add_coordinates(std::cos(i * 0.01) * 3);
  }
  absl::StatusOr<v1::ClosestPointResponse> answer =
      Hurried(std::chrono::milliseconds(300))
          ->Unary(client_->curves(), &v1::CurveService::Stub::ClosestPoint,
                  request);
  EXPECT_EQ(answer.status().code(), absl::StatusCode::kDeadlineExceeded)
      << answer.status();
  EXPECT_TRUE(Drains(Scaled(std::chrono::seconds(2))));
}

// Two wiggly plane splines of 20,000 points cross tens of thousands of
// times.
TEST_F(QueryLimitsTest, IntersectionStopsAtTheDeadline) {
  v1::IntersectCurvesRequest request;
  *request.mutable_first() = WigglySpline(20'000, 2, 3);
  *request.mutable_second() = WigglySpline(20'000, 2, 5);
  absl::StatusOr<v1::IntersectCurvesResponse> answer =
      Hurried(std::chrono::milliseconds(300))
          ->Unary(client_->curves(), &v1::CurveService::Stub::Intersect,
                  request);
  EXPECT_THAT(answer.status().code(),
              ::testing::AnyOf(absl::StatusCode::kDeadlineExceeded,
                               absl::StatusCode::kResourceExhausted))
      << answer.status();
  EXPECT_TRUE(Drains(Scaled(std::chrono::seconds(2))));
}

// --max_query_work bounds one search: two wiggly splines of 200 points
// cross a few hundred times, which the default limit lets through and 2^16
// units do not (RESOURCE_EXHAUSTED naming the tolerance and the flag);
// the section of a wave net likewise.
TEST_F(QueryLimitsTest, QueryWorkIsBoundedByTheServersLimit) {
  v1::IntersectCurvesRequest crossing;
  *crossing.mutable_first() = WigglySpline(200, 2, 3);
  *crossing.mutable_second() = WigglySpline(200, 2, 5);
  v1::SectionSurfaceRequest section;
  v1::BSplineSurface& wave = *section.mutable_surface()->mutable_bspline();
  wave.set_degree_u(3);
  wave.set_degree_v(3);
  wave.mutable_control_net()->set_dimension(3);
  wave.mutable_control_net()->set_count_u(30);
  wave.mutable_control_net()->set_count_v(30);
  for (int i = 0; i < 30; ++i) {
    for (int j = 0; j < 30; ++j) {
      for (const double c : {i / 29.0, j / 29.0, std::sin(i * 0.7 + j)}) {
        wave.mutable_control_net()->add_coordinates(c);
      }
    }
  }
  for (int k = 0; k < 34; ++k) {
    wave.add_knots_u(std::clamp(k - 3, 0, 27));
    wave.add_knots_v(std::clamp(k - 3, 0, 27));
  }
  for (const double c : {0.0, 0.0, 0.0}) section.add_plane_point(c);
  for (const double c : {0.0, 0.0, 1.0}) section.add_plane_normal(c);
  const auto both = [&] {
    return std::pair{
        client_->Unary(client_->curves(), &v1::CurveService::Stub::Intersect,
                       crossing),
        client_->Unary(client_->surfaces(), &v1::SurfaceService::Stub::Section,
                       section)};
  };
  {
    const auto [intersection, cut] = both();
    ASSERT_TRUE(intersection.ok()) << intersection.status();
    EXPECT_GT(intersection->first_parameters_size(), 0);
    ASSERT_TRUE(cut.ok()) << cut.status();
    EXPECT_GT(cut->polylines_size(), 0);
  }
  ServiceLimits limits;
  limits.max_query_work = uint64_t{1} << 16;
  StartServer(limits);
  const auto [intersection, cut] = both();
  ASSERT_EQ(intersection.status().code(), absl::StatusCode::kResourceExhausted)
      << intersection.status();
  EXPECT_EQ(FieldViolationsOf(intersection.status()).at(0).field,
            "options.tolerance");
  EXPECT_THAT(std::string(intersection.status().message()),
              ::testing::HasSubstr("--max_query_work"));
  ASSERT_EQ(cut.status().code(), absl::StatusCode::kResourceExhausted)
      << cut.status();
  EXPECT_EQ(FieldViolationsOf(cut.status()).at(0).field, "tolerance");
}

TEST_F(QueryLimitsTest, BatchesBeyondTheLimitsAreRefusedByField) {
  ServiceLimits limits;
  limits.max_control_points = 1000;
  limits.max_parameters = 1000;
  limits.max_output_values = 100'000;
  StartServer(limits);

  v1::CurveClosestPointRequest closest;
  *closest.mutable_curve() = WigglySpline(50, 2, 3);
  closest.mutable_queries()->set_dimension(2);
  for (int i = 0; i < 2 * 1001; ++i) {
    closest.mutable_queries()->add_coordinates(i);
  }
  absl::Status status =
      client_
          ->Unary(client_->curves(), &v1::CurveService::Stub::ClosestPoint,
                  closest)
          .status();
  EXPECT_EQ(status.code(), absl::StatusCode::kResourceExhausted) << status;
  EXPECT_EQ(FieldViolationsOf(status).at(0).field, "queries");

  // 1000 queries of 1024 minima each would answer millions of values.
  closest.mutable_queries()->mutable_coordinates()->Truncate(2 * 1000);
  closest.mutable_options()->set_max_minima(1024);
  status = client_
               ->Unary(client_->curves(), &v1::CurveService::Stub::ClosestPoint,
                       closest)
               .status();
  EXPECT_EQ(status.code(), absl::StatusCode::kResourceExhausted) << status;
  EXPECT_EQ(FieldViolationsOf(status).at(0).field, "queries");

  v1::IntersectCurvesRequest intersect;
  *intersect.mutable_first() = WigglySpline(50, 2, 3);
  *intersect.mutable_second() = WigglySpline(50, 2, 3);
  intersect.mutable_options()->set_max_results(1'000'000);
  status = client_
               ->Unary(client_->curves(), &v1::CurveService::Stub::Intersect,
                       intersect)
               .status();
  EXPECT_EQ(status.code(), absl::StatusCode::kResourceExhausted) << status;
  EXPECT_EQ(FieldViolationsOf(status).at(0).field, "options.max_results");

  v1::ArcLengthRequest lengths;
  *lengths.mutable_curve() = WigglySpline(50, 2, 3);
  for (int i = 0; i < 1001; ++i) lengths.add_intervals();
  status = client_
               ->Unary(client_->curves(), &v1::CurveService::Stub::ArcLength,
                       lengths)
               .status();
  EXPECT_EQ(status.code(), absl::StatusCode::kResourceExhausted) << status;
  EXPECT_EQ(FieldViolationsOf(status).at(0).field, "intervals");

  v1::SampleByArcLengthRequest samples;
  *samples.mutable_curve() = WigglySpline(50, 2, 3);
  samples.set_count(4'000'000'000u);
  status = client_
               ->Unary(client_->curves(),
                       &v1::CurveService::Stub::SampleByArcLength, samples)
               .status();
  EXPECT_EQ(status.code(), absl::StatusCode::kResourceExhausted) << status;
  EXPECT_EQ(FieldViolationsOf(status).at(0).field, "count");
}

// A degree-60 spline of 1000 points in 60-D has Bezier pieces of about
// 29 MB; under a 16 MiB memory budget the query is refused naming the curve
// before anything is cut.
TEST_F(QueryLimitsTest, PiecesOverTheMemoryBudgetAreRefused) {
  ServiceLimits limits;
  limits.memory_budget_bytes = 16 << 20;
  StartServer(limits);
  v1::CurveBoundingBoxRequest request;
  *request.mutable_curve() = WigglySpline(1000, 60, 60);
  const absl::Status status =
      client_
          ->Unary(client_->curves(), &v1::CurveService::Stub::BoundingBox,
                  request)
          .status();
  EXPECT_EQ(status.code(), absl::StatusCode::kResourceExhausted) << status;
  EXPECT_EQ(FieldViolationsOf(status).at(0).field, "curve");
}

}  // namespace
}  // namespace freeform::server
