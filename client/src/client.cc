#include "freeform/client.h"

#include <grpcpp/create_channel.h>
#include <grpcpp/security/credentials.h>

#include <string>
#include <vector>

#include "absl/strings/cord.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "freeform/io/file.h"
#include "google/rpc/error_details.pb.h"
#include "google/rpc/status.pb.h"
#include "grpc/health/v1/health.grpc.pb.h"

namespace freeform {
namespace {

constexpr absl::string_view kStatusDetailsPayload =
    "type.googleapis.com/google.rpc.Status";

// Retries UNAVAILABLE with exponential backoff on every freeform method.
constexpr char kRetryMethodConfig[] = R"("methodConfig": [{
    "name": [{"service": "freeform.v1.CurveService"},
             {"service": "freeform.v1.SurfaceService"},
             {"service": "freeform.v1.FaceService"}],
    "retryPolicy": {
      "maxAttempts": 4,
      "initialBackoff": "0.05s",
      "maxBackoff": "1s",
      "backoffMultiplier": 2,
      "retryableStatusCodes": ["UNAVAILABLE"]
    }
  }])";

// ServiceConfig returns the channel's service config: pick_first, or
// round_robin over several addresses with client-side health checking
// (gRPC proposal A17: each connection watches grpc.health.v1.Health, and
// a replica that reports NOT_SERVING, as a draining freeformd does at
// once, gets no new call), and the retry policy unless it is off.
std::string ServiceConfig(const ClientOptions& options) {
  const bool balance = options.round_robin || !options.replicas.empty();
  std::vector<std::string> parts = {
      absl::StrCat(R"("loadBalancingConfig": [{")",
                   balance ? "round_robin" : "pick_first", R"(": {}}])")};
  if (balance)
    parts.emplace_back(R"("healthCheckConfig": {"serviceName": ""})");
  if (options.retry_unavailable) parts.emplace_back(kRetryMethodConfig);
  return absl::StrCat("{", absl::StrJoin(parts, ", "), "}");
}

// ReadCredentialFile reads a certificate, key or CA file of at most
// kMaxCredentialFileBytes (freeform/io/file.h).
absl::StatusOr<std::string> ReadCredentialFile(const std::string& path) {
  return ReadRegularFile(path, kMaxCredentialFileBytes);
}

absl::StatusOr<std::shared_ptr<grpc::ChannelCredentials>> Credentials(
    const ClientOptions& options) {
  if (!options.use_tls) return grpc::InsecureChannelCredentials();
  grpc::SslCredentialsOptions ssl;
  if (!options.root_ca_file.empty()) {
    absl::StatusOr<std::string> ca = ReadCredentialFile(options.root_ca_file);
    if (!ca.ok()) return ca.status();
    ssl.pem_root_certs = *ca;
  }
  if (!options.cert_file.empty()) {
    absl::StatusOr<std::string> cert = ReadCredentialFile(options.cert_file);
    if (!cert.ok()) return cert.status();
    absl::StatusOr<std::string> key = ReadCredentialFile(options.key_file);
    if (!key.ok()) return key.status();
    ssl.pem_cert_chain = *cert;
    ssl.pem_private_key = *key;
  }
  return grpc::SslCredentials(ssl);
}

std::string ChannelTarget(const ClientOptions& options) {
  if (options.replicas.empty()) return options.target;
  return absl::StrCat("ipv4:", absl::StrJoin(options.replicas, ","));
}

// Appends one response's derivative arrays to `samples`.
absl::Status Append(const v1::EvaluateCurveResponse& response,
                    CurveSamples& samples) {
  if (samples.derivatives.empty()) {
    samples.dimension = static_cast<int>(response.dimension());
    samples.derivatives.resize(
        static_cast<size_t>(response.derivatives_size()));
  }
  if (static_cast<size_t>(response.derivatives_size()) !=
          samples.derivatives.size() ||
      response.first_index() != samples.count) {
    return absl::DataLossError("the server sent inconsistent chunks");
  }
  for (int k = 0; k < response.derivatives_size(); ++k) {
    const auto& coordinates = response.derivatives(k).coordinates();
    samples.derivatives[static_cast<size_t>(k)].insert(
        samples.derivatives[static_cast<size_t>(k)].end(), coordinates.begin(),
        coordinates.end());
  }
  samples.count += response.count();
  return absl::OkStatus();
}

