#include "metrics.h"

#include <CivetServer.h>
#include <civetweb.h>
#include <google/protobuf/descriptor.h>
#include <prometheus/client_metric.h>
#include <prometheus/collectable.h>
#include <prometheus/counter.h>
#include <prometheus/exposer.h>
#include <prometheus/family.h>
#include <prometheus/histogram.h>
#include <prometheus/labels.h>
#include <prometheus/metric_family.h>
#include <prometheus/registry.h>
#include <prometheus/text_serializer.h>

#include <array>
#include <atomic>
#include <cstring>
#include <exception>
#include <utility>

#include "absl/strings/str_cat.h"
#include "freeform_services.h"

namespace freeform::server {
namespace {

using prometheus::Counter;
using prometheus::Family;
using prometheus::Histogram;

constexpr char kMethodLabel[] = "method";
constexpr char kTransportLabel[] = "transport";
constexpr char kUnknownMethod[] = "unknown";

// The gRPC codes: OK (0) to UNAUTHENTICATED (16).
constexpr int kCodes = 17;

// KnownCode maps a code outside gRPC's to UNKNOWN, as gRPC sends it.
absl::StatusCode KnownCode(absl::StatusCode code) {
  const int value = static_cast<int>(code);
  return value >= 0 && value < kCodes ? code : absl::StatusCode::kUnknown;
}

constexpr std::array<Refusal, 3> kRefusals = {
    Refusal::kMemoryBudget, Refusal::kQueueFull, Refusal::kDraining};

const char* RefusalName(Refusal reason) {
  switch (reason) {
    case Refusal::kMemoryBudget:
      return "memory_budget";
    case Refusal::kQueueFull:
      return "queue_full";
    case Refusal::kDraining:
      return "draining";
  }
  return "unknown";
}

prometheus::MetricFamily GaugeFamily(std::string name, std::string help,
                                     double value) {
  prometheus::ClientMetric metric;
  metric.gauge.value = value;
  return {.name = std::move(name),
          .help = std::move(help),
          .type = prometheus::MetricType::Gauge,
          .metric = {std::move(metric)}};
}

constexpr char kMetricsPath[] = "/metrics";

// The endpoint's civetweb: prometheus-cpp's Exposer serves on it. civetweb
// gives each connection a worker thread of its own from the moment it is
// accepted until its request has arrived and been answered, so an idle or
// slow connection holds a worker until request_timeout_ms; with the
// Exposer's 2 workers and civetweb's 30 s, two idle connections stopped
// every scrape for 30 s. Here a request (a scraper sends its few hundred
// bytes at once) must arrive within 1 s, from the accept, and 16 workers
// serve: up to 15 idle connections leave a scrape unaffected, and more
// delay it by 1 s per 16 of them ahead of it in civetweb's queue. No
// keep-alive: each scrape is its own connection.
std::vector<std::string> EndpointCivetwebOptions(const std::string& address) {
  return {"listening_ports",    address, "num_threads",       "16",
          "request_timeout_ms", "1000",  "enable_keep_alive", "no"};
}

// civetweb matches a handler's URI as a case-insensitive prefix of the
// request's path after merging repeated slashes: /metricsX, /METRICS,
// //metrics and /metrics/x would all reach prometheus-cpp's /metrics
// handler. civetweb calls this first for every request: it answers 404 to
// any path (as sent, percent-decoded, without the query) but exactly
// /metrics, and leaves that one to the handler (returns 0).
int AnswerOnlyTheMetricsPath(mg_connection* connection) {
  const mg_request_info* request = mg_get_request_info(connection);
  if (request != nullptr && request->local_uri_raw != nullptr &&
      std::strcmp(request->local_uri_raw, kMetricsPath) == 0) {
    return 0;
  }
  constexpr int kNotFound = 404;
  mg_send_http_error(connection, kNotFound, "Not Found: only %s is served\n",
                     kMetricsPath);
  return kNotFound;
}

}  // namespace

std::vector<std::string> FreeformMethodNames() {
  std::vector<std::string> names;
  for (const char* service_name : FreeformServiceNames()) {
    const google::protobuf::ServiceDescriptor* service =
        google::protobuf::DescriptorPool::generated_pool()->FindServiceByName(
            service_name);
    if (service == nullptr) continue;
    for (int i = 0; i < service->method_count(); ++i) {
      names.push_back(
          absl::StrCat(service->name(), ".", service->method(i)->name()));
    }
  }
  return names;
}

std::vector<double> CallDurationBuckets() {
  return {50e-6, 100e-6, 250e-6, 500e-6, 1e-3, 2.5e-3, 5e-3,
          10e-3, 25e-3,  50e-3,  100e-3, 0.25, 0.5,    1,
          2.5,   5,      10,     30,     60};
}

struct ServerMetrics::Families {
  explicit Families(prometheus::Registry& registry)
      : calls(prometheus::BuildCounter()
                  .Name("freeform_calls_total")
                  .Help("freeform.v1 calls by method, transport (grpc or "
                        "http) and final gRPC code")
                  .Register(registry)),
        duration(prometheus::BuildHistogram()
                     .Name("freeform_call_duration_seconds")
                     .Help("Time from a call's start until its answer (the "
                           "last streamed message and the status) was sent")
                     .Register(registry)),
        request_bytes(prometheus::BuildCounter()
                          .Name("freeform_request_bytes_total")
                          .Help("Serialized bytes of the calls' requests")
                          .Register(registry)),
        response_bytes(prometheus::BuildCounter()
                           .Name("freeform_response_bytes_total")
                           .Help("Serialized bytes of the calls' answers, "
                                 "every streamed message included")
                           .Register(registry)),
        refusals(prometheus::BuildCounter()
                     .Name("freeform_admission_refusals_total")
                     .Help("Calls refused before their work ran, by reason")
                     .Register(registry)) {
    for (Refusal reason : kRefusals) {
      refusal_counters[static_cast<size_t>(reason)] =
          &refusals.Add({{"reason", RefusalName(reason)}});
    }
  }

