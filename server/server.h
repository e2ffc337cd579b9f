// FreeformServer: freeformd's gRPC server, usable in-process by tests.
//
// Start() builds the thread pool, registers CurveService, SurfaceService,
// the standard grpc.health.v1.Health service and server reflection, and
// listens on the given address (port 0 picks a free port; port() tells
// which). Shutdown() marks health NOT_SERVING, lets in-flight RPCs finish
// within the grace period, then stops. Thread-safe after Start().
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
#include "freeform/core/thread_pool.h"
#include "memory_trimmer.h"
#include "rpc.h"
#include "service_limits.h"

namespace freeform::server {

class CurveServiceImpl;
class SurfaceServiceImpl;

struct TlsOptions {
  // PEM files; TLS is on when cert and key are both set.
  std::string cert_file;
  std::string key_file;
  // With a client CA, clients must present a certificate it signed (mTLS).
  std::string client_ca_file;
};

struct ServerOptions {
  std::string listen_address = "0.0.0.0:50051";
  // Pool threads for large batches; 0 means one per hardware thread.
  int threads = 0;
  ServiceLimits limits;
  TlsOptions tls;
};

class FreeformServer {
 public:
  static absl::StatusOr<std::unique_ptr<FreeformServer>> Start(
      const ServerOptions& options);
  ~FreeformServer();

  // port returns the bound port.
  int port() const { return port_; }
  // budget returns the server's memory budget (admission.h).
  const MemoryBudget& budget() const { return *budget_; }
  // calls_in_flight counts the freeform calls started and not yet done.
  int64_t calls_in_flight() const { return frame_->calls_in_flight(); }
  // calls_started counts every freeform call ever started.
  int64_t calls_started() const { return frame_->calls_started(); }
  // BeginDrain turns health NOT_SERVING and answers every call that starts
  // from now on with UNAVAILABLE at once, while the calls in flight run on;
  // Shutdown afterwards then finds nothing to cancel.
  void BeginDrain();
  // pool_size returns the number of math threads.
  int pool_size() const { return pool_->size(); }
  // InProcessChannel returns a channel that skips the network.
  std::shared_ptr<grpc::Channel> InProcessChannel();
  // Shutdown drains and stops the server (idempotent).
  void Shutdown(std::chrono::milliseconds grace);
  // Wait blocks until the server has shut down.
  void Wait();

 private:
  FreeformServer() = default;

  std::unique_ptr<ThreadPool> pool_;
  std::unique_ptr<MemoryBudget> budget_;
  std::unique_ptr<MemoryTrimmer> trimmer_;
  std::unique_ptr<RpcFrame> frame_;
  std::unique_ptr<CurveServiceImpl> curve_service_;
  std::unique_ptr<SurfaceServiceImpl> surface_service_;
  std::unique_ptr<grpc::Server> server_;
  int port_ = 0;
  int max_message_bytes_ = 0;
  std::atomic<bool> shut_down_{false};
};

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_SERVER_H_
