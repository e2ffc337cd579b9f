// transport_echo_server: the bare-transport baseline for service_load. It
// serves freeform.bench.echo.TransportEcho with gRPC's callback API and does
// almost no work per call (a cubic de Casteljau, or a copy of precomputed
// points), so what service_load measures against it is the cost of gRPC on
// this machine, the floor under freeformd's figures.
//
//   transport_echo_server --listen=127.0.0.1:0 [--max_points=2000000]
//                         [--max_seconds=86400]
//
// Prints "listening on 127.0.0.1:PORT" on stdout once it serves (port 0 picks
// a free port). Exits on SIGTERM or SIGINT, or after --max_seconds.
#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "transport_echo.grpc.pb.h"

ABSL_FLAG(std::string, listen, "127.0.0.1:0",
          "Loopback address to listen on; port 0 picks a free port");
ABSL_FLAG(uint32_t, max_points, 2'000'000,
          "Most points a bulk call returns (the precomputed buffer's size)");
ABSL_FLAG(int, max_seconds, 86400, "Exit after this long even without signal");

namespace {

namespace echo = freeform::bench::echo;

constexpr uint32_t kDefaultChunk = 65536;

// The points bulk calls copy from: point i is (t, 2t, 3t + 1), t = i * 1e-6.
class PointSource {
 public:
  explicit PointSource(uint32_t count) : xyz_(3 * size_t{count}) {
    for (uint32_t i = 0; i < count; ++i) {
      const double t = static_cast<double>(i) * 1e-6;
      xyz_[3 * size_t{i}] = t;
      xyz_[3 * size_t{i} + 1] = 2.0 * t;
      xyz_[3 * size_t{i} + 2] = 3.0 * t + 1.0;
    }
  }
  uint32_t size() const { return static_cast<uint32_t>(xyz_.size() / 3); }

  // Replaces resp's points with points [first, first + count).
  void Fill(uint32_t first, uint32_t count, echo::PointsResponse* resp) const {
    auto* xyz = resp->mutable_xyz();
    xyz->Resize(static_cast<int>(3 * count), 0.0);
    std::memcpy(xyz->mutable_data(), xyz_.data() + 3 * size_t{first},
                sizeof(double) * 3 * count);
  }

 private:
  std::vector<double> xyz_;
};

// A cubic Bezier (4 control points, xyz) by de Casteljau at each parameter;
// a malformed request yields an empty answer.
void EvalBezier(const echo::EvalRequest& req, echo::EvalResponse* resp) {
  if (req.control_points_size() != 12) return;
  resp->mutable_xyz()->Reserve(3 * req.params_size());
  for (const double t : req.params()) {
    double p[12];
    std::memcpy(p, req.control_points().data(), sizeof(p));
    for (int level = 3; level > 0; --level) {
      for (int i = 0; i < 3 * level; ++i) p[i] = (1 - t) * p[i] + t * p[i + 3];
    }
    resp->add_xyz(p[0]);
    resp->add_xyz(p[1]);
    resp->add_xyz(p[2]);
  }
}

// Writes points [0, total) in messages of `chunk` points, one at a time.
class ChunkWriter final
    : public grpc::ServerWriteReactor<echo::PointsResponse> {
 public:
  ChunkWriter(const PointSource* source, uint32_t total, uint32_t chunk)
      : source_(source), total_(total), chunk_(chunk) {
    Next();
  }
  void OnWriteDone(bool ok) override {
    if (ok) {
      Next();
    } else {
      Finish(grpc::Status(grpc::StatusCode::CANCELLED, "write failed"));
    }
  }
  void OnDone() override { delete this; }

 private:
  void Next() {
    if (sent_ >= total_) {
      Finish(grpc::Status::OK);
      return;
    }
    const uint32_t count = std::min(chunk_, total_ - sent_);
    source_->Fill(sent_, count, &message_);
    sent_ += count;
    StartWrite(&message_);
  }

  const PointSource* const source_;
  const uint32_t total_;
  const uint32_t chunk_;
  uint32_t sent_ = 0;
  echo::PointsResponse message_;
};

class EchoService final : public echo::TransportEcho::CallbackService {
 public:
  explicit EchoService(const PointSource* source) : source_(source) {}

  grpc::ServerUnaryReactor* Eval(grpc::CallbackServerContext* context,
                                 const echo::EvalRequest* request,
                                 echo::EvalResponse* response) override {
    EvalBezier(*request, response);
    return Done(context);
  }
  grpc::ServerUnaryReactor* BulkPoints(
      grpc::CallbackServerContext* context, const echo::BulkRequest* request,
      echo::PointsResponse* response) override {
    source_->Fill(0, Clamp(request->num_points()), response);
    return Done(context);
  }
  grpc::ServerWriteReactor<echo::PointsResponse>* BulkPointsStream(
      grpc::CallbackServerContext*, const echo::BulkRequest* request) override {
    const uint32_t chunk =
        request->chunk_points() ? request->chunk_points() : kDefaultChunk;
    return new ChunkWriter(source_, Clamp(request->num_points()),
                           std::min(chunk, source_->size()));
  }

 private:
  static grpc::ServerUnaryReactor* Done(grpc::CallbackServerContext* context) {
    grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
    reactor->Finish(grpc::Status::OK);
    return reactor;
  }
  uint32_t Clamp(uint32_t points) const {
    return std::min(points, source_->size());
  }

  const PointSource* const source_;
};

// Blocks SIGTERM and SIGINT in this thread and every thread started later,
// so WaitForStop() can take them.
sigset_t BlockStopSignals() {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  return signals;
}

void WaitForStop(const sigset_t& signals, int max_seconds) {
  timespec timeout{.tv_sec = std::max(max_seconds, 1), .tv_nsec = 0};
  sigtimedwait(&signals, nullptr, &timeout);
}

}  // namespace

int main(int argc, char** argv) {
  absl::ParseCommandLine(argc, argv);
  const std::string listen = absl::GetFlag(FLAGS_listen);
  if (listen.rfind("127.0.0.1:", 0) != 0) {
    std::fprintf(stderr, "--listen must be 127.0.0.1:PORT\n");
    return 2;
  }
  const sigset_t stop_signals = BlockStopSignals();
  const PointSource source(absl::GetFlag(FLAGS_max_points));
  EchoService service(&source);

  grpc::ServerBuilder builder;
  int port = 0;
  builder.AddListeningPort(listen, grpc::InsecureServerCredentials(), &port);
  builder.RegisterService(&service);
  std::unique_ptr<grpc::Server> server = builder.BuildAndStart();
  if (!server || port == 0) {
    std::fprintf(stderr, "cannot listen on %s\n", listen.c_str());
    return 1;
  }
  std::printf("listening on 127.0.0.1:%d\n", port);
  std::fflush(stdout);

  WaitForStop(stop_signals, absl::GetFlag(FLAGS_max_seconds));
  server->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(2));
  server->Wait();
  return 0;
}