// Appends one surface response to `evaluation`.
absl::Status AppendSurface(const v1::EvaluateSurfaceResponse& response,
                           SurfaceEvaluation& evaluation) {
  if (evaluation.partials.empty()) {
    evaluation.dimension = static_cast<int>(response.dimension());
    for (const v1::PartialDerivative& partial : response.partials()) {
      evaluation.partials.push_back(
          {.order_u = static_cast<int>(partial.order_u()),
           .order_v = static_cast<int>(partial.order_v()),
           .values = {}});
    }
  }
  if (static_cast<size_t>(response.partials_size()) !=
          evaluation.partials.size() ||
      response.first_index() != evaluation.count) {
    return absl::DataLossError("the server sent inconsistent chunks");
  }
  for (int k = 0; k < response.partials_size(); ++k) {
    const auto& values = response.partials(k).values().coordinates();
    std::vector<double>& into =
        evaluation.partials[static_cast<size_t>(k)].values;
    into.insert(into.end(), values.begin(), values.end());
  }
  const auto& normals = response.normals().coordinates();
  evaluation.normals.insert(evaluation.normals.end(), normals.begin(),
                            normals.end());
  evaluation.count += response.count();
  return absl::OkStatus();
}

// Hands every chunk of a server stream to `on_chunk`, checking that each
// starts where the one before ended; a failing `on_chunk` cancels the call.
template <typename Response>
absl::Status ForEachChunk(
    grpc::ClientContext& context, grpc::ClientReader<Response>& reader,
    absl::FunctionRef<absl::Status(const Response&)> on_chunk) {
  Response response;
  absl::Status handled;
  uint64_t next_index = 0;
  while (reader.Read(&response)) {
    handled = response.first_index() == next_index
                  ? on_chunk(response)
                  : absl::DataLossError("the server sent inconsistent chunks");
    if (!handled.ok()) {
      context.TryCancel();
      break;
    }
    next_index += response.count();
  }
  grpc::Status status = reader.Finish();
  if (!handled.ok()) return handled;
  return FromGrpcStatus(status);
}

// Reads every chunk of a server stream into one result.
template <typename Response, typename Result>
absl::StatusOr<Result> ReadChunks(grpc::ClientContext& context,
                                  grpc::ClientReader<Response>& reader,
                                  absl::Status (*append)(const Response&,
                                                         Result&)) {
  Result result;
  absl::Status status = ForEachChunk<Response>(
      context, reader,
      [&](const Response& response) { return append(response, result); });
  if (!status.ok()) return status;
  return result;
}

}  // namespace

absl::Span<const double> SurfaceEvaluation::Point(int order_u, int order_v,
                                                  size_t index) const {
  for (const Partial& partial : partials) {
    if (partial.order_u == order_u && partial.order_v == order_v) {
      return absl::MakeConstSpan(partial.values)
          .subspan(index * static_cast<size_t>(dimension),
                   static_cast<size_t>(dimension));
    }
  }
  return {};
}

absl::Status FromGrpcStatus(const grpc::Status& status) {
  if (status.ok()) return absl::OkStatus();
  absl::Status converted(static_cast<absl::StatusCode>(status.error_code()),
                         status.error_message());
  if (!status.error_details().empty()) {
    converted.SetPayload(kStatusDetailsPayload,
                         absl::Cord(status.error_details()));
  }
  return converted;
}

