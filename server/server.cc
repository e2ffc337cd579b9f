#include "server.h"

#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/health_check_service_interface.h>
#include <grpcpp/impl/server_builder_option.h>
#include <grpcpp/security/server_credentials.h>
#include <grpcpp/server_builder.h>

#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "curve_service.h"
#include "face_service.h"
#include "freeform_services.h"
#include "grpc_handoff.h"
#include "metrics.h"
#include "parse_errors.h"
#include "surface_service.h"

namespace freeform::server {
namespace {

// Memory released by calls before an idle server hands it back.
constexpr uint64_t kTrimAfterReleasedBytes = 64ull << 20;

// ReflectionOption gives one server exactly one server reflection plugin,
// or none. Linking gRPC's reflection library registers its plugin for every
// server the process builds (a static initializer calls
// InitProtoReflectionServerBuilderPlugin), with no switch to leave it out:
// the option removes what the builder got from there and adds its own.
class ReflectionOption final : public grpc::ServerBuilderOption {
 public:
  explicit ReflectionOption(bool enabled) : enabled_(enabled) {}

  void UpdateArguments(grpc::ChannelArguments* /*arguments*/) override {}
  void UpdatePlugins(std::vector<std::unique_ptr<grpc::ServerBuilderPlugin>>*
                         plugins) override {
    auto reflection =
        std::make_unique<grpc::reflection::ProtoServerReflectionPlugin>();
    const std::string name = reflection->name();
    std::erase_if(*plugins,
                  [&](const auto& plugin) { return plugin->name() == name; });
    if (enabled_) plugins->push_back(std::move(reflection));
  }

