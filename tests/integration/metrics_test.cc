// freeformd --metrics_listen: the real binary's Prometheus endpoint counts
// the calls a client makes by method and code, with their latency and
// bytes, scraped over plain HTTP.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

#include "absl/strings/str_cat.h"
#include "freeform/client.h"
#include "metrics_scrape.h"
#include "server_process.h"

namespace freeform {
namespace {

using ::testing::HasSubstr;
using ::testing::Optional;

constexpr char kEvaluateOk[] =
    R"(freeform_calls_total{code="OK",method="CurveService.Evaluate"})";
constexpr char kEvaluateInvalid[] =
    R"(freeform_calls_total{code="INVALID_ARGUMENT",)"
    R"(method="CurveService.Evaluate"})";
constexpr char kEvaluateCount[] =
    R"(freeform_call_duration_seconds_count{method="CurveService.Evaluate"})";

// ScrapeWhenCounted scrapes the metrics until the latency histogram of
// CurveService.Evaluate and its OK and INVALID_ARGUMENT counters together
// count `calls`, and no call is in flight: a call is counted when the server
// is done with it, just after the client has its answer, and a scrape may
// fall between one call's histogram and its counter. Returns the last
// scrape.
std::string ScrapeWhenCounted(int port, double calls) {
  std::string text;
  const auto give_up =
      std::chrono::steady_clock::now() + std::chrono::seconds(10);
  do {
    absl::StatusOr<std::string> scraped = HttpGet(port, "/metrics");
    EXPECT_TRUE(scraped.ok()) << scraped.status();
    if (!scraped.ok()) return "";
    text = *std::move(scraped);
    const double coded = MetricValue(text, kEvaluateOk).value_or(0) +
                         MetricValue(text, kEvaluateInvalid).value_or(0);
    if (MetricValue(text, kEvaluateCount) == calls && coded == calls &&
        MetricValue(text, "freeform_calls_in_flight") == 0.0) {
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  } while (std::chrono::steady_clock::now() < give_up);
  return text;
}

TEST(FreeformdMetrics, CountsCallsByMethodAndCode) {
  ServerProcess server({"--metrics_listen=127.0.0.1:0"});
  ASSERT_GT(server.port(), 0);
  ASSERT_GT(server.metrics_port(), 0);
  absl::StatusOr<std::unique_ptr<Client>> client =
      Client::Create({.target = server.address()});
  ASSERT_TRUE(client.ok()) << client.status();

  // Before any call: the method's OK series, the refusal reasons and the
  // gauges are there at zero.
  absl::StatusOr<std::string> before =
      HttpGet(server.metrics_port(), "/metrics");
  ASSERT_TRUE(before.ok()) << before.status();
  EXPECT_THAT(MetricValue(*before, kEvaluateOk), Optional(0.0));
  EXPECT_THAT(MetricValue(*before, R"(freeform_admission_refusals_total{)"
                                   R"(reason="memory_budget"})"),
              Optional(0.0));
  EXPECT_THAT(MetricValue(*before, "freeform_pool_queued_tasks"),
              Optional(0.0));

  for (int i = 0; i < 3; ++i) {
    absl::StatusOr<CurveSamples> samples = (*client)->EvaluateBezier(
        2, {0, 0, 1, 2, 3, 2, 4, 0}, {0.0, 0.5, 1.0}, 1);
    ASSERT_TRUE(samples.ok()) << samples.status();
  }
  // Three coordinates are not points of dimension 2.
  absl::StatusOr<CurveSamples> invalid =
      (*client)->EvaluateBezier(2, {0, 0, 1}, {0.0});
  EXPECT_EQ(invalid.status().code(), absl::StatusCode::kInvalidArgument);

  const std::string text = ScrapeWhenCounted(server.metrics_port(), 4);
  EXPECT_THAT(MetricValue(text, kEvaluateOk), Optional(3.0)) << text;
  EXPECT_THAT(MetricValue(text, kEvaluateInvalid), Optional(1.0));
  EXPECT_THAT(MetricValue(text, kEvaluateCount), Optional(4.0));
  EXPECT_THAT(MetricValue(text, R"(freeform_call_duration_seconds_bucket{)"
                                R"(method="CurveService.Evaluate",le="+Inf"})"),
              Optional(4.0));
  EXPECT_GT(MetricValue(text, R"(freeform_call_duration_seconds_sum{)"
                              R"(method="CurveService.Evaluate"})")
                .value_or(0),
            0);
  EXPECT_GT(MetricValue(text, R"(freeform_request_bytes_total{)"
                              R"(method="CurveService.Evaluate"})")
                .value_or(0),
            0);
  EXPECT_GT(MetricValue(text, R"(freeform_response_bytes_total{)"
                              R"(method="CurveService.Evaluate"})")
                .value_or(0),
            0);
  EXPECT_THAT(MetricValue(text, "freeform_calls_in_flight"), Optional(0.0));
  // No other method was called; the health check is not a freeform call.
  EXPECT_THAT(MetricValue(text, R"(freeform_calls_total{code="OK",)"
                                R"(method="SurfaceService.Evaluate"})"),
              Optional(0.0));
  EXPECT_THAT(text, HasSubstr("# TYPE freeform_call_duration_seconds "
                              "histogram"));
}

// An address the metrics cannot bind stops freeformd at start with a
// message naming the flag.
TEST(FreeformdMetrics, UnusableAddressFailsAtStart) {
  ServerProcess first({"--metrics_listen=127.0.0.1:0"});
  ASSERT_GT(first.metrics_port(), 0);
  const std::string log =
      absl::StrCat(testing::TempDir(), "/metrics_busy_port.log");
  ServerProcess second(
      {absl::StrCat("--metrics_listen=127.0.0.1:", first.metrics_port())}, log);
  EXPECT_EQ(second.port(), 0);
  EXPECT_EQ(second.WaitForExit(std::chrono::seconds(10)), 1);
  std::ifstream file(log);
  const std::string logged((std::istreambuf_iterator<char>(file)),
                           std::istreambuf_iterator<char>());
  EXPECT_THAT(logged, HasSubstr(absl::StrCat("--metrics_listen=127.0.0.1:",
                                             first.metrics_port())));
}

}  // namespace
}  // namespace freeform
