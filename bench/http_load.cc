// http_load: freeformd's HTTP/JSON gateway (--http_listen) against its gRPC
// listener, in one run, from one client program: the same calls over both,
// alternating round after round, each figure the best of its rounds.
//
//   http_load --grpc_target=127.0.0.1:PORT --http_target=127.0.0.1:PORT
//             [--rounds=3] [--iters=2000] [--bulk_iters=15]
//             [--points=100000]
//
// S1      one small call (the cubic Bezier at one parameter, as
//         service_load's S1), sequential, p50 in microseconds.
// bulk    the W1 curve (cubic B-spline, 100 control points, LCG seed 1) at
//         --points parameters (10^5: 300,000 coordinates), sequential,
//         median in milliseconds.
// Each over gRPC (grpc::GenericStub, the answer's bytes received), HTTP
// with JSON and HTTP with binary proto (libcurl on one kept-alive
// connection, the answer's body received); neither decodes the answer.
// Prints a Markdown table with the ratios HTTP/gRPC and the targets
// (JSON S1 p50 <= 2x, JSON bulk <= 3x) with ok or MISSED. Exit 1 when a
// call fails.
#include <google/protobuf/util/json_util.h>
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/strings/str_cat.h"
#include "freeform/v1/curve_service.grpc.pb.h"
#include "http_client.h"
#include "workloads.h"

ABSL_FLAG(std::string, grpc_target, "127.0.0.1:50051", "freeformd's gRPC");
ABSL_FLAG(std::string, http_target, "127.0.0.1:8080",
          "freeformd's --http_listen");
