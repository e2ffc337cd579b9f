// Hostile requests through a real in-process server, one test per class of
// defect the first independent probing found: integer fields taken beyond
// their range, work that outgrows the request or outlives its deadline,
// validation gaps, and non-finite answers with status OK. Each refusal must
// be INVALID_ARGUMENT or RESOURCE_EXHAUSTED naming the field's full path.
#include <gmock/gmock.h>
#include <google/protobuf/text_format.h>
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/support/byte_buffer.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

#include "absl/strings/str_cat.h"
#include "in_process_server.h"
#include "long_requests.h"

namespace freeform::server {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

template <typename Message>
Message Parse(const std::string& text) {
  Message message;
  EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(text, &message))
      << text;
  return message;
}

// A line y = x as a clamped uniform cubic B-spline with `count` points.
std::string LongBSpline(int count) {
  std::string text = "bspline { degree: 3 control_points { dimension: 2 ";
  for (int i = 0; i < count; ++i) {
    absl::StrAppend(&text, "coordinates: ", i, " coordinates: ", i, " ");
  }
  text += "} ";
  for (int k = 0; k < count + 4; ++k) {
    const int value = std::clamp(k - 3, 0, count - 3);
    absl::StrAppend(&text, "knots: ", value, " ");
  }
  return text + "}";
}

using HostileInputTest = InProcessServerTest;

// 1. Integer fields are checked in their own type.

TEST_F(HostileInputTest, LeastSquaresCountBeyondInt32IsRefused) {
  for (const std::string count : {"2147483648", "4294967295"}) {
    std::string text = "points { dimension: 1 ";
    for (int i = 0; i < 20; ++i)
      absl::StrAppend(&text, "coordinates: ", i, " ");
    text += "} least_squares { degree: 3 control_point_count: " + count + " }";
    auto result =
        client_->InterpolateCurve(Parse<v1::InterpolateCurveRequest>(text));
    ExpectInvalid(result.status(), "least_squares.control_point_count");
    EXPECT_THAT(std::string(result.status().message()), HasSubstr(count));
  }
}

TEST_F(HostileInputTest, DegreesBeyondInt32AreReportedAsSent) {
  auto curve = client_->EvaluateCurve(Parse<v1::EvaluateCurveRequest>(
      "curve { bspline { degree: 4294967295 control_points { dimension: 1 "
      "coordinates: 0 coordinates: 1 } } } parameters { list { values: 0 } }"));
  ExpectInvalid(curve.status(), "curve.bspline.degree");
  EXPECT_THAT(std::string(curve.status().message()), HasSubstr("4294967295"));

  auto subdivided = client_->SubdividePolygon(Parse<v1::SubdivideRequest>(
      "polygon { dimension: 1 coordinates: 0 coordinates: 1 coordinates: 2 }"
      " scheme: SUBDIVISION_SCHEME_UNIFORM_BSPLINE degree: 4294967295 "
      "levels: 1"));
  ExpectInvalid(subdivided.status(), "degree");
  EXPECT_THAT(std::string(subdivided.status().message()),
              HasSubstr("4294967295"));

  auto levels = client_->SubdividePolygon(Parse<v1::SubdivideRequest>(
      "polygon { dimension: 1 coordinates: 0 coordinates: 1 coordinates: 2 }"
      " scheme: SUBDIVISION_SCHEME_CHAIKIN levels: 4294967295"));
  EXPECT_EQ(FieldViolationsOf(levels.status()).at(0).field, "levels")
      << levels.status();

  auto basis =
      client_->EvaluateSurfaceBasis(Parse<v1::EvaluateSurfaceBasisRequest>(
          "triangular_degree: 4294967295 parameters { points { uv: 0 uv: 0 } "
          "}"));
  ExpectInvalid(basis.status(), "triangular_degree");
}

// 2. Work stays linear in the request and stops at the deadline.

