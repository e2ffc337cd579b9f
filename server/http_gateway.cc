#include "http_gateway.h"

#include <arpa/inet.h>
#include <civetweb.h>
#include <google/protobuf/util/json_util.h>

#include <array>
#include <exception>
#include <utility>

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/strip.h"
#include "connect_protocol.h"
#include "cors_policy.h"
#include "http_exchange.h"
#include "proto_json.h"
#include "spdlog/spdlog.h"
#include "static_files.h"

namespace freeform::server {
// Outside the anonymous namespace: HttpGateway::Call holds a Codec.
namespace gateway_codec {

// The codecs of a request: proto or JSON, bare (unary) or enveloped
// (streaming).
struct Codec {
  bool json = true;
  bool enveloped = false;
};

// MediaTypeOf returns the media type of a Content-Type value, lower case,
// without its parameters ("application/json; charset=utf-8" gives
// "application/json").
std::string MediaTypeOf(absl::string_view content_type) {
  const size_t semicolon = content_type.find(';');
  return absl::AsciiStrToLower(
      absl::StripAsciiWhitespace(content_type.substr(0, semicolon)));
}

// CodecOf returns the codec of `content_type` for `method`; nullopt when
// the method does not take it (415).
std::optional<Codec> CodecOf(absl::string_view content_type,
                             const GatewayMethod& method) {
  const std::string type = MediaTypeOf(content_type);
  if (method.server_streaming) {
    if (type == "application/connect+json") return Codec{true, true};
    if (type == "application/connect+proto") return Codec{false, true};
  } else {
    if (type == "application/json") return Codec{true, false};
    if (type == "application/proto") return Codec{false, false};
  }
  return std::nullopt;
}

absl::string_view ContentTypeOf(const Codec& codec) {
  if (codec.enveloped) {
    return codec.json ? "application/connect+json"
                      : "application/connect+proto";
  }
  return codec.json ? "application/json" : "application/proto";
}

}  // namespace gateway_codec

namespace {

using gateway_codec::Codec;
using gateway_codec::CodecOf;
using gateway_codec::ContentTypeOf;

// The gateway's civetweb. Each connection holds a worker from its accept
// until it closes, so a kept-alive connection that goes quiet is closed
// after 1 s; a request must arrive, and each write of an answer go out,
// within request_timeout_ms. 32 workers serve 32 connections at once, the
// next wait in civetweb's queue. civetweb's own CORS answers are off: the
// gateway sends CORS headers only as --http_cors_origins says.
// Answers go out at once (no Nagle delay: headers and body are two writes,
// which with delayed ACKs would wait 40 ms).
// clang-format off
constexpr std::array<const char*, 16> kCivetwebOptions = {
    "tcp_nodelay", "1",
    "num_threads", "32",
    "request_timeout_ms", "30000",
    "enable_keep_alive", "yes",
    "keep_alive_timeout_ms", "1000",
    "access_control_allow_origin", "",
    "access_control_allow_methods", "",
    "access_control_allow_headers", ""};
// clang-format on

// The memory a request holds while it is converted and called, per byte of
// its body: the body, the parsed message, its serialized copy.
constexpr uint64_t kRequestMemoryPerByte = 3;
// The memory of a JSON answer per byte of the serialized one: the parsed
// message and its JSON text (up to about 24 characters per 8-byte double).
constexpr uint64_t kJsonAnswerMemoryPerByte = 5;

grpc::Status ToGrpc(const absl::Status& status) {
  return grpc::Status(static_cast<grpc::StatusCode>(status.code()),
                      std::string(status.message()));
}

// LogRefusal writes the access-log line of a request the gateway answered
// by itself, before any call.
void LogRefusal(absl::string_view method, const HttpExchange& exchange,
                const grpc::Status& status) {
  spdlog::info("rpc method={} transport=http peer={} status={} error=\"{}\"",
               std::string(method), exchange.client(),
               absl::StatusCodeToString(
                   static_cast<absl::StatusCode>(status.error_code())),
               status.error_message());
}

// IsLoopback is true for a host of the loopback range: localhost,
// 127.0.0.0/8, ::1.
bool IsLoopback(absl::string_view host) {
  if (absl::ConsumePrefix(&host, "[")) absl::ConsumeSuffix(&host, "]");
  if (absl::AsciiStrToLower(host) == "localhost") return true;
  const std::string text(host);
  std::array<unsigned char, 16> address{};
  if (inet_pton(AF_INET, text.c_str(), address.data()) == 1) {
    return address[0] == 127;
  }
  if (inet_pton(AF_INET6, text.c_str(), address.data()) == 1) {
    std::array<unsigned char, 16> loopback{};
    loopback[15] = 1;
    return address == loopback;
  }
  return false;
}

// The message civetweb last logged on this thread: why mg_start failed.
thread_local std::string last_civetweb_message;

int LogCivetwebMessage(const mg_connection* /*connection*/,
                       const char* message) {
  last_civetweb_message = message == nullptr ? "" : message;
  spdlog::warn("http: {}", last_civetweb_message);
  return 1;  // civetweb writes nothing itself
}

// Decrements a counter when it goes.
class InFlight {
 public:
  explicit InFlight(std::atomic<int64_t>& count) : count_(count) {
    count_.fetch_add(1, std::memory_order_acq_rel);
  }
  ~InFlight() { count_.fetch_sub(1, std::memory_order_acq_rel); }
  InFlight(const InFlight&) = delete;
  InFlight& operator=(const InFlight&) = delete;