ABSL_FLAG(int, rounds, 3, "Rounds of every measurement");
ABSL_FLAG(int, iters, 2000, "S1 calls per measurement");
ABSL_FLAG(int, bulk_iters, 15, "Bulk calls per measurement");
ABSL_FLAG(int, points, 100'000, "Parameters of the bulk call");

namespace {

namespace v1 = freeform::v1;
using Clock = std::chrono::steady_clock;

constexpr char kEvaluatePath[] = "/freeform.v1.CurveService/Evaluate";

v1::EvaluateCurveRequest S1Request() {
  v1::EvaluateCurveRequest request;
  v1::Points* points =
      request.mutable_curve()->mutable_bezier()->mutable_control_points();
  points->set_dimension(3);
  for (double value : {0, 0, 0, 1, 2, 0, 3, 2, 1, 4, 0, 1}) {
    points->add_coordinates(value);
  }
  request.mutable_parameters()->mutable_list()->add_values(0.37);
  return request;
}

v1::EvaluateCurveRequest BulkRequest(int points) {
  v1::EvaluateCurveRequest request;
  v1::BSplineCurve* bspline = request.mutable_curve()->mutable_bspline();
  bspline->set_degree(3);
  const std::vector<double> xyz = freeform::bench::RandomPoints(1, 100, 3);
  bspline->mutable_control_points()->set_dimension(3);
  bspline->mutable_control_points()->mutable_coordinates()->Add(xyz.begin(),
                                                                xyz.end());
  const std::vector<double> knots =
      freeform::bench::ClampedUniformKnots(100, 3);
  bspline->mutable_knots()->Add(knots.begin(), knots.end());
  v1::UniformRange* range = request.mutable_parameters()->mutable_range();
  range->set_start(0);
  range->set_end(1);
  range->set_count(static_cast<uint32_t>(points));
  return request;
}

// One way of making the call; returns the answer's bytes, 0 on failure.
using Call = std::function<size_t()>;

Call GrpcCall(grpc::GenericStub& stub,
              const v1::EvaluateCurveRequest& request) {
  const std::string bytes = request.SerializeAsString();
  return [&stub, bytes] {
    grpc::Slice slice(bytes);
    const grpc::ByteBuffer buffer(&slice, 1);
    grpc::CompletionQueue queue;
    grpc::ClientContext context;
    auto call = stub.PrepareUnaryCall(&context, kEvaluatePath, buffer, &queue);
    call->StartCall();
    grpc::ByteBuffer answer;
    grpc::Status status;
    call->Finish(&answer, &status, &queue);
    void* tag = nullptr;
    bool ok = false;
    queue.Next(&tag, &ok);
    queue.Shutdown();
    while (queue.Next(&tag, &ok)) {
    }
    return status.ok() ? answer.Length() : 0;
  };
}

Call HttpCall(freeform::HttpClient& client, const std::string& url,
              const std::string& content_type, std::string body) {
  return [&client, url, content_type, body = std::move(body)] {
    const freeform::HttpReply reply = client.Post(url, content_type, body);
    return reply.status == 200 ? reply.body.size() : 0;
  };
}

// Measure returns the call times of `iters` calls after `iters / 10 + 1`
// warm-up calls, sorted, in microseconds; empty when a call failed.
std::vector<double> Measure(const Call& call, int iters) {
  for (int i = 0; i < iters / 10 + 1; ++i) {
    if (call() == 0) return {};
  }
  std::vector<double> micros;
  micros.reserve(static_cast<size_t>(iters));
  for (int i = 0; i < iters; ++i) {
    const auto start = Clock::now();
    if (call() == 0) return {};
    micros.push_back(
        std::chrono::duration<double, std::micro>(Clock::now() - start)
            .count());
  }
  std::sort(micros.begin(), micros.end());
  return micros;
}

struct Row {
  std::string name;
  Call grpc, json, proto;
  int iters;
  double target;
  bool bulk;
  double best_grpc = 1e300, best_json = 1e300, best_proto = 1e300;
  size_t json_bytes = 0, grpc_bytes = 0;
};

}  // namespace

int main(int argc, char** argv) {
  absl::ParseCommandLine(argc, argv);
  grpc::ChannelArguments arguments;
  arguments.SetMaxReceiveMessageSize(256 << 20);
  grpc::GenericStub stub(
      grpc::CreateCustomChannel(absl::GetFlag(FLAGS_grpc_target),
                                grpc::InsecureChannelCredentials(), arguments));
  freeform::HttpClient http;
  const std::string url =
      absl::StrCat("http://", absl::GetFlag(FLAGS_http_target), kEvaluatePath);

  std::vector<Row> rows;
  for (const bool bulk : {false, true}) {
    const v1::EvaluateCurveRequest request =
        bulk ? BulkRequest(absl::GetFlag(FLAGS_points)) : S1Request();
    std::string json;
    if (!google::protobuf::util::MessageToJsonString(request, &json).ok()) {
      return 1;
    }
    rows.push_back(
        {.name = bulk ? absl::StrCat("W1 at ", absl::GetFlag(FLAGS_points),
                                     " points, median (ms)")
                      : "S1 one point, p50 (us)",
         .grpc = GrpcCall(stub, request),
         .json = HttpCall(http, url, "application/json", json),
         .proto = HttpCall(http, url, "application/proto",
                           request.SerializeAsString()),
         .iters = bulk ? absl::GetFlag(FLAGS_bulk_iters)
                       : absl::GetFlag(FLAGS_iters),
         .target = bulk ? 3.0 : 2.0,
         .bulk = bulk});
    rows.back().grpc_bytes = rows.back().grpc();
    rows.back().json_bytes = rows.back().json();
  }
  for (int round = 0; round < absl::GetFlag(FLAGS_rounds); ++round) {
    for (Row& row : rows) {
      for (auto [call, best] : {std::pair{&row.grpc, &row.best_grpc},
                                std::pair{&row.json, &row.best_json},
                                std::pair{&row.proto, &row.best_proto}}) {
        const std::vector<double> micros = Measure(*call, row.iters);
        if (micros.empty()) {
          std::fprintf(stderr, "%s: a call failed\n", row.name.c_str());
          return 1;
        }
        const double median = micros[micros.size() / 2];
        *best = std::min(*best, row.bulk ? median / 1000 : median);
      }
    }
  }
  std::printf(
      "| workload | gRPC | HTTP JSON | HTTP proto | JSON/gRPC | target | "
      "proto/gRPC |\n|---|---|---|---|---|---|---|\n");
  for (const Row& row : rows) {
    const double ratio = row.best_json / row.best_grpc;
    std::printf("| %s | %.3g | %.3g | %.3g | %.2fx | <= %.0fx %s | %.2fx |\n",
                row.name.c_str(), row.best_grpc, row.best_json, row.best_proto,
                ratio, row.target, ratio <= row.target ? "ok" : "MISSED",
                row.best_proto / row.best_grpc);
  }
  for (const Row& row : rows) {
    std::printf("\n%s: answer %zu bytes as proto, %zu as JSON",
                row.name.c_str(), row.grpc_bytes, row.json_bytes);
  }
  std::printf("\n");
  return 0;
}
