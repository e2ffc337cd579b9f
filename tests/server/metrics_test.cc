// The metrics module (server/metrics.h) on its own, and the frame's reports
// into it through an in-process server: refusals by reason, the endpoint's
// port, and an address it cannot bind.
#include "metrics.h"

#include <gmock/gmock.h>
#include <grpcpp/create_channel.h>
#include <grpcpp/security/credentials.h>
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "freeform/client.h"
#include "metrics_scrape.h"
#include "server.h"

namespace freeform::server {
namespace {

using ::testing::Contains;
using ::testing::HasSubstr;
using ::testing::Optional;
using ::testing::SizeIs;

ServerMetrics::Readings FixedReadings() {
  return {.calls_in_flight = [] { return int64_t{2}; },
          .tasks_queued = [] { return int64_t{5}; },
          .memory_reserved_bytes = [] { return uint64_t{1000}; },
          .memory_capacity_bytes = 3000};
}

TEST(MetricsModule, NamesEveryRpcOfEveryService) {
  const std::vector<std::string> names = FreeformMethodNames();
  EXPECT_THAT(names, SizeIs(42));  // 21 curve, 17 surface and 4 face RPCs
  EXPECT_THAT(names, Contains("CurveService.Evaluate"));
  EXPECT_THAT(names, Contains("SurfaceService.TessellateStream"));
  EXPECT_THAT(names, Contains("FaceService.Area"));
}

TEST(MetricsModule, CountsCallsByMethodAndCode) {
  ServerMetrics metrics({"CurveService.Evaluate", "CurveService.Split"},
                        FixedReadings());
  MethodObserver& evaluate =
      metrics.ForMethod("CurveService.Evaluate", Transport::kGrpc);
  using std::chrono::microseconds;
  evaluate.CallDone(absl::StatusCode::kOk, microseconds(2000), 10, 20);
  evaluate.CallDone(absl::StatusCode::kOk, microseconds(2000), 10, 20);
  evaluate.CallDone(absl::StatusCode::kInvalidArgument, microseconds(200), 5,
                    0);
  const std::string text = metrics.Exposition();
  const auto value = [&](absl::string_view series) {
    return MetricValue(text, series);
  };
  EXPECT_THAT(value(R"(freeform_calls_total{code="OK",)"
                    R"(method="CurveService.Evaluate",transport="grpc"})"),
              Optional(2.0))
      << text;
  EXPECT_THAT(value(R"(freeform_calls_total{code="INVALID_ARGUMENT",)"
                    R"(method="CurveService.Evaluate",transport="grpc"})"),
              Optional(1.0));
  // Codes no call ended with have no series; OK has one from the start.
  EXPECT_EQ(value(R"(freeform_calls_total{code="INTERNAL",)"
                  R"(method="CurveService.Evaluate",transport="grpc"})"),
            std::nullopt);
  EXPECT_THAT(value(R"(freeform_calls_total{code="OK",)"
                    R"(method="CurveService.Split",transport="grpc"})"),
              Optional(0.0));
  EXPECT_THAT(value(R"(freeform_call_duration_seconds_count{)"
                    R"(method="CurveService.Evaluate",transport="grpc"})"),
              Optional(3.0));
  EXPECT_THAT(
      value(R"(freeform_call_duration_seconds_bucket{)"
            R"(method="CurveService.Evaluate",transport="grpc",le="0.00025"})"),
      Optional(1.0));
  EXPECT_THAT(
      value(R"(freeform_call_duration_seconds_bucket{)"
            R"(method="CurveService.Evaluate",transport="grpc",le="0.0025"})"),
      Optional(3.0));
  EXPECT_THAT(value(R"(freeform_request_bytes_total{)"
                    R"(method="CurveService.Evaluate",transport="grpc"})"),
              Optional(25.0));
  EXPECT_THAT(value(R"(freeform_response_bytes_total{)"
                    R"(method="CurveService.Evaluate",transport="grpc"})"),
              Optional(40.0));
  EXPECT_THAT(value("freeform_calls_in_flight"), Optional(2.0));
  EXPECT_THAT(value("freeform_pool_queued_tasks"), Optional(5.0));
  EXPECT_THAT(value("freeform_memory_reserved_bytes"), Optional(1000.0));
  EXPECT_THAT(value("freeform_memory_capacity_bytes"), Optional(3000.0));
}

TEST(MetricsModule, UnknownMethodsAndCodesHaveTheirOwnLabel) {
  ServerMetrics metrics({"CurveService.Evaluate"}, FixedReadings());
  metrics.ForMethod("CurveService.Missing", Transport::kGrpc)
      .CallDone(static_cast<absl::StatusCode>(99), std::chrono::seconds(1), 1,
                1);
  EXPECT_THAT(MetricValue(metrics.Exposition(),
                          R"(freeform_calls_total{code="UNKNOWN",)"
                          R"(method="unknown",transport="grpc"})"),
              Optional(1.0));
}

TEST(MetricsModule, CountsRefusalsByReason) {
  ServerMetrics metrics({}, FixedReadings());
  metrics.Refused(Refusal::kDraining);
  metrics.Refused(Refusal::kDraining);
  metrics.Refused(Refusal::kQueueFull);
  const std::string text = metrics.Exposition();
  const std::string refusals = "freeform_admission_refusals_total";
  EXPECT_THAT(MetricValue(text, refusals + R"({reason="draining"})"),
              Optional(2.0));
  EXPECT_THAT(MetricValue(text, refusals + R"({reason="queue_full"})"),
              Optional(1.0));
  EXPECT_THAT(MetricValue(text, refusals + R"({reason="memory_budget"})"),
              Optional(0.0));
}

TEST(MetricsModule, EndpointReportsAnAddressItCannotBind) {
  ServerMetrics metrics({}, FixedReadings());
  absl::StatusOr<std::unique_ptr<MetricsEndpoint>> first =
      MetricsEndpoint::Start("127.0.0.1:0", metrics);
  ASSERT_TRUE(first.ok()) << first.status();
  const std::string busy = absl::StrCat("127.0.0.1:", (*first)->port());
  absl::StatusOr<std::unique_ptr<MetricsEndpoint>> second =
      MetricsEndpoint::Start(busy, metrics);
  EXPECT_EQ(second.status().code(), absl::StatusCode::kUnavailable);
  EXPECT_THAT(second.status().message(),
              HasSubstr(absl::StrCat("--metrics_listen=", busy)));
  EXPECT_FALSE(MetricsEndpoint::Start("not an address", metrics).ok());
}

// A server with metrics, its client over loopback TCP (the in-process
// channel and ThreadSanitizer do not mix, in_process_server.h).
class MetricsServerTest : public ::testing::Test {
 protected:
  void StartServer(uint64_t memory_budget_bytes) {
    ServerOptions options;
    options.listen_address = "127.0.0.1:0";
    options.threads = 2;
    options.limits.memory_budget_bytes = memory_budget_bytes;
    options.metrics_listen_address = "127.0.0.1:0";
    absl::StatusOr<std::unique_ptr<FreeformServer>> server =
        FreeformServer::Start(options);
    ASSERT_TRUE(server.ok()) << server.status();
    server_ = *std::move(server);
    ASSERT_GT(server_->metrics_port(), 0);
    ClientOptions client_options;
    client_options.retry_unavailable = false;  // one call, one refusal
    client_ = std::make_unique<Client>(
        grpc::CreateChannel(absl::StrCat("127.0.0.1:", server_->port()),
                            grpc::InsecureChannelCredentials()),
        client_options);
  }

