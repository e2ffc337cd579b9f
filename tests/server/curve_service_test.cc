// CurveService through a real in-process gRPC server and the client library.
#include "curve_service.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "in_process_server.h"

namespace freeform::server {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

class CurveServiceTest : public InProcessServerTest {
 protected:
  static v1::EvaluateCurveRequest CubicRequest() {
    v1::EvaluateCurveRequest request;
    v1::Points* points =
        request.mutable_curve()->mutable_bezier()->mutable_control_points();
    points->set_dimension(2);
    for (double value : {0, 0, 1, 2, 3, 2, 4, 0})
      points->add_coordinates(value);
    for (double t : {0.0, 0.5, 1.0}) {
      request.mutable_parameters()->mutable_list()->add_values(t);
    }
    request.set_derivative_order(1);
    return request;
  }

  // Expects INVALID_ARGUMENT with exactly one violation on `field`, which
  // the message names too.
  void ExpectInvalidRequest(const v1::EvaluateCurveRequest& request,
                            const std::string& field) {
    absl::StatusOr<CurveSamples> result = client_->EvaluateCurve(request);
    ASSERT_FALSE(result.ok()) << field;
    ExpectInvalid(result.status(), field);
    EXPECT_THAT(std::string(result.status().message()), HasSubstr(field));
  }
};

TEST_F(CurveServiceTest, EvaluatesTheWorkedCubic) {
  absl::StatusOr<CurveSamples> samples = client_->EvaluateCurve(CubicRequest());
  ASSERT_TRUE(samples.ok()) << samples.status();
  EXPECT_EQ(samples->dimension, 2);
  EXPECT_EQ(samples->count, 3u);
  EXPECT_THAT(samples->derivatives[0], ElementsAre(0, 0, 2, 1.5, 4, 0));
  EXPECT_THAT(samples->Point(1, 0), ElementsAre(3, 6));
}

TEST_F(CurveServiceTest, ConvenienceCallMatches) {
  absl::StatusOr<CurveSamples> samples =
      client_->EvaluateBezier(2, {0, 0, 1, 2, 3, 2, 4, 0}, {0.0, 0.5, 1.0}, 1);
  ASSERT_TRUE(samples.ok()) << samples.status();
  EXPECT_THAT(samples->Point(0, 1), ElementsAre(2, 1.5));
  EXPECT_THAT(samples->Point(1, 0), ElementsAre(3, 6));
}

TEST_F(CurveServiceTest, UniformRangeDefaultsToTheDomain) {
  v1::EvaluateCurveRequest request = CubicRequest();
  request.mutable_parameters()->mutable_range()->set_count(5);
  absl::StatusOr<CurveSamples> samples = client_->EvaluateCurve(request);
  ASSERT_TRUE(samples.ok()) << samples.status();
  ASSERT_EQ(samples->count, 5u);
  EXPECT_THAT(samples->Point(0, 0), ElementsAre(0, 0));
  EXPECT_THAT(samples->Point(0, 2), ElementsAre(2, 1.5));
  EXPECT_THAT(samples->Point(0, 4), ElementsAre(4, 0));
}

TEST_F(CurveServiceTest, StreamEqualsUnary) {
  v1::EvaluateCurveRequest request = CubicRequest();
  v1::UniformRange* range = request.mutable_parameters()->mutable_range();
  range->set_count(100'001);
  request.set_derivative_order(2);
  request.set_chunk_size(7'000);
  absl::StatusOr<CurveSamples> unary = client_->EvaluateCurve(request);
  absl::StatusOr<CurveSamples> streamed =
      client_->EvaluateCurveStreamed(request);
  ASSERT_TRUE(unary.ok()) << unary.status();
  ASSERT_TRUE(streamed.ok()) << streamed.status();
  EXPECT_EQ(streamed->count, 100'001u);
  EXPECT_EQ(unary->derivatives, streamed->derivatives);
}

TEST_F(CurveServiceTest, RationalCurveStaysOnTheCircle) {
  v1::EvaluateCurveRequest request;
  v1::BezierCurve* bezier = request.mutable_curve()->mutable_bezier();
  bezier->mutable_control_points()->set_dimension(2);
  for (double value : {1, 0, 1, 1, 0, 1}) {
    bezier->mutable_control_points()->add_coordinates(value);
  }
  for (double weight : {1.0, std::sqrt(0.5), 1.0}) bezier->add_weights(weight);
  request.mutable_parameters()->mutable_range()->set_count(1001);
  absl::StatusOr<CurveSamples> samples = client_->EvaluateCurve(request);
  ASSERT_TRUE(samples.ok()) << samples.status();
  for (size_t r = 0; r < samples->count; ++r) {
    auto point = samples->Point(0, r);
    EXPECT_NEAR(std::hypot(point[0], point[1]), 1.0, 1e-15);
  }
}

// A client that renames fields (proto-loader without keepCase) sends a curve
// without its control points: the answer names the dimension and says the
// points are missing.
TEST_F(CurveServiceTest, MissingControlPointsAreNamed) {
  v1::EvaluateCurveRequest request = CubicRequest();
  request.mutable_curve()->mutable_bezier()->clear_control_points();
  absl::StatusOr<CurveSamples> result = client_->EvaluateCurve(request);
  ASSERT_FALSE(result.ok());
  ExpectInvalid(result.status(), "curve.bezier.control_points.dimension");
  EXPECT_THAT(std::string(result.status().message()),
              HasSubstr("got 0 (is the points message missing?)"));
}

TEST_F(CurveServiceTest, InvalidRequestsNameTheField) {
  v1::EvaluateCurveRequest request = CubicRequest();
  request.mutable_curve()
      ->mutable_bezier()
      ->mutable_control_points()
      ->add_coordinates(9);  // 9 values for dimension 2
  ExpectInvalidRequest(request, "curve.bezier.control_points.coordinates");

  request = CubicRequest();
  request.mutable_curve()
      ->mutable_bezier()
      ->mutable_control_points()
      ->set_coordinates(3, std::nan(""));
  ExpectInvalidRequest(request, "curve.bezier.control_points.coordinates[3]");

  request = CubicRequest();
  request.mutable_curve()
      ->mutable_bezier()
      ->mutable_control_points()
      ->clear_coordinates();
  ExpectInvalidRequest(request, "curve.bezier.control_points.coordinates");

  request = CubicRequest();
  request.mutable_curve()
      ->mutable_bezier()
      ->mutable_control_points()
      ->set_dimension(0);
  ExpectInvalidRequest(request, "curve.bezier.control_points.dimension");

  request = CubicRequest();
  request.mutable_curve()
      ->mutable_bezier()
      ->mutable_control_points()
      ->set_dimension(1'000'000);
  ExpectInvalidRequest(request, "curve.bezier.control_points.dimension");

  request = CubicRequest();
  request.clear_curve();
  ExpectInvalidRequest(request, "curve");

  request = CubicRequest();
  request.mutable_curve()->mutable_bezier()->add_weights(1);
  ExpectInvalidRequest(request, "curve.bezier.weights");

  request = CubicRequest();
  request.mutable_parameters()->mutable_list()->set_values(1, 1.5);
  ExpectInvalidRequest(request, "parameters.list.values[1]");

  request = CubicRequest();
  request.mutable_parameters()->mutable_list()->set_values(2, INFINITY);
  ExpectInvalidRequest(request, "parameters.list.values[2]");

  request = CubicRequest();
  request.clear_parameters();
  ExpectInvalidRequest(request, "parameters");

  request = CubicRequest();
  request.mutable_parameters()->mutable_range()->set_count(0);
  ExpectInvalidRequest(request, "parameters.range.count");

  request = CubicRequest();
  request.mutable_parameters()->mutable_range()->set_count(3);
  request.mutable_parameters()->mutable_range()->set_end(2.0);
  ExpectInvalidRequest(request, "parameters.range.end");

  request = CubicRequest();
  request.set_derivative_order(1000);
  ExpectInvalidRequest(request, "derivative_order");
}

TEST_F(CurveServiceTest, DegreeOverTheLimitIsInvalid) {
  v1::EvaluateCurveRequest request = CubicRequest();
  v1::Points* points =
      request.mutable_curve()->mutable_bezier()->mutable_control_points();
  points->clear_coordinates();
  for (int i = 0; i < 2 * 66; ++i) points->add_coordinates(i);  // degree 65
  ExpectInvalidRequest(request, "curve.bezier.control_points");
}

TEST_F(CurveServiceTest, HugeRequestsAreResourceExhausted) {
  v1::EvaluateCurveRequest request = CubicRequest();
  request.mutable_parameters()->mutable_range()->set_count(4'000'000'000u);
  absl::StatusOr<CurveSamples> result = client_->EvaluateCurve(request);
  EXPECT_EQ(result.status().code(), absl::StatusCode::kResourceExhausted);
  EXPECT_THAT(std::string(result.status().message()), HasSubstr("parameters"));
}

TEST_F(CurveServiceTest, UnaryAnswerOverTheMessageLimitPointsToTheStream) {
  ServiceLimits limits;
  limits.max_message_bytes = 1 << 20;
  StartServer(limits);
  v1::EvaluateCurveRequest request = CubicRequest();
  request.mutable_parameters()->mutable_range()->set_count(100'000);
  absl::StatusOr<CurveSamples> result = client_->EvaluateCurve(request);
  EXPECT_EQ(result.status().code(), absl::StatusCode::kResourceExhausted);
  EXPECT_THAT(std::string(result.status().message()),
              HasSubstr("EvaluateStream"));
  absl::StatusOr<CurveSamples> streamed =
      client_->EvaluateCurveStreamed(request);
  ASSERT_TRUE(streamed.ok()) << streamed.status();
  EXPECT_EQ(streamed->count, 100'000u);
}

TEST_F(CurveServiceTest, DeadlineStopsALargeBatch) {
  // Degree 64 over 5 * 10^6 parameters takes seconds; 50 ms is far too
  // little, so the server must stop early and answer DEADLINE_EXCEEDED.
  v1::EvaluateCurveRequest request;
  v1::Points* points =
      request.mutable_curve()->mutable_bezier()->mutable_control_points();
  points->set_dimension(1);
  for (int i = 0; i <= 64; ++i) points->add_coordinates(i % 3);
  request.mutable_parameters()->mutable_range()->set_count(5'000'000);
  ClientOptions options;
  options.timeout = std::chrono::milliseconds(50);
  Client hurried(ClientChannel(), options);
  const auto started = std::chrono::steady_clock::now();
  absl::StatusOr<CurveSamples> result = hurried.EvaluateCurve(request);
  EXPECT_EQ(result.status().code(), absl::StatusCode::kDeadlineExceeded);
  // Give the server a moment, then check it answers promptly again.
  absl::StatusOr<CurveSamples> next = client_->EvaluateCurve(CubicRequest());
  EXPECT_TRUE(next.ok()) << next.status();
  EXPECT_LT(std::chrono::steady_clock::now() - started,
            Scaled(std::chrono::seconds(5)));
}

TEST_F(CurveServiceTest, HealthIsServingUntilShutdown) {
  EXPECT_TRUE(client_->CheckHealth().ok());
  EXPECT_TRUE(client_->CheckHealth("freeform.v1.CurveService").ok());
  EXPECT_EQ(client_->CheckHealth("no.such.Service").code(),
            absl::StatusCode::kNotFound);
}

}  // namespace
}  // namespace freeform::server