  Family<Counter>& calls;
  Family<Histogram>& duration;
  Family<Counter>& request_bytes;
  Family<Counter>& response_bytes;
  Family<Counter>& refusals;
  std::array<Counter*, kRefusals.size()> refusal_counters{};
};

// One method's series. The counter of each code is made on the first call
// that ends with it (a series of zeros for every code would be noise),
// then kept.
class ServerMetrics::MethodMetrics final : public MethodObserver {
 public:
  MethodMetrics(std::string name, Transport transport, Families& families)
      : name_(std::move(name)),
        transport_(TransportName(transport)),
        calls_family_(families.calls),
        duration_(families.duration.Add(Labels(), CallDurationBuckets())),
        request_bytes_(families.request_bytes.Add(Labels())),
        response_bytes_(families.response_bytes.Add(Labels())) {
    Calls(absl::StatusCode::kOk);  // rate() needs the series before a call
  }

  const std::string& name() const { return name_; }

  void CallDone(absl::StatusCode code,
                std::chrono::steady_clock::duration elapsed,
                size_t request_bytes, size_t response_bytes) override {
    Calls(code).Increment();
    duration_.Observe(std::chrono::duration<double>(elapsed).count());
    request_bytes_.Increment(static_cast<double>(request_bytes));
    response_bytes_.Increment(static_cast<double>(response_bytes));
  }

 private:
  prometheus::Labels Labels() const {
    return {{kMethodLabel, name_}, {kTransportLabel, transport_}};
  }

  Counter& Calls(absl::StatusCode code) {
    code = KnownCode(code);
    std::atomic<Counter*>& slot = calls_[static_cast<size_t>(code)];
    Counter* counter = slot.load(std::memory_order_acquire);
    if (counter == nullptr) {
      // Family::Add returns the series already made for the same labels,
      // so calls racing here all get one counter.
      prometheus::Labels labels = Labels();
      labels.emplace("code", absl::StatusCodeToString(code));
      counter = &calls_family_.Add(labels);
      slot.store(counter, std::memory_order_release);
    }
    return *counter;
  }

  const std::string name_;
  const std::string transport_;
  Family<Counter>& calls_family_;
  std::array<std::atomic<Counter*>, kCodes> calls_{};
  Histogram& duration_;
  Counter& request_bytes_;
  Counter& response_bytes_;
};

// The gauges read from the server at each scrape.
class ServerMetrics::ReadingsCollector final : public prometheus::Collectable {
 public:
  explicit ReadingsCollector(Readings readings)
      : readings_(std::move(readings)) {}