  // Refusals returns the refusal count of `reason` once the server is done
  // with every call (a call is counted just after its client has the
  // answer).
  double Refusals(absl::string_view reason) {
    for (int i = 0; i < 500 && server_->calls_in_flight() > 0; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    absl::StatusOr<std::string> text =
        HttpGet(server_->metrics_port(), "/metrics");
    EXPECT_TRUE(text.ok()) << text.status();
    return MetricValue(text.value_or(""),
                       absl::StrCat("freeform_admission_refusals_total{reason=",
                                    "\"", reason, "\"}"))
        .value_or(-1);
  }

  std::unique_ptr<FreeformServer> server_;
  std::unique_ptr<Client> client_;
};

TEST_F(MetricsServerTest, ServerWithoutAnAddressServesNoMetrics) {
  absl::StatusOr<std::unique_ptr<FreeformServer>> server =
      FreeformServer::Start({.listen_address = "127.0.0.1:0", .threads = 1});
  ASSERT_TRUE(server.ok()) << server.status();
  EXPECT_EQ((*server)->metrics_port(), 0);
}

TEST_F(MetricsServerTest, CountsCallsOverTheMemoryBudget) {
  StartServer(/*memory_budget_bytes=*/1 << 20);
  // 100,000 points of a line: 1.6 MB of answer, over the budget.
  std::vector<double> parameters(100'000, 0.5);
  absl::StatusOr<CurveSamples> refused =
      client_->EvaluateBezier(1, {0, 1}, parameters);
  EXPECT_EQ(refused.status().code(), absl::StatusCode::kResourceExhausted);
  EXPECT_TRUE(client_->EvaluateBezier(1, {0, 1}, {0.5}).ok());
  EXPECT_EQ(Refusals("memory_budget"), 1);
  EXPECT_EQ(Refusals("draining"), 0);
}

TEST_F(MetricsServerTest, CountsCallsRefusedWhileDraining) {
  StartServer(/*memory_budget_bytes=*/64 << 20);
  server_->BeginDrain();
  absl::StatusOr<CurveSamples> refused =
      client_->EvaluateBezier(1, {0, 1}, {0.5});
  EXPECT_EQ(refused.status().code(), absl::StatusCode::kUnavailable);
  EXPECT_EQ(Refusals("draining"), 1);
  EXPECT_EQ(Refusals("memory_budget"), 0);
}

}  // namespace
}  // namespace freeform::server