 private:
  std::atomic<int64_t>& count_;
};

}  // namespace

// One request on its way through the gateway: checks, body, call, answer.
class HttpGateway::Call {
 public:
  Call(HttpGateway& gateway, HttpExchange& http)
      : gateway_(gateway), http_(http) {}

  void Serve() {
    if (http_.method() == "OPTIONS") return http_.AnswerPreflight();
    if (http_.method() == "GET" || http_.method() == "HEAD") {
      if (const StaticFile* file = FindStaticFile(http_.path())) {
        return ServeFile(*file);
      }
    }
    absl::StatusOr<GatewayMethod> method = ResolveMethod(http_.path());
    if (!method.ok()) {
      // Connect clients read 404 as unimplemented, as gRPC names a method
      // it does not have.
      constexpr int kNotFound = 404;
      return Refuse(http_.path(),
                    grpc::Status(grpc::StatusCode::UNIMPLEMENTED,
                                 std::string(method.status().message())),
                    kNotFound);
    }
    method_ = *std::move(method);
    if (http_.method() != "POST") {
      constexpr int kMethodNotAllowed = 405;
      return Refuse(method_.name,
                    grpc::Status(grpc::StatusCode::UNIMPLEMENTED,
                                 absl::StrCat("freeform.v1 methods take POST, "
                                              "not ",
                                              http_.method())),
                    kMethodNotAllowed);
    }
    const std::optional<Codec> codec =
        CodecOf(http_.header("Content-Type"), method_);
    if (!codec.has_value()) {
      constexpr int kUnsupportedMediaType = 415;
      return Refuse(
          method_.name,
          grpc::Status(
              grpc::StatusCode::UNIMPLEMENTED,
              absl::StrCat(method_.name, " takes Content-Type ",
                           method_.server_streaming
                               ? "application/connect+json or "
                                 "application/connect+proto (a "
                                 "server-streaming method)"
                               : "application/json or application/proto",
                           ", not \"", http_.header("Content-Type"), "\"")),
          kUnsupportedMediaType);
    }
    codec_ = *codec;
    if (grpc::Status status = CheckHeaders(); !status.ok()) {
      return Refuse(method_.name, status);
    }
    absl::StatusOr<std::string> request = ReadRequest();
    if (!request.ok()) {
      // A body left unread ends the connection with the answer.
      return Refuse(method_.name, ToGrpc(request.status()), 0,
                    /*close=*/!body_read_);
    }
    if (method_.server_streaming) return CallStream(*request);
    CallUnary(*request);
  }