  std::vector<prometheus::MetricFamily> Collect() const override {
    return {
        GaugeFamily("freeform_calls_in_flight",
                    "freeform.v1 calls started and not yet done",
                    static_cast<double>(readings_.calls_in_flight())),
        GaugeFamily("freeform_pool_queued_tasks",
                    "Tasks of calls (planning, heavy work, stream chunks) "
                    "waiting in the thread pool's queue",
                    static_cast<double>(readings_.tasks_queued())),
        GaugeFamily("freeform_memory_reserved_bytes",
                    "Bytes the calls in flight hold of the memory budget",
                    static_cast<double>(readings_.memory_reserved_bytes())),
        GaugeFamily("freeform_memory_capacity_bytes",
                    "Bytes the calls may reserve together (3/4 of "
                    "--memory_budget)",
                    static_cast<double>(readings_.memory_capacity_bytes)),
    };
  }

 private:
  const Readings readings_;
};

ServerMetrics::ServerMetrics(const std::vector<std::string>& methods,
                             Readings readings,
                             const std::vector<Transport>& transports)
    : registry_(std::make_shared<prometheus::Registry>()),
      families_(std::make_unique<Families>(*registry_)),
      readings_(std::make_shared<ReadingsCollector>(std::move(readings))) {
  for (const std::string& method : methods) {
    if (by_name_.contains(method)) continue;
    const ByTransport series = AddMethod(method, transports);
    by_name_.emplace(methods_.back()->name(), series);
  }
  unknown_ = AddMethod(kUnknownMethod, transports);
}

ServerMetrics::~ServerMetrics() = default;

ServerMetrics::ByTransport ServerMetrics::AddMethod(
    const std::string& method, const std::vector<Transport>& transports) {
  const std::vector<Transport> made =
      transports.empty() ? std::vector<Transport>{Transport::kGrpc}
                         : transports;
  ByTransport series{};
  for (Transport transport : made) {
    methods_.push_back(
        std::make_unique<MethodMetrics>(method, transport, *families_));
    series[static_cast<size_t>(transport)] = methods_.back().get();
  }
  MethodMetrics* const first = series[static_cast<size_t>(made.front())];
  for (MethodMetrics*& slot : series) {
    if (slot == nullptr) slot = first;
  }
  return series;
}

MethodObserver& ServerMetrics::ForMethod(absl::string_view method,
                                         Transport transport) {
  const auto found = by_name_.find(method);
  const ByTransport& series =
      found == by_name_.end() ? unknown_ : found->second;
  return *series[static_cast<size_t>(transport)];
}

void ServerMetrics::Refused(Refusal reason) {
  families_->refusal_counters[static_cast<size_t>(reason)]->Increment();
}

std::vector<std::weak_ptr<prometheus::Collectable>>
ServerMetrics::collectables() const {
  return {registry_, readings_};
}

std::string ServerMetrics::Exposition() const {
  std::vector<prometheus::MetricFamily> families = registry_->Collect();
  for (prometheus::MetricFamily& family : readings_->Collect()) {
    families.push_back(std::move(family));
  }
  return prometheus::TextSerializer().Serialize(families);
}

MetricsEndpoint::MetricsEndpoint(std::unique_ptr<prometheus::Exposer> exposer,
                                 int port)
    : exposer_(std::move(exposer)), port_(port) {}

MetricsEndpoint::~MetricsEndpoint() = default;

absl::StatusOr<std::unique_ptr<MetricsEndpoint>> MetricsEndpoint::Start(
    const std::string& address, const ServerMetrics& metrics) {
  std::unique_ptr<prometheus::Exposer> exposer;
  try {
    // civetweb throws when it cannot bind the address. It copies the
    // callbacks.
    CivetCallbacks callbacks;
    callbacks.begin_request = AnswerOnlyTheMetricsPath;
    exposer = std::make_unique<prometheus::Exposer>(
        EndpointCivetwebOptions(address), &callbacks);
  } catch (const std::exception& error) {
    return absl::UnavailableError(
        absl::StrCat("cannot serve metrics on --metrics_listen=", address,
                     " (HOST:PORT with a numeric host, port 0 for a free "
                     "port): ",
                     error.what()));
  }
  const std::vector<int> ports = exposer->GetListeningPorts();
  if (ports.empty() || ports.front() <= 0) {
    return absl::UnavailableError(absl::StrCat(
        "cannot serve metrics on --metrics_listen=", address, ": no port"));
  }
  for (const std::weak_ptr<prometheus::Collectable>& collectable :
       metrics.collectables()) {
    exposer->RegisterCollectable(collectable, kMetricsPath);
  }
  return std::unique_ptr<MetricsEndpoint>(
      new MetricsEndpoint(std::move(exposer), ports.front()));
}

}  // namespace freeform::server
