// freeformd --metrics_listen: the real binary's Prometheus endpoint counts
// the calls a client makes by method and code, with their latency and
// bytes, scraped over plain HTTP.
#include <arpa/inet.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "freeform/client.h"
#include "metrics_scrape.h"
#include "server_process.h"

namespace freeform {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::Optional;

constexpr char kEvaluateOk[] =
    R"(freeform_calls_total{code="OK",method="CurveService.Evaluate",transport="grpc"})";
constexpr char kEvaluateInvalid[] =
    R"(freeform_calls_total{code="INVALID_ARGUMENT",)"
    R"(method="CurveService.Evaluate",transport="grpc"})";
constexpr char kEvaluateCount[] =
    R"(freeform_call_duration_seconds_count{method="CurveService.Evaluate",transport="grpc"})";

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
  EXPECT_THAT(
      MetricValue(
          text,
          R"(freeform_call_duration_seconds_bucket{)"
          R"(method="CurveService.Evaluate",transport="grpc",le="+Inf"})"),
      Optional(4.0));
  EXPECT_GT(
      MetricValue(text, R"(freeform_call_duration_seconds_sum{)"
                        R"(method="CurveService.Evaluate",transport="grpc"})")
          .value_or(0),
      0);
  EXPECT_GT(
      MetricValue(text, R"(freeform_request_bytes_total{)"
                        R"(method="CurveService.Evaluate",transport="grpc"})")
          .value_or(0),
      0);
  EXPECT_GT(
      MetricValue(text, R"(freeform_response_bytes_total{)"
                        R"(method="CurveService.Evaluate",transport="grpc"})")
          .value_or(0),
      0);
  EXPECT_THAT(MetricValue(text, "freeform_calls_in_flight"), Optional(0.0));
  // No other method was called; the health check is not a freeform call.
  EXPECT_THAT(
      MetricValue(text,
                  R"(freeform_calls_total{code="OK",)"
                  R"(method="SurfaceService.Evaluate",transport="grpc"})"),
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

// Only exactly /metrics is served, with or without a query (Prometheus'
// scrape `params`). civetweb matches a handler's path as a case-insensitive
// prefix after merging repeated slashes: each of these used to get the
// metrics.
TEST(FreeformdMetrics, OnlyTheMetricsPathIsServed) {
  ServerProcess server({"--metrics_listen=127.0.0.1:0"});
  ASSERT_GT(server.metrics_port(), 0);
  for (const char* path : {"/metrics", "/metrics?name[]=freeform_calls"}) {
    absl::StatusOr<std::string> metrics = HttpGet(server.metrics_port(), path);
    ASSERT_TRUE(metrics.ok()) << metrics.status();
    EXPECT_THAT(*metrics, HasSubstr("freeform_calls_total")) << path;
  }
  for (const char* path :
       {"/metricsX", "//metrics", "/METRICS", "/Metrics", "/metrics/",
        "/metrics/x", "/metrics.txt", "/./metrics", "/x/../metrics", "/"}) {
    absl::StatusOr<HttpAnswer> answer =
        HttpExchange(server.metrics_port(), path);
    ASSERT_TRUE(answer.ok()) << path << ": " << answer.status();
    EXPECT_THAT(answer->status_line, HasSubstr(" 404 ")) << path;
    EXPECT_THAT(answer->body, Not(HasSubstr("freeform_calls_total"))) << path;
  }
}

// ConnectToLoopback returns a socket connected to 127.0.0.1:PORT, or -1.
int ConnectToLoopback(int port) {
  const int socket_fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (socket_fd >= 0 &&
      connect(socket_fd, reinterpret_cast<const sockaddr*>(&address),
              sizeof(address)) != 0) {
    close(socket_fd);
    return -1;
  }
  return socket_fd;
}

// Connections that send nothing, or their request a byte every 50 ms,
// each hold one of the endpoint's 16 workers until its 1 s request
// timeout: 28 of them delay a scrape until the first 16 have timed out,
// about 1 s. With civetweb's defaults in prometheus-cpp's Exposer (2
// workers, 30 s) two idle connections stopped every scrape for 30 s.
TEST(FreeformdMetrics, IdleAndSlowConnectionsDoNotStarveAScrape) {
  ServerProcess server({"--metrics_listen=127.0.0.1:0"});
  ASSERT_GT(server.metrics_port(), 0);
  std::vector<int> idle;
  for (int i = 0; i < 20; ++i) {
    idle.push_back(ConnectToLoopback(server.metrics_port()));
    ASSERT_GE(idle.back(), 0);
  }
  std::vector<int> slow;
  for (int i = 0; i < 8; ++i) {
    slow.push_back(ConnectToLoopback(server.metrics_port()));
    ASSERT_GE(slow.back(), 0);
  }
  std::atomic<bool> stop{false};
  std::thread trickle([&] {
    constexpr char kStart[] = "GET /metrics HTTP/1.1\r\nX-Slow: ";
    for (int socket_fd : slow) {
      send(socket_fd, kStart, sizeof(kStart) - 1, MSG_NOSIGNAL);
    }
    while (!stop) {
      for (int socket_fd : slow) send(socket_fd, "x", 1, MSG_NOSIGNAL);
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(100));

  const auto start = std::chrono::steady_clock::now();
  absl::StatusOr<std::string> metrics =
      HttpGet(server.metrics_port(), "/metrics");
  const auto elapsed = std::chrono::steady_clock::now() - start;
  stop = true;
  trickle.join();
  for (int socket_fd : idle) close(socket_fd);
  for (int socket_fd : slow) close(socket_fd);
  ASSERT_TRUE(metrics.ok()) << metrics.status();
  EXPECT_THAT(*metrics, HasSubstr("freeform_calls_total"));
  EXPECT_LT(elapsed, std::chrono::seconds(2))
      << std::chrono::duration<double>(elapsed).count() << " s";
}

}  // namespace
}  // namespace freeform