 private:
  // Refuse answers `status` without a call, with `http_status` when set
  // (else the code's), and logs it; a stream's error goes in its
  // EndStreamResponse once the request was understood as one.
  void Refuse(absl::string_view method, const grpc::Status& status,
              int http_status = 0, bool close = false) {
    LogRefusal(method, http_, status);
    if (http_status == 0 && method_.server_streaming && !close) {
      return EndStream(status);
    }
    http_.AnswerError(status, close, http_status);
  }

  // ServeFile answers a GET or HEAD of an embedded file (the playground).
  // A request that carries a body (which a GET has no use for) gets its
  // answer and the connection ends, unread.
  void ServeFile(const StaticFile& file) {
    const bool carries_body = http_.declared_body_bytes().value_or(0) > 0 ||
                              !http_.header("Transfer-Encoding").empty();
    http_.AnswerFile(file.content_type, file.body,
                     /*with_body=*/http_.method() == "GET", carries_body);
  }

  grpc::Status CheckHeaders() {
    const absl::string_view version = http_.header("Connect-Protocol-Version");
    if (!version.empty() && version != "1") {
      return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT,
                          absl::StrCat("Connect-Protocol-Version \"", version,
                                       "\": this server speaks version 1"));
    }
    for (const char* encoding_header :
         {"Content-Encoding", "Connect-Content-Encoding"}) {
      const absl::string_view encoding = http_.header(encoding_header);
      if (!encoding.empty() && !absl::EqualsIgnoreCase(encoding, "identity")) {
        return grpc::Status(
            grpc::StatusCode::UNIMPLEMENTED,
            absl::StrCat(encoding_header, " \"", encoding,
                         "\" is not supported; the supported encoding is "
                         "identity"));
      }
    }
    if (const absl::string_view timeout = http_.header("Connect-Timeout-Ms");
        !timeout.empty()) {
      absl::StatusOr<absl::Duration> parsed = connect::ParseTimeout(timeout);
      if (!parsed.ok()) return ToGrpc(parsed.status());
      settings_.timeout = *parsed;
    }
    settings_.client = http_.client();
    return grpc::Status::OK;
  }

  // ReadRequest reads the body within its bound and reserves its memory,
  // and returns the serialized request message.
  absl::StatusOr<std::string> ReadRequest() {
    const uint64_t max_bytes = gateway_.options_.max_request_bytes;
    if (const std::optional<uint64_t> declared = http_.declared_body_bytes();
        declared.has_value() && *declared <= max_bytes) {
      if (absl::Status status = Reserve(*declared * kRequestMemoryPerByte);
          !status.ok()) {
        return status;
      }
    }
    absl::StatusOr<std::string> body = http_.ReadBody(max_bytes);
    if (!body.ok()) return body.status();
    body_read_ = true;
    if (!http_.declared_body_bytes().has_value()) {
      if (absl::Status status = Reserve(body->size() * kRequestMemoryPerByte);
          !status.ok()) {
        return status;
      }
    }
    absl::string_view message = *body;
    if (codec_.enveloped) {
      absl::StatusOr<absl::string_view> unwrapped =
          connect::SingleEnvelopedMessage(*body);
      if (!unwrapped.ok()) return unwrapped.status();
      message = *unwrapped;
    }
    if (!codec_.json) {
      // The server parses the bytes itself, and answers INVALID_ARGUMENT
      // naming the message when they do not parse.
      if (!codec_.enveloped) return body;
      return std::string(message);
    }
    std::unique_ptr<google::protobuf::Message> request(
        method_.request_prototype->New());
    if (const auto status = google::protobuf::util::JsonStringToMessage(
            google::protobuf::StringPiece(message.data(), message.size()),
            request.get());
        !status.ok()) {
      return absl::InvalidArgumentError(absl::StrCat(
          "request is not a valid ", request->GetDescriptor()->full_name(),
          " in proto3 JSON: ", std::string(status.message())));
    }
    return request->SerializeAsString();
  }

