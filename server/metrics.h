// ServerMetrics and MetricsEndpoint: freeformd's Prometheus metrics
// (--metrics_listen), with prometheus-cpp.
//
// ServerMetrics is the frame's CallObserver (call_observer.h). It counts
// every freeform.v1 call by method, transport (grpc or http, transport.h)
// and final code, its latency and its request and answer bytes, and admission's
// refusals by reason; the calls in flight, the pool tasks waiting and the
// reserved memory are read from the server when scraped. docs/operations.md
// lists each metric with its labels. The per-method series are made once at
// construction (the calls' codes on first use), so recording a call takes no
// lookup by label: a few atomic adds and the histogram's own lock.
//
// MetricsEndpoint serves them as Prometheus text at http://ADDRESS/metrics
// until it is destroyed: that path exactly (any other gets 404), with
// enough workers and a short request timeout that idle or slow connections
// cannot hold back a scrape for long (metrics.cc).
#ifndef FREEFORM_SERVER_METRICS_H_
#define FREEFORM_SERVER_METRICS_H_

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "call_observer.h"
#include "transport.h"

namespace prometheus {
class Collectable;
class Exposer;
class Registry;
}  // namespace prometheus

namespace freeform::server {

// FreeformMethodNames returns the access log's names of every RPC of
// freeform.v1's CurveService and SurfaceService ("CurveService.Evaluate").
std::vector<std::string> FreeformMethodNames();

// The buckets of freeform_call_duration_seconds: 50 us to 60 s.
std::vector<double> CallDurationBuckets();

class ServerMetrics final : public CallObserver {
 public:
  // The server's state, read at each scrape. Each function must be safe to
  // call from the endpoint's threads while the metrics are served.
  struct Readings {
    std::function<int64_t()> calls_in_flight;
    std::function<int64_t()> tasks_queued;
    std::function<uint64_t()> memory_reserved_bytes;
    uint64_t memory_capacity_bytes = 0;
  };

  // Makes the series of `methods` for each of `transports`; a method not
  // among them is counted as "unknown", a transport not among them as the
  // first of them.
  ServerMetrics(const std::vector<std::string>& methods, Readings readings,
                const std::vector<Transport>& transports = {Transport::kGrpc});
  ~ServerMetrics() override;
  ServerMetrics(const ServerMetrics&) = delete;
  ServerMetrics& operator=(const ServerMetrics&) = delete;

  MethodObserver& ForMethod(absl::string_view method,
                            Transport transport) override;
  void Refused(Refusal reason) override;

  // collectables returns what an endpoint exposes.
  std::vector<std::weak_ptr<prometheus::Collectable>> collectables() const;
  // Exposition returns the metrics in Prometheus' text format, as scraped.
  std::string Exposition() const;

 private:
  class MethodMetrics;
  class ReadingsCollector;
  struct Families;

  std::shared_ptr<prometheus::Registry> registry_;
  std::unique_ptr<Families> families_;
  std::shared_ptr<ReadingsCollector> readings_;
  // One method's series for each transport, indexed by Transport; those of
  // a transport without series point to the first transport's.
  using ByTransport = std::array<MethodMetrics*, kTransports.size()>;

  // AddMethod makes the series of `method` for each of `transports`.
  ByTransport AddMethod(const std::string& method,
                        const std::vector<Transport>& transports);

  std::vector<std::unique_ptr<MethodMetrics>> methods_;
  // Keys view the names held by methods_.
  absl::flat_hash_map<absl::string_view, ByTransport> by_name_;
  ByTransport unknown_{};
};

class MetricsEndpoint {
 public:
  // Start serves `metrics` on `address` (HOST:PORT; port 0 picks a free
  // port) until the endpoint is destroyed; UNAVAILABLE naming
  // --metrics_listen when the address cannot be bound. `metrics` must
  // outlive the endpoint.
  static absl::StatusOr<std::unique_ptr<MetricsEndpoint>> Start(
      const std::string& address, const ServerMetrics& metrics);
  ~MetricsEndpoint();
  MetricsEndpoint(const MetricsEndpoint&) = delete;
  MetricsEndpoint& operator=(const MetricsEndpoint&) = delete;

  // port returns the bound port.
  int port() const { return port_; }

 private:
  MetricsEndpoint(std::unique_ptr<prometheus::Exposer> exposer, int port);

  std::unique_ptr<prometheus::Exposer> exposer_;
  int port_;
};

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_METRICS_H_
