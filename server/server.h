// FreeformServer: freeformd's gRPC server, usable in-process by tests.
//
// Start() builds the thread pool, registers CurveService, SurfaceService,
// the standard grpc.health.v1.Health service and (unless turned off) server
// reflection, and listens on the given address, in plaintext or with TLS
// (tls.h) (port 0 picks a free port; port() tells
// which). With a metrics address it also serves Prometheus metrics there
// (metrics.h; metrics_port() tells the port), and with an HTTP address the
// Connect protocol's HTTP/JSON gateway to the same services (http_gateway.h;
// http_port() tells the port). Shutdown() marks health
// NOT_SERVING, lets in-flight RPCs finish within the grace period, then
// stops. Thread-safe after Start().
#ifndef FREEFORM_SERVER_SERVER_H_
#define FREEFORM_SERVER_SERVER_H_

#include <grpcpp/channel.h>
#include <grpcpp/server.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "admission.h"
#include "connection_age.h"
#include "freeform/core/thread_pool.h"
#include "http_gateway.h"
#include "memory_trimmer.h"
#include "rpc.h"
#include "service_limits.h"
#include "tls.h"

namespace freeform::server {

class CurveServiceImpl;
class FaceServiceImpl;
class MetricsEndpoint;
class ServerMetrics;
class SurfaceServiceImpl;

struct ServerOptions {
  std::string listen_address = "0.0.0.0:50051";
  // Pool threads for large batches; 0 means one per hardware thread.
  int threads = 0;
  ServiceLimits limits;
  TlsOptions tls;
  // Serve grpc.reflection.v1alpha.ServerReflection: lists the services and
  // their proto descriptors to any client (grpcurl, grpcui).
  bool reflection = true;
  // HOST:PORT of the Prometheus metrics (http://HOST:PORT/metrics; port 0
  // picks a free port); empty serves none.
  std::string metrics_listen_address;
  // The HTTP gateway (--http_listen); an empty listen_address serves none.
  // It refuses to start beside TLS options it would bypass
  // (CheckHttpListener).
  HttpGatewayOptions http;
  // --max_connection_age and its grace (connection_age.h): clients
  // reconnect, and so re-resolve, at least that often.
  ConnectionAgeOptions connection_age;
};

class FreeformServer {
 public:
  static absl::StatusOr<std::unique_ptr<FreeformServer>> Start(
      const ServerOptions& options);
  ~FreeformServer();

  // port returns the bound port.
  int port() const { return port_; }
  // metrics_port returns the bound port of the metrics, 0 without them.
  int metrics_port() const;
  // http_port returns the bound port of the HTTP gateway, 0 without it.
  int http_port() const {
    return http_gateway_ == nullptr ? 0 : http_gateway_->port();
  }
  // budget returns the server's memory budget (admission.h).
  const MemoryBudget& budget() const { return *budget_; }
  // calls_in_flight counts the freeform calls started and not yet done,
  // and the HTTP requests being answered.
  int64_t calls_in_flight() const {
    return frame_->calls_in_flight() +
           (http_gateway_ == nullptr ? 0 : http_gateway_->requests_in_flight());
  }
  // calls_started counts every freeform call and HTTP request ever started.
  int64_t calls_started() const {
    return frame_->calls_started() +
           (http_gateway_ == nullptr ? 0 : http_gateway_->requests_started());
  }
  // tasks_queued counts the tasks waiting in the pool's queue: the calls'
  // (planning, heavy work, stream chunks) and the helpers of large batches.
  int64_t tasks_queued() const { return static_cast<int64_t>(pool_->queued()); }
  // BeginDrain turns health NOT_SERVING and answers every call that starts
  // from now on with UNAVAILABLE at once, while the calls in flight run on;
  // Shutdown afterwards then finds nothing to cancel.
  void BeginDrain();
  // pool_size returns the number of math threads.
  int pool_size() const { return pool_->size(); }
  // InProcessChannel returns a channel that skips the network.
  std::shared_ptr<grpc::Channel> InProcessChannel();
  // Shutdown drains and stops the server, then the HTTP gateway, once its
  // requests are answered (idempotent).
  void Shutdown(std::chrono::milliseconds grace);
  // Wait blocks until the server has shut down.
  void Wait();

 private:
  FreeformServer() = default;

  // Members are destroyed bottom up, each before what it uses: the gRPC
  // server (its calls report to the metrics) before the metrics, the
  // metrics endpoint (it reads the frame when scraped) before the frame,
  // the HTTP gateway (it calls the gRPC server) before the gRPC server.
  std::unique_ptr<ThreadPool> pool_;
  std::unique_ptr<MemoryBudget> budget_;
  std::unique_ptr<MemoryTrimmer> trimmer_;
  std::unique_ptr<ServerMetrics> metrics_;
  std::unique_ptr<RpcFrame> frame_;
  std::unique_ptr<MetricsEndpoint> metrics_endpoint_;
  std::unique_ptr<CurveServiceImpl> curve_service_;
  std::unique_ptr<SurfaceServiceImpl> surface_service_;
  std::unique_ptr<FaceServiceImpl> face_service_;
  std::unique_ptr<grpc::Server> server_;
  // Calls the gRPC server in-process: destroyed (stopped) before it.
  std::unique_ptr<HttpGateway> http_gateway_;
  int port_ = 0;
  int max_message_bytes_ = 0;
  std::atomic<bool> shut_down_{false};
};

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_SERVER_H_
