// Load tool for a running freeformd (service workloads S1 and S2 of
// shared/bench/WORKLOADS.md, Bezier parts).
//
//   service_load --target=127.0.0.1:50051 [--seconds=5] [--callers=1,4,16,64]
//
// S1: unary Evaluate of a cubic Bezier at one parameter: p50/p99 latency with
//     one caller, then calls/s with N concurrent callers (blocking calls on N
//     threads sharing one channel).
// S2: the W1 curve (cubic clamped B-spline, 100 control points from LCG
//     seed 1) at 10^6 uniform parameters, unary and streamed, end to end
//     including the client's decoding; best and median of 10.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_split.h"
#include "freeform/client.h"
#include "workloads.h"

ABSL_FLAG(std::string, target, "127.0.0.1:50051", "freeformd address");
ABSL_FLAG(double, seconds, 5, "Duration of each throughput run");
ABSL_FLAG(std::string, callers, "1,4,16,64", "Concurrent callers to try");
ABSL_FLAG(bool, retry, true, "Client retries UNAVAILABLE (gRPC retry policy)");

namespace {

using Clock = std::chrono::steady_clock;

freeform::v1::EvaluateCurveRequest CubicRequest(uint32_t count) {
  freeform::v1::EvaluateCurveRequest request;
  auto* points =
      request.mutable_curve()->mutable_bezier()->mutable_control_points();
  points->set_dimension(3);
  for (double value :
       {0.1, -0.4, 0.9, 0.5, 0.3, -0.2, -0.7, 0.8, 0.05, 0.6, -0.9, 0.35}) {
    points->add_coordinates(value);
  }
  if (count == 1) {
    request.mutable_parameters()->mutable_list()->add_values(0.37);
  } else {
    request.mutable_parameters()->mutable_range()->set_count(count);
  }
  return request;
}

double Percentile(std::vector<double> values, double fraction) {
  std::sort(values.begin(), values.end());
  const double last = static_cast<double>(values.size() - 1);
  return values[static_cast<size_t>(fraction * last)];
}

void Latency(freeform::Client& client) {
  const auto request = CubicRequest(1);
  std::vector<double> micros;
  for (int i = 0; i < 5000; ++i) {
    const auto start = Clock::now();
    auto result = client.EvaluateCurve(request);
    if (!result.ok()) {
      std::printf("error: %s\n", result.status().ToString().c_str());
      return;
    }
    micros.push_back(
        std::chrono::duration<double, std::micro>(Clock::now() - start)
            .count());
  }
  std::printf("S1 latency, 1 caller, 5000 calls: p50 %.0f us, p99 %.0f us\n",
              Percentile(micros, 0.5), Percentile(micros, 0.99));
}

void Throughput(freeform::Client& client, int callers, double seconds) {
  const auto request = CubicRequest(1);
  std::atomic<long> calls{0};
  std::atomic<long> errors{0};
  const auto stop = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                       std::chrono::duration<double>(seconds));
  std::vector<std::thread> threads;
  for (int c = 0; c < callers; ++c) {
    threads.emplace_back([&] {
      while (Clock::now() < stop) {
        (client.EvaluateCurve(request).ok() ? calls : errors).fetch_add(1);
      }
    });
  }
  for (auto& thread : threads) thread.join();
  std::printf("S1 throughput, %2d callers: %.0f calls/s (%ld errors)\n",
              callers, static_cast<double>(calls.load()) / seconds,
              errors.load());
}

// The W1 curve at 10^6 uniform parameters.
freeform::v1::EvaluateCurveRequest W1Request() {
  freeform::v1::EvaluateCurveRequest request;
  auto* bspline = request.mutable_curve()->mutable_bspline();
  bspline->set_degree(3);
  bspline->mutable_control_points()->set_dimension(3);
  const std::vector<double> control = freeform::bench::RandomPoints(1, 100, 3);
  bspline->mutable_control_points()->mutable_coordinates()->Add(control.begin(),
                                                                control.end());
  const std::vector<double> knots =
      freeform::bench::ClampedUniformKnots(100, 3);
  bspline->mutable_knots()->Add(knots.begin(), knots.end());
  request.mutable_parameters()->mutable_range()->set_count(1'000'000);
  return request;
}

void Bulk(freeform::Client& client, bool streamed) {
  const auto request = W1Request();
  std::vector<double> millis;
  double checksum = 0;
  for (int i = 0; i < 10; ++i) {
    const auto start = Clock::now();
    auto result = streamed ? client.EvaluateCurveStreamed(request)
                           : client.EvaluateCurve(request);
    millis.push_back(
        std::chrono::duration<double, std::milli>(Clock::now() - start)
            .count());
    if (!result.ok()) {
      std::printf("error: %s\n", result.status().ToString().c_str());
      return;
    }
    checksum = 0;
    for (double value : result->derivatives[0]) checksum += value;
  }
  std::printf(
      "S2 (W1) 10^6 3D points, %s: best %.1f ms, median %.1f ms "
      "(checksum %.6f)\n",
      streamed ? "streamed" : "unary", Percentile(millis, 0),
      Percentile(millis, 0.5), checksum);
}

}  // namespace

int main(int argc, char** argv) {
  absl::ParseCommandLine(argc, argv);
  freeform::ClientOptions options;
  options.target = absl::GetFlag(FLAGS_target);
  options.retry_unavailable = absl::GetFlag(FLAGS_retry);
  auto client = freeform::Client::Create(options);
  if (!client.ok()) return 1;
  Latency(**client);
  for (absl::string_view text :
       absl::StrSplit(absl::GetFlag(FLAGS_callers), ',')) {
    int callers = 0;
    if (absl::SimpleAtoi(text, &callers) && callers > 0) {
      Throughput(**client, callers, absl::GetFlag(FLAGS_seconds));
    }
  }
  Bulk(**client, false);
  Bulk(**client, true);
  return 0;
}