  absl::Status Reserve(uint64_t bytes) {
    absl::StatusOr<MemoryBudget::Reservation> reservation =
        gateway_.budget_->Reserve(bytes, method_.name);
    if (!reservation.ok()) return reservation.status();
    reservations_.push_back(*std::move(reservation));
    return absl::OkStatus();
  }

  // ToJson converts a serialized answer message to JSON.
  absl::StatusOr<std::string> ToJson(const std::string& answer) {
    std::unique_ptr<google::protobuf::Message> message(
        method_.response_prototype->New());
    if (!message->ParseFromString(answer)) {
      return absl::InternalError("the gateway could not read the answer");
    }
    return MessageJson(*message);
  }

  void CallUnary(const std::string& request) {
    std::string answer;
    grpc::Status status =
        gateway_.caller_.Unary(method_, settings_, request, answer);
    if (!status.ok()) return http_.AnswerError(status);
    if (!codec_.json) {
      return http_.Answer(200, ContentTypeOf(codec_), answer);
    }
    if (absl::Status reserved =
            Reserve(answer.size() * kJsonAnswerMemoryPerByte);
        !reserved.ok()) {
      return Refuse(method_.name, ToGrpc(reserved));
    }
    absl::StatusOr<std::string> json = ToJson(answer);
    if (!json.ok()) return Refuse(method_.name, ToGrpc(json.status()));
    http_.Answer(200, ContentTypeOf(codec_), *json);
  }

  void CallStream(const std::string& request) {
    http_.StartStream(ContentTypeOf(codec_));
    std::string envelope;
    grpc::Status converted = grpc::Status::OK;
    const grpc::Status status = gateway_.caller_.Stream(
        method_, settings_, request, [&](std::string message) {
          envelope.clear();
          if (codec_.json) {
            absl::StatusOr<std::string> json = ToJson(message);
            if (!json.ok()) {
              converted = ToGrpc(json.status());
              return false;
            }
            message = *std::move(json);
          }
          connect::AppendEnvelope(0, message, envelope);
          return http_.WriteChunk(envelope);
        });
    EndStream(converted.ok() ? status : converted);
  }

  // EndStream sends the EndStreamResponse of `status` and the last chunk,
  // after the answer's headers if none went yet.
  void EndStream(const grpc::Status& status) {
    if (!http_.answered()) http_.StartStream(ContentTypeOf(codec_));
    std::string envelope;
    connect::AppendEnvelope(connect::kEndStreamFlag,
                            connect::EndStreamJson(status), envelope);
    http_.WriteChunk(envelope);
    http_.EndStream();
  }

  HttpGateway& gateway_;
  HttpExchange& http_;
  GatewayMethod method_;
  Codec codec_;
  CallSettings settings_;
  bool body_read_ = false;
  std::vector<MemoryBudget::Reservation> reservations_;
};

absl::Status CheckHttpListener(const HttpGatewayOptions& options,
                               const TlsOptions& tls) {
  if (options.listen_address.empty()) return absl::OkStatus();
  if (absl::StatusOr<CorsPolicy> cors = CorsPolicy::Make(options.cors_origins);
      !cors.ok()) {
    return cors.status();
  }
  if (!tls.client_ca_file.empty()) {
    return absl::InvalidArgumentError(
        "--http_listen serves plaintext HTTP, where clients present no "
        "certificate: it cannot be combined with mutual TLS "
        "(--tls_client_ca), whose client identities it would bypass");
  }
  const std::string& address = options.listen_address;
  const size_t colon = address.rfind(':');
  if (colon == std::string::npos) {
    return absl::InvalidArgumentError(
        absl::StrCat("--http_listen=", address, " is not HOST:PORT"));
  }
  if (!tls.cert_file.empty() && !IsLoopback(address.substr(0, colon))) {
    return absl::InvalidArgumentError(absl::StrCat(
        "--http_listen=", address,
        ": the HTTP listener is plaintext only, so with TLS (--tls_cert) it "
        "may listen on a loopback address only (127.0.0.1, [::1]), behind a "
        "TLS-terminating proxy on the same host"));
  }
  return absl::OkStatus();
}

