// Requests from the second black-box campaign, sent to the real freeformd
// binary: each once crashed it, leaked its call or held the CPU, and must
// now get its answer (or its refusal) while the server stays up.
#include <google/protobuf/text_format.h>
#include <grpcpp/create_channel.h>
#include <grpcpp/security/credentials.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "freeform/v1/curve_service.grpc.pb.h"
#include "freeform/v1/surface_service.grpc.pb.h"
#include "long_requests.h"
#include "server_process.h"

namespace freeform {
namespace {

template <typename Message>
Message Parse(const std::string& text) {
  Message message;
  EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(text, &message))
      << text;
  return message;
}

class HostileRequestsTest : public ::testing::Test {
 protected:
  void Start(std::vector<std::string> flags = {}) {
    server_ = std::make_unique<ServerProcess>(std::move(flags));
    auto channel = grpc::CreateChannel(server_->address(),
                                       grpc::InsecureChannelCredentials());
    curves_ = v1::CurveService::NewStub(channel);
    surfaces_ = v1::SurfaceService::NewStub(channel);
  }

  // A context with a 30 s deadline, or with none at all.
  static std::unique_ptr<grpc::ClientContext> Context(bool deadline = true) {
    auto context = std::make_unique<grpc::ClientContext>();
    if (deadline) {
      context->set_deadline(std::chrono::system_clock::now() +
                            std::chrono::seconds(30));
    }
    return context;
  }

  // The server still answers a small call.
  void ExpectAlive() {
    v1::EvaluateCurveResponse response;
    const grpc::Status status = curves_->Evaluate(
        Context().get(),
        Parse<v1::EvaluateCurveRequest>(
            "curve { bezier { control_points { dimension: 1 coordinates: 0 "
            "coordinates: 2 } } } parameters { list { values: 0.25 } }"),
        &response);
    ASSERT_TRUE(status.ok()) << status.error_message();
    EXPECT_EQ(response.derivatives(0).coordinates(0), 0.5);
  }

  std::unique_ptr<ServerProcess> server_;
  std::unique_ptr<v1::CurveService::Stub> curves_;
  std::unique_ptr<v1::SurfaceService::Stub> surfaces_;
};

// Item 1 of the campaign: a degree-0 B-spline (a step function) made
// RemoveKnots throw std::length_error and abort the process. Its knot 1
// joins the equal steps 1, 1; its knot 2 (a jump of 1) stays at 1e-9.
TEST_F(HostileRequestsTest, DegreeZeroKnotRemovalAnswers) {
  Start();
  const std::string step =
      "curve { bspline { degree: 0 control_points { dimension: 1 "
      "coordinates: 1 coordinates: 1 coordinates: 2 } knots: 0 knots: 1 "
      "knots: 2 knots: 3 } } tolerance: 1e-9";
  for (const std::string& extra : {std::string(""), std::string(" knot: 1"),
                                   std::string(" knot: 2 times: 1")}) {
    v1::RemoveCurveKnotsResponse response;
    const grpc::Status status = curves_->RemoveKnots(
        Context().get(), Parse<v1::RemoveCurveKnotsRequest>(step + extra),
        &response);
    ASSERT_TRUE(status.ok()) << extra << ": " << status.error_message();
    const bool joins = extra.find("knot: 2") == std::string::npos;
    EXPECT_EQ(response.removals(), joins ? 1u : 0u) << extra;
    const auto& points = response.curve().bspline().control_points();
    EXPECT_EQ(
        std::vector<double>(points.coordinates().begin(),
                            points.coordinates().end()),
        joins ? std::vector<double>({1, 2}) : std::vector<double>({1, 1, 2}))
        << extra;
  }
  // The surface: degree 0 in u over three rows, the first two equal.
  for (const std::string& direction : {std::string("SURFACE_DIRECTION_U"),
                                       std::string("SURFACE_DIRECTION_BOTH")}) {
    v1::RemoveSurfaceKnotsResponse response;
    const grpc::Status status = surfaces_->RemoveKnots(
        Context().get(),
        Parse<v1::RemoveSurfaceKnotsRequest>(
            "surface { bspline { degree_u: 0 degree_v: 1 control_net { "
            "dimension: 1 count_u: 3 count_v: 2 coordinates: 1 coordinates: 5 "
            "coordinates: 1 coordinates: 5 coordinates: 2 coordinates: 7 } "
            "knots_u: 0 knots_u: 1 knots_u: 2 knots_u: 3 knots_v: 0 knots_v: 0 "
            "knots_v: 1 knots_v: 1 } } tolerance: 1e-9 direction: " +
            direction),
        &response);
    ASSERT_TRUE(status.ok()) << direction << ": " << status.error_message();
    EXPECT_EQ(response.removals_u(), 1u);
    const auto& net = response.surface().bspline().control_net();
    EXPECT_EQ(
        std::vector<double>(net.coordinates().begin(), net.coordinates().end()),
        std::vector<double>({1, 5, 2, 7}));
  }
  ExpectAlive();
}

// Item 5: a caller that sets no deadline (or a late one) is stopped at the
// server's --max_call_time. The degree-10 elevation by 54 of 16,000 4-D
// points is about 10^10 operations, legal but far longer than 0.5 s.
TEST_F(HostileRequestsTest, CallsWithoutADeadlineStopAtTheServersLimit) {
  Start({"--max_call_time=500ms"});
  const v1::ElevateCurveDegreeRequest request = LongElevation();
  for (const bool client_deadline : {false, true}) {
    const auto start = std::chrono::steady_clock::now();
    v1::ElevateCurveDegreeResponse response;
    const grpc::Status status = curves_->ElevateDegree(
        Context(client_deadline).get(), request, &response);
    const auto elapsed = std::chrono::steady_clock::now() - start;
    EXPECT_EQ(status.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED)
        << status.error_message();
    EXPECT_NE(status.error_message().find("--max_call_time=500ms"),
              std::string::npos)
        << status.error_message();
    EXPECT_LT(elapsed, std::chrono::milliseconds(500 + 1500));
  }
  ExpectAlive();
}

}  // namespace
}  // namespace freeform