std::vector<FieldViolation> FieldViolationsOf(const absl::Status& status) {
  std::vector<FieldViolation> violations;
  auto payload = status.GetPayload(kStatusDetailsPayload);
  google::rpc::Status details;
  if (!payload.has_value() || !details.ParseFromString(std::string(*payload))) {
    return violations;
  }
  for (const google::protobuf::Any& detail : details.details()) {
    google::rpc::BadRequest bad_request;
    if (!detail.UnpackTo(&bad_request)) continue;
    for (const auto& violation : bad_request.field_violations()) {
      violations.push_back({violation.field(), violation.description()});
    }
  }
  return violations;
}

absl::StatusOr<std::unique_ptr<Client>> Client::Create(
    const ClientOptions& options) {
  absl::StatusOr<std::shared_ptr<grpc::ChannelCredentials>> credentials =
      Credentials(options);
  if (!credentials.ok()) return credentials.status();
  grpc::ChannelArguments arguments;
  arguments.SetMaxReceiveMessageSize(options.max_receive_message_bytes);
  if (options.stream_window_bytes > 0) {
    arguments.SetInt(GRPC_ARG_HTTP2_BDP_PROBE, 0);
    arguments.SetInt(GRPC_ARG_HTTP2_STREAM_LOOKAHEAD_BYTES,
                     options.stream_window_bytes);
  }
  if (options.min_time_between_resolutions.count() > 0) {
    arguments.SetInt(
        GRPC_ARG_DNS_MIN_TIME_BETWEEN_RESOLUTIONS_MS,
        static_cast<int>(options.min_time_between_resolutions.count()));
  }
  arguments.SetServiceConfigJSON(ServiceConfig(options));
  auto channel = grpc::CreateCustomChannel(ChannelTarget(options), *credentials,
                                           arguments);
  return std::make_unique<Client>(std::move(channel), options);
}

Client::Client(std::shared_ptr<grpc::Channel> channel,
               const ClientOptions& options)
    : options_(options),
      channel_(std::move(channel)),
      curves_(v1::CurveService::NewStub(channel_)),
      surfaces_(v1::SurfaceService::NewStub(channel_)),
      faces_(v1::FaceService::NewStub(channel_)) {}

std::unique_ptr<grpc::ClientContext> Client::NewContext() const {
  auto context = std::make_unique<grpc::ClientContext>();
  context->set_deadline(std::chrono::system_clock::now() + options_.timeout);
  return context;
}

absl::StatusOr<CurveSamples> Client::EvaluateBezier(
    int dimension, absl::Span<const double> control_points,
    absl::Span<const double> parameters, int derivative_order) {
  v1::EvaluateCurveRequest request;
  v1::Points* points =
      request.mutable_curve()->mutable_bezier()->mutable_control_points();
  points->set_dimension(static_cast<uint32_t>(dimension));
  points->mutable_coordinates()->Add(control_points.begin(),
                                     control_points.end());
  request.mutable_parameters()->mutable_list()->mutable_values()->Add(
      parameters.begin(), parameters.end());
  request.set_derivative_order(static_cast<uint32_t>(derivative_order));
  return EvaluateCurve(request);
}

absl::StatusOr<CurveSamples> Client::EvaluateCurve(
    const v1::EvaluateCurveRequest& request) {
  std::unique_ptr<grpc::ClientContext> context = NewContext();
  v1::EvaluateCurveResponse response;
  if (grpc::Status status =
          curves_->Evaluate(context.get(), request, &response);
      !status.ok()) {
    return FromGrpcStatus(status);
  }
  CurveSamples samples;
  if (absl::Status status = Append(response, samples); !status.ok()) {
    return status;
  }
  return samples;
}

absl::StatusOr<CurveSamples> Client::EvaluateCurveStreamed(
    const v1::EvaluateCurveRequest& request) {
  std::unique_ptr<grpc::ClientContext> context = NewContext();
  std::unique_ptr<grpc::ClientReader<v1::EvaluateCurveResponse>> reader =
      curves_->EvaluateStream(context.get(), request);
  return ReadChunks(*context, *reader, &Append);
}