TEST_F(HostileInputTest, DecomposeIsLinearInTheKnots) {
  // 2 * 10^5 control points: a quadratic algorithm takes minutes.
  auto client = Hurried(Scaled(std::chrono::seconds(20)));
  auto result = client->DecomposeCurve(Parse<v1::DecomposeCurveRequest>(
      "curve { " + LongBSpline(200'000) + " }"));
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_EQ(result->segments_size(), 200'000 - 3);
}

TEST_F(HostileInputTest, PowerFormBeyondTheDegreeLimitIsRefused) {
  std::string text = "curve { power { coefficients { dimension: 1 ";
  for (int i = 0; i < 2000; ++i) text += "coordinates: 1 ";
  text += "} } }";
  auto result = client_->DecomposeCurve(Parse<v1::DecomposeCurveRequest>(text));
  ExpectInvalid(result.status(), "curve.power.coefficients");
}

// Interpolation and least squares of degree 64 through 3 * 10^5 points take
// seconds of work for a 2.4 MB request; with a 300 ms deadline the server
// must stop soon after it. The values rise steadily, so their chord-length
// parameters are spread within a factor of 2 and the system is regular (a
// plain sine's clusters of parameters at its peaks make the degree-64
// system singular in double precision, which the row-by-row elimination
// finds well before any deadline).
TEST_F(HostileInputTest, InterpolationStopsAtTheDeadline) {
  v1::InterpolateCurveRequest request;
  request.mutable_points()->set_dimension(1);
  for (int i = 0; i < 300'000; ++i) {
    request.mutable_points()->add_coordinates(std::sin(0.001 * i) + 0.003 * i);
  }
  request.mutable_bspline()->set_degree(64);
  v1::InterpolateCurveRequest least_squares = request;
  least_squares.mutable_least_squares()->set_degree(64);
  least_squares.mutable_least_squares()->set_control_point_count(150'000);
  for (const auto& hurried : {request, least_squares}) {
    auto result =
        Hurried(std::chrono::milliseconds(300))->InterpolateCurve(hurried);
    EXPECT_EQ(result.status().code(), absl::StatusCode::kDeadlineExceeded)
        << result.status();
    EXPECT_TRUE(Drains(Scaled(std::chrono::seconds(1))));
  }
}

// A degree-10 B-spline of 16,000 points in 4-D elevated by 54: about
// 10^10 operations for an answer under every limit.
TEST_F(HostileInputTest, ElevationStopsAtTheDeadline) {
  const v1::ElevateCurveDegreeRequest request = LongElevation();
  auto result = Hurried(std::chrono::seconds(1))->ElevateCurveDegree(request);
  EXPECT_EQ(result.status().code(), absl::StatusCode::kDeadlineExceeded)
      << result.status();
  EXPECT_TRUE(Drains(Scaled(std::chrono::seconds(1))));
}

TEST_F(HostileInputTest, CurveTessellationRefusesATinyToleranceAtOnce) {
  auto result = Hurried(std::chrono::seconds(1))
                    ->TessellateCurve(Parse<v1::TessellateCurveRequest>(
                        "curve { bezier { control_points { dimension: 2 "
                        "coordinates: 0 coordinates: 0 coordinates: 1 "
                        "coordinates: 2 coordinates: 3 coordinates: -1 } "
                        "weights: 1 weights: 3 weights: 1 } } "
                        "tolerance: 1e-300"));
  EXPECT_EQ(FieldViolationsOf(result.status()).at(0).field, "tolerance")
      << result.status();
}

// 3. Answers too large are refused before they are built.

// A rational curve's polyline is bounded before the work like a polynomial
// one's: a quarter circle at 1e-3 needs 65 points at most, so a server with
// a small memory budget tessellates it (it reserved the whole message
// limit, 64 MiB, before and refused).
TEST_F(HostileInputTest, RationalTessellationReservesOnlyItsBound) {
  ServiceLimits limits;
  limits.memory_budget_bytes = 16 << 20;
  StartServer(limits);
  auto result = client_->TessellateCurve(Parse<v1::TessellateCurveRequest>(
      "curve { bezier { control_points { dimension: 2 coordinates: [1, 0, 1, "
      "1, 0, 1] } weights: [1, 0.70710678118654752, 1] } } tolerance: 1e-3"));
  ASSERT_TRUE(result.ok()) << result.status();
  const int points = result->parameters_size();
  EXPECT_GE(points, 17);
  EXPECT_LE(points, 65);
  for (int i = 0; i < points; ++i) {
    EXPECT_NEAR(std::hypot(result->points().coordinates(2 * i),
                           result->points().coordinates(2 * i + 1)),
                1.0, 1e-12);
  }
}

TEST_F(HostileInputTest, SurfaceStreamCutsInsideRows) {
  auto request = Parse<v1::EvaluateSurfaceRequest>(
      "surface { bezier { control_net { dimension: 3 count_u: 2 count_v: 2 "
      "coordinates: [0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1] } } } "
      "parameters { grid { u { range { count: 1 } } v { range { count: "
      "3000000 } } } }");
  auto result = client_->EvaluateSurfaceStreamed(request);
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_EQ(result->count, 3'000'000u);
}

TEST_F(HostileInputTest, GridStreamCutAnywhereEqualsUnary) {
  auto request = Parse<v1::EvaluateSurfaceRequest>(
      "surface { bezier { control_net { dimension: 3 count_u: 2 count_v: 3 "
      "coordinates: [0, 0, 0, 1, 0, 2, 2, 0, 0, 0, 1, 0, 1, 1, -1, 2, 1, 0] "
      "} } } parameters { grid { u { range { count: 3 } } v { range { count: "
      "5 } } } } derivative_order: 1 normals: true chunk_size: 4");
  auto unary = client_->EvaluateSurface(request);
  auto streamed = client_->EvaluateSurfaceStreamed(request);
  ASSERT_TRUE(unary.ok()) << unary.status();
  ASSERT_TRUE(streamed.ok()) << streamed.status();
  ASSERT_EQ(streamed->count, 15u);
  ASSERT_EQ(streamed->partials.size(), unary->partials.size());
  for (size_t k = 0; k < unary->partials.size(); ++k) {
    EXPECT_EQ(streamed->partials[k].values, unary->partials[k].values) << k;
  }
  EXPECT_EQ(streamed->normals, unary->normals);
  // Point (1, 2) is u = v = 1/2: rows (1, 0, 1) and (1, 1, -1/2) with the
  // quadratic weights 1/4, 1/2, 1/4 in v, then averaged in u.
  EXPECT_THAT(unary->Point(0, 0, 7), testing::ElementsAre(1.0, 0.5, 0.25));
}

// 4. Validation gaps.

TEST_F(HostileInputTest, BernsteinBasisOfTheHighestDegreeEvaluates) {
  auto result = client_->EvaluateBasis(Parse<v1::EvaluateBasisRequest>(
      "basis { bernstein { degree: 64 } } parameters { list { values: 0.25 "
      "} }"));
  ASSERT_TRUE(result.ok()) << result.status();
  double sum = 0;
  for (double value : result->derivatives[0]) sum += value;
  EXPECT_NEAR(sum, 1.0, 1e-14);
  EXPECT_NEAR(result->derivatives[0][0], std::pow(0.75, 64), 1e-20);
}

TEST_F(HostileInputTest, TriangularParameterErrorHasItsFullPath) {
  auto result = client_->EvaluateSurface(Parse<v1::EvaluateSurfaceRequest>(
      "surface { triangular_bezier { degree: 1 control_points { dimension: 1 "
      "coordinates: [0, 1, 2] } } } parameters { points { uv: [0.9, 0.9] } "
      "}"));
  ExpectInvalid(result.status(), "parameters.points.uv[0]");
}

TEST_F(HostileInputTest, DegreeZeroBSplineIsAStepFunction) {
  auto result = client_->EvaluateCurve(Parse<v1::EvaluateCurveRequest>(
      "curve { bspline { degree: 0 control_points { dimension: 1 "
      "coordinates: [5, 7] } knots: [0, 1, 2] } } "
      "parameters { list { values: [0, 0.5, 1.5, 2] } }"));
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_THAT(result->derivatives[0], testing::ElementsAre(5, 5, 7, 7));
}

TEST_F(HostileInputTest, DecomposeTakesLagrangeCurves) {
  // The parabola through (0, 0), (1, 1), (2, 4) at nodes 0, 1, 2 is one
  // Bezier segment with control points 0, 0, 4 (x: 0, 1, 2).
  auto result = client_->DecomposeCurve(Parse<v1::DecomposeCurveRequest>(
      "curve { lagrange { points { dimension: 2 coordinates: [0, 0, 1, 1, 2, "
      "4] } nodes: [0, 1, 2] } }"));
  ASSERT_TRUE(result.ok()) << result.status();
  ASSERT_EQ(result->segments_size(), 1);
  const auto& points = result->segments(0).bezier().control_points();
  ASSERT_EQ(points.coordinates_size(), 6);
  const double expected[] = {0, 0, 1, 0, 2, 4};
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(points.coordinates(i), expected[i], 1e-14) << i;
  }
}

TEST_F(HostileInputTest, ReductionByTheWholeDegreeIsRefused) {
  auto result = client_->ReduceCurveDegree(Parse<v1::ReduceCurveDegreeRequest>(
      "curve { bezier { control_points { dimension: 1 coordinates: [0, 1, 0] "
      "} } } by: 2"));
  ExpectInvalid(result.status(), "by");
}

// 5. An OK answer is finite.

// Either every derivative in `result` is finite, or the request was refused
// on a field under `geometry`.
template <typename Samples>
void ExpectFiniteOrRefused(const absl::StatusOr<Samples>& result,
                           const std::string& geometry) {
  if (!result.ok()) {
    ASSERT_FALSE(FieldViolationsOf(result.status()).empty()) << result.status();
    EXPECT_THAT(FieldViolationsOf(result.status())[0].field,
                testing::StartsWith(geometry))
        << result.status();
    return;
  }
  for (const auto& order : result->derivatives) {
    for (double value : order) EXPECT_TRUE(std::isfinite(value));
  }
}

TEST_F(HostileInputTest, HugeControlPointsGiveAFiniteAnswerOrARefusal) {
  ExpectFiniteOrRefused(
      client_->EvaluateCurve(Parse<v1::EvaluateCurveRequest>(
          "curve { bezier { control_points { dimension: 1 coordinates: "
          "[1e308, -1e308, 1e308, -1e308] } } } parameters { list { values: "
          "[0.3, 0.5] } } derivative_order: 2")),
      "curve.bezier");
}

TEST_F(HostileInputTest, DenormalKnotSpanGivesAFiniteAnswerOrARefusal) {
  ExpectFiniteOrRefused(
      client_->EvaluateBasis(Parse<v1::EvaluateBasisRequest>(
          "basis { bspline { degree: 2 knots: [0, 0, 0, 5e-324, 1, 1, 1] } } "
          "parameters { list { values: [0, 1e-324, 0.5] } } "
          "derivative_order: 2")),
      "basis.bspline");
}

TEST_F(HostileInputTest, ExtremeWeightsGiveAFiniteAnswerOrARefusal) {
  ExpectFiniteOrRefused(
      client_->EvaluateCurve(Parse<v1::EvaluateCurveRequest>(
          "curve { bezier { control_points { dimension: 1 coordinates: [0, 1, "
          "2] } weights: [1e-300, 1e300, 1e-300] } } parameters { list { "
          "values: [0, 1e-300, 0.5, 1] } } derivative_order: 3")),
      "curve.bezier");
}

// 6. Bytes that do not parse as the request message.

TEST_F(HostileInputTest, UnparseableBytesNameTheRequestMessage) {
  grpc::GenericStub stub(ClientChannel());
  // Field 1 (curve) as a length-delimited field longer than the message.
  const char garbage[] = {0x0a, 0x7f, 0x01, 0x02};
  grpc::Slice slice(garbage, sizeof(garbage));
  const grpc::ByteBuffer request(&slice, 1);
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() +
                       std::chrono::seconds(10));
  grpc::ByteBuffer response;
  grpc::Status status;
  std::mutex mutex;
  std::condition_variable done_signal;
  bool done = false;
  stub.UnaryCall(&context, "/freeform.v1.CurveService/Evaluate",
                 grpc::StubOptions(), &request, &response,
                 [&](grpc::Status result) {
                   std::lock_guard<std::mutex> lock(mutex);
                   status = std::move(result);
                   done = true;
                   done_signal.notify_one();
                 });
  std::unique_lock<std::mutex> lock(mutex);
  done_signal.wait(lock, [&] { return done; });
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT)
      << status.error_message();
  EXPECT_THAT(status.error_message(),
              HasSubstr("not a valid freeform.v1.EvaluateCurveRequest"));
}

// 7. A refusal names the field that caused it (the second campaign).

// A unit bilinear square meshed within a loose tolerance: its edges of at
// most 1e-5 need (2 / 1e-5)^2 = 4e10 cells, far over max_vertices, which
// the edge length alone causes (the tolerance alone needs one cell).
TEST_F(HostileInputTest, MeshTooFineForItsEdgeLengthNamesMaxEdgeLength) {
  const std::string square =
      "surfaces { bezier { control_net { dimension: 3 count_u: 2 count_v: 2 "
      "coordinates: [0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0] } } } ";
  const auto status = [&](const std::string& options) {
    return client_
        ->TessellateSurfaces(
            Parse<v1::TessellateSurfaceRequest>(square + options))
        .status();
  };
  const absl::Status by_edges = status("tolerance: 0.1 max_edge_length: 1e-5");
  EXPECT_EQ(by_edges.code(), absl::StatusCode::kResourceExhausted) << by_edges;
  ASSERT_EQ(FieldViolationsOf(by_edges).size(), 1u) << by_edges;
  EXPECT_EQ(FieldViolationsOf(by_edges)[0].field, "max_edge_length");
  // A curved patch whose tolerance alone is too fine still names it, with
  // or without an edge limit.
  const std::string bowl =
      "surfaces { bezier { control_net { dimension: 3 count_u: 3 count_v: 3 "
      "coordinates: [0, 0, 1, 0, 1, 0, 0, 2, 1, 1, 0, 0, 1, 1, -1, 1, 2, 0, "
      "2, 0, 1, 2, 1, 0, 2, 2, 1] } } } ";
  for (const std::string options :
       {"tolerance: 1e-13", "tolerance: 1e-13 max_edge_length: 1e-5"}) {
    const absl::Status by_tolerance =
        client_
            ->TessellateSurfaces(
                Parse<v1::TessellateSurfaceRequest>(bowl + options))
            .status();
    EXPECT_EQ(by_tolerance.code(), absl::StatusCode::kResourceExhausted)
        << by_tolerance;
    ASSERT_EQ(FieldViolationsOf(by_tolerance).size(), 1u) << by_tolerance;
    EXPECT_EQ(FieldViolationsOf(by_tolerance)[0].field, "tolerance") << options;
  }
}

// 400 points of the plane z = x / 2 + y / 4 over the unit square: a
// smoothing of 1e308 (times the 400 points it overflows) is refused on
// smoothing, with the rule; one that keeps the data fits the plane. Without
// parameters, a singular system is blamed on the points that cause it.
TEST_F(HostileInputTest, ScatteredFitRefusalsNameSmoothingOrPoints) {
  v1::FitScatteredSurfaceRequest request;
  request.mutable_points()->set_dimension(3);
  for (int k = 0; k < 400; ++k) {
    const double x = std::fmod(0.5 + k * 0.6180339887498949, 1.0);
    const double y = std::fmod(0.5 + k * 0.7548776662466927, 1.0);
    for (const double c : {x, y, x / 2 + y / 4}) {
      request.mutable_points()->add_coordinates(c);
    }
    request.add_parameters(x);
    request.add_parameters(y);
  }
  request.set_degree_u(2);
  request.set_degree_v(2);
  request.set_control_count_u(6);
  request.set_control_count_v(6);
  for (const double smoothing : {1e308, 1e200, 1e30}) {
    request.set_smoothing(smoothing);
    const absl::Status status = client_->FitScatteredSurface(request).status();
    ExpectInvalid(status, "smoothing");
    EXPECT_THAT(status.message(), HasSubstr("use at most")) << status;
  }
  request.set_smoothing(1.0);
  const auto fit = client_->FitScatteredSurface(request);
  ASSERT_TRUE(fit.ok()) << fit.status();
  EXPECT_LT(fit->max_residual(), 1e-9);
  // All points on the line x = y in (u, v): no data fixes the net off it.
  v1::FitScatteredSurfaceRequest line;
  line.mutable_points()->set_dimension(3);
  for (int k = 0; k < 40; ++k) {
    const double t = k / 39.0;
    for (const double c : {t, t, t}) line.mutable_points()->add_coordinates(c);
  }
  line.set_degree_u(1);
  line.set_degree_v(1);
  line.set_control_count_u(2);
  line.set_control_count_v(2);
  line.set_smoothing(0.0);
  ExpectInvalid(client_->FitScatteredSurface(line).status(), "points");
}

}  // namespace
}  // namespace freeform::server