HttpGateway::HttpGateway(const HttpGatewayOptions& options,
                         std::shared_ptr<grpc::Channel> channel,
                         MemoryBudget* budget, CorsPolicy cors)
    : options_(options),
      cors_(std::move(cors)),
      caller_(std::move(channel)),
      budget_(budget) {}

absl::StatusOr<std::unique_ptr<HttpGateway>> HttpGateway::Start(
    const HttpGatewayOptions& options, std::shared_ptr<grpc::Channel> channel,
    MemoryBudget* budget) {
  absl::StatusOr<CorsPolicy> cors = CorsPolicy::Make(options.cors_origins);
  if (!cors.ok()) return cors.status();
  std::unique_ptr<HttpGateway> gateway(
      new HttpGateway(options, std::move(channel), budget, *std::move(cors)));
  std::vector<const char*> civetweb_options = {
      "listening_ports", gateway->options_.listen_address.c_str()};
  civetweb_options.insert(civetweb_options.end(), kCivetwebOptions.begin(),
                          kCivetwebOptions.end());
  civetweb_options.push_back(nullptr);
  mg_callbacks callbacks{};
  callbacks.begin_request = HandleRequest;
  callbacks.log_message = LogCivetwebMessage;
  last_civetweb_message.clear();
  gateway->context_ =
      mg_start(&callbacks, gateway.get(), civetweb_options.data());
  if (gateway->context_ == nullptr) {
    return absl::UnavailableError(absl::StrCat(
        "cannot serve HTTP on --http_listen=", options.listen_address,
        " (HOST:PORT with a numeric host, port 0 for a free port): ",
        last_civetweb_message));
  }
  std::array<mg_server_port, 4> ports{};
  const int count = mg_get_server_ports(
      gateway->context_, static_cast<int>(ports.size()), ports.data());
  if (count < 1 || ports[0].port <= 0) {
    return absl::UnavailableError(absl::StrCat(
        "cannot serve HTTP on --http_listen=", options.listen_address,
        ": no port"));
  }
  gateway->port_ = ports[0].port;
  return gateway;
}

HttpGateway::~HttpGateway() { Stop(); }

void HttpGateway::Stop() {
  if (context_ == nullptr || stopped_.exchange(true)) return;
  mg_stop(context_);
}

int HttpGateway::HandleRequest(mg_connection* connection) {
  auto* gateway =
      static_cast<HttpGateway*>(mg_get_user_data(mg_get_context(connection)));
  InFlight in_flight(gateway->requests_in_flight_);
  gateway->requests_started_.fetch_add(1, std::memory_order_acq_rel);
  HttpExchange http(connection, gateway->cors_);
  try {
    Call(*gateway, http).Serve();
  } catch (const std::exception& exception) {
    spdlog::error("http {} {} threw: {} (a server bug)",
                  std::string(http.method()), std::string(http.path()),
                  exception.what());
  } catch (...) {
    spdlog::error(
        "http {} {} threw an exception of unknown type (a server "
        "bug)",
        std::string(http.method()), std::string(http.path()));
  }
  if (!http.answered()) {
    http.AnswerError(
        grpc::Status(grpc::StatusCode::INTERNAL,
                     "the gateway failed on this request (a server bug: "
                     "please report the request)"),
        /*close=*/true);
  }
  return http.status();
}

}  // namespace freeform::server