absl::Status Client::EvaluateCurveStream(
    const v1::EvaluateCurveRequest& request,
    absl::FunctionRef<absl::Status(const v1::EvaluateCurveResponse&)>
        on_chunk) {
  std::unique_ptr<grpc::ClientContext> context = NewContext();
  std::unique_ptr<grpc::ClientReader<v1::EvaluateCurveResponse>> reader =
      curves_->EvaluateStream(context.get(), request);
  return ForEachChunk(*context, *reader, on_chunk);
}

absl::StatusOr<SurfaceEvaluation> Client::EvaluateSurface(
    const v1::EvaluateSurfaceRequest& request) {
  std::unique_ptr<grpc::ClientContext> context = NewContext();
  v1::EvaluateSurfaceResponse response;
  if (grpc::Status status =
          surfaces_->Evaluate(context.get(), request, &response);
      !status.ok()) {
    return FromGrpcStatus(status);
  }
  SurfaceEvaluation evaluation;
  if (absl::Status status = AppendSurface(response, evaluation); !status.ok()) {
    return status;
  }
  return evaluation;
}

absl::StatusOr<SurfaceEvaluation> Client::EvaluateSurfaceStreamed(
    const v1::EvaluateSurfaceRequest& request) {
  std::unique_ptr<grpc::ClientContext> context = NewContext();
  std::unique_ptr<grpc::ClientReader<v1::EvaluateSurfaceResponse>> reader =
      surfaces_->EvaluateStream(context.get(), request);
  return ReadChunks(*context, *reader, &AppendSurface);
}

absl::Status Client::EvaluateSurfaceStream(
    const v1::EvaluateSurfaceRequest& request,
    absl::FunctionRef<absl::Status(const v1::EvaluateSurfaceResponse&)>
        on_chunk) {
  std::unique_ptr<grpc::ClientContext> context = NewContext();
  std::unique_ptr<grpc::ClientReader<v1::EvaluateSurfaceResponse>> reader =
      surfaces_->EvaluateStream(context.get(), request);
  return ForEachChunk(*context, *reader, on_chunk);
}

absl::StatusOr<BasisSamples> Client::EvaluateSurfaceBasis(
    const v1::EvaluateSurfaceBasisRequest& request) {
  std::unique_ptr<grpc::ClientContext> context = NewContext();
  v1::EvaluateSurfaceBasisResponse response;
  if (grpc::Status status =
          surfaces_->EvaluateBasis(context.get(), request, &response);
      !status.ok()) {
    return FromGrpcStatus(status);
  }
  return BasisSamples{.function_count = response.function_count(),
                      .count = response.count(),
                      .derivatives = {std::vector<double>(
                          response.values().begin(), response.values().end())}};
}

absl::StatusOr<BasisSamples> Client::EvaluateBasis(
    const v1::EvaluateBasisRequest& request) {
  std::unique_ptr<grpc::ClientContext> context = NewContext();
  v1::EvaluateBasisResponse response;
  if (grpc::Status status =
          curves_->EvaluateBasis(context.get(), request, &response);
      !status.ok()) {
    return FromGrpcStatus(status);
  }
  BasisSamples samples{.function_count = response.function_count(),
                       .count = response.count(),
                       .derivatives = {}};
  for (const v1::BasisValues& values : response.derivatives()) {
    samples.derivatives.emplace_back(values.values().begin(),
                                     values.values().end());
  }
  return samples;
}

absl::Status Client::CheckHealth(const std::string& service) {
  auto stub = grpc::health::v1::Health::NewStub(channel_);
  std::unique_ptr<grpc::ClientContext> context = NewContext();
  grpc::health::v1::HealthCheckRequest request;
  request.set_service(service);
  grpc::health::v1::HealthCheckResponse response;
  if (grpc::Status status = stub->Check(context.get(), request, &response);
      !status.ok()) {
    return FromGrpcStatus(status);
  }
  if (response.status() != grpc::health::v1::HealthCheckResponse::SERVING) {
    return absl::UnavailableError(
        absl::StrCat("not serving: ",
                     grpc::health::v1::HealthCheckResponse::ServingStatus_Name(
                         response.status())));
  }
  return absl::OkStatus();
}

}  // namespace freeform