 private:
  const bool enabled_;
};

// ServedServices returns the full names of the services of the server
// `options` describe.
std::vector<std::string> ServedServices(const ServerOptions& options) {
  const auto names = FreeformServiceNames();
  std::vector<std::string> services(names.begin(), names.end());
  services.push_back("grpc.health.v1.Health");
  if (options.reflection) {
    services.push_back("grpc.reflection.v1alpha.ServerReflection");
  }
  return services;
}

// MakeMetrics returns the metrics of `server`, which read its frame and
// budget when scraped.
std::unique_ptr<ServerMetrics> MakeMetrics(const FreeformServer& server,
                                           const MemoryBudget& budget,
                                           bool http) {
  std::vector<Transport> transports = {Transport::kGrpc};
  if (http) transports.push_back(Transport::kHttp);
  return std::make_unique<ServerMetrics>(
      FreeformMethodNames(),
      ServerMetrics::Readings{
          .calls_in_flight = [&server] { return server.calls_in_flight(); },
          .tasks_queued = [&server] { return server.tasks_queued(); },
          .memory_reserved_bytes = [&budget] { return budget.in_use(); },
          .memory_capacity_bytes = budget.capacity()},
      transports);
}

}  // namespace

absl::StatusOr<std::unique_ptr<FreeformServer>> FreeformServer::Start(
    const ServerOptions& options) {
  if (absl::Status status = CheckHttpListener(options.http, options.tls);
      !status.ok()) {
    return status;
  }
  if (absl::Status status = CheckConnectionAge(options.connection_age);
      !status.ok()) {
    return status;
  }
  absl::StatusOr<std::shared_ptr<grpc::ServerCredentials>> credentials =
      ListenerCredentials(options.tls);
  if (!credentials.ok()) return credentials.status();
  const bool http = !options.http.listen_address.empty();

  std::unique_ptr<FreeformServer> server(new FreeformServer());
  const int threads =
      options.threads > 0
          ? options.threads
          : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  server->pool_ = std::make_unique<ThreadPool>(threads);
  server->budget_ =
      std::make_unique<MemoryBudget>(options.limits.memory_budget_bytes);
  server->trimmer_ = std::make_unique<MemoryTrimmer>(
      server->budget_.get(), kTrimAfterReleasedBytes, std::chrono::seconds(1));
  if (!options.metrics_listen_address.empty()) {
    server->metrics_ = MakeMetrics(*server, *server->budget_, http);
  }
  server->frame_ =
      std::make_unique<RpcFrame>(server->pool_.get(), server->budget_.get(),
                                 options.limits, server->metrics_.get());
  server->curve_service_ =
      std::make_unique<CurveServiceImpl>(server->frame_.get());
  server->surface_service_ =
      std::make_unique<SurfaceServiceImpl>(server->frame_.get());
  server->face_service_ =
      std::make_unique<FaceServiceImpl>(server->frame_.get());

  grpc::EnableDefaultHealthCheckService(true);
  grpc::ServerBuilder builder;
  builder.SetOption(std::make_unique<ReflectionOption>(options.reflection));
  const int max_message = static_cast<int>(options.limits.max_message_bytes);
  server->max_message_bytes_ = max_message;
  builder.SetMaxReceiveMessageSize(max_message);
  builder.SetMaxSendMessageSize(max_message);
  for (const auto& [name, value] :
       ConnectionAgeArguments(options.connection_age)) {
    builder.AddChannelArgument(name, value);
  }
  builder.AddListeningPort(options.listen_address, *credentials,
                           &server->port_);
  std::vector<
      std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface>>
      interceptors;
  interceptors.push_back(
      std::make_unique<ParseErrorInterceptorFactory>(ServedServices(options)));
  // Every call starts with the factory making its interceptor: from then on
  // the call's thread sees the server built here (grpc_handoff.h).
  HandOffToGrpc(interceptors.back().get());
  builder.experimental().SetInterceptorCreators(std::move(interceptors));
  builder.RegisterService(server->curve_service_.get());
  builder.RegisterService(server->surface_service_.get());
  builder.RegisterService(server->face_service_.get());
  server->server_ = builder.BuildAndStart();
  if (server->server_ == nullptr || server->port_ == 0) {
    return absl::UnavailableError(
        absl::StrCat("cannot listen on ", options.listen_address));
  }
  if (server->metrics_ != nullptr) {
    absl::StatusOr<std::unique_ptr<MetricsEndpoint>> endpoint =
        MetricsEndpoint::Start(options.metrics_listen_address,
                               *server->metrics_);
    if (!endpoint.ok()) return endpoint.status();
    server->metrics_endpoint_ = *std::move(endpoint);
  }
  if (http) {
    absl::StatusOr<std::unique_ptr<HttpGateway>> gateway = HttpGateway::Start(
        options.http, server->InProcessChannel(), server->budget_.get());
    if (!gateway.ok()) return gateway.status();
    server->http_gateway_ = *std::move(gateway);
  }
  if (grpc::HealthCheckServiceInterface* health =
          server->server_->GetHealthCheckService();
      health != nullptr) {
    health->SetServingStatus("", true);
    for (const char* name : FreeformServiceNames()) {
      health->SetServingStatus(name, true);
    }
  }
  return server;
}

FreeformServer::~FreeformServer() {
  Shutdown(std::chrono::milliseconds(0));
  // gRPC's Shutdown returns after the last handler has returned. Each one
  // handed the frame over on entering it (RpcFrame::Unary, Stream), after
  // gRPC's generated code read the service's vtable to call it, so the
  // services can now be destroyed (grpc_handoff.h).
  if (frame_ != nullptr) TakeBackFromGrpc(frame_.get());
}

int FreeformServer::metrics_port() const {
  return metrics_endpoint_ == nullptr ? 0 : metrics_endpoint_->port();
}

std::shared_ptr<grpc::Channel> FreeformServer::InProcessChannel() {
  grpc::ChannelArguments arguments;
  arguments.SetMaxReceiveMessageSize(max_message_bytes_);
  return server_->InProcessChannel(arguments);
}

void FreeformServer::BeginDrain() {
  if (grpc::HealthCheckServiceInterface* health =
          server_->GetHealthCheckService();
      health != nullptr) {
    health->Shutdown();  // every service reports NOT_SERVING from now on
  }
  frame_->BeginDrain();
}

void FreeformServer::Shutdown(std::chrono::milliseconds grace) {
  // A server whose Start failed to listen has no gRPC server to stop.
  if (shut_down_.exchange(true) || server_ == nullptr) return;
  if (grpc::HealthCheckServiceInterface* health =
          server_->GetHealthCheckService();
      health != nullptr) {
    health->Shutdown();  // every service reports NOT_SERVING from now on
  }
  server_->Shutdown(std::chrono::system_clock::now() + grace);
  // Requests that arrive from now on get UNAVAILABLE from the stopped
  // server; those being answered finish writing before Stop returns.
  if (http_gateway_ != nullptr) http_gateway_->Stop();
}

void FreeformServer::Wait() {
  if (server_ != nullptr) server_->Wait();
}

}  // namespace freeform::server
