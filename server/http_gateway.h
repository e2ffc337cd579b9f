// HttpGateway: freeformd's HTTP/JSON door (--http_listen), the Connect
// protocol's unary and server-streaming forms over HTTP/1.1 on civetweb.
//
//   POST /freeform.v1.CurveService/Evaluate
//   Content-Type: application/json       (or application/proto)
//   Connect-Timeout-Ms: 5000              (optional: the call's deadline)
//   {"curve": {...}, "parameters": {...}}
//
// answers 200 with the response's canonical proto3 JSON (proto_json.h), or
// an error status with a Connect Error object (connect_protocol.h).
// Server-streaming methods take application/connect+json (or +proto): the
// request and each answer message in a 5-byte envelope, the last envelope
// the EndStreamResponse (flag 0x02) with the error, if any.
//
// Every call runs through the server's own services in-process
// (gateway_call.h): the same admission, limits, deadline, metrics and
// access log as gRPC, labelled transport=http. What the gateway decides by
// itself, before a call: the path (404 unimplemented for anything but a
// freeform.v1 method), the method (POST; OPTIONS for CORS preflights), the
// content type (415), the Connect headers (400), the body's size (a
// Content-Length above max_request_bytes is refused at once with
// resource_exhausted, before the body is read; a chunked body is cut off at
// the bound) and its memory, reserved from the server's MemoryBudget with
// the answer's before they are converted. A GET or HEAD of one of the
// playground page's files (static_files.h: "/", "/playground.js", ...) is
// answered from the binary, without a call. docs/http.md describes it all.
// Thread-safe.
#ifndef FREEFORM_SERVER_HTTP_GATEWAY_H_
#define FREEFORM_SERVER_HTTP_GATEWAY_H_

#include <grpcpp/channel.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "admission.h"
#include "cors_policy.h"
#include "gateway_call.h"
#include "tls.h"

struct mg_connection;
struct mg_context;

namespace freeform::server {

struct HttpGatewayOptions {
  // HOST:PORT (numeric host; port 0 picks a free port); empty serves none.
  std::string listen_address;
  // Origins whose browser pages may call (CORS), "https://app.example:8443"
  // each, or "*" for any; empty sends no CORS headers at all.
  std::vector<std::string> cors_origins;
  // Largest request body, in bytes.
  uint64_t max_request_bytes = 64 << 20;
};

// CheckHttpListener refuses, with INVALID_ARGUMENT naming the flags, an
// HTTP listener that would open what gRPC's TLS closes: the gateway speaks
// plaintext only, so with --tls_cert it may listen on a loopback address
// only (behind a TLS proxy on the same host), and with --tls_client_ca
// (mutual TLS: client identities) not at all. Also checks the CORS origins.
absl::Status CheckHttpListener(const HttpGatewayOptions& options,
                               const TlsOptions& tls);

class HttpGateway {
 public:
  // Start serves on `options.listen_address` until Stop, calling the
  // server through `channel` (its InProcessChannel) and reserving memory
  // from `budget`, which must outlive the gateway. UNAVAILABLE naming
  // --http_listen when the address cannot be bound.
  static absl::StatusOr<std::unique_ptr<HttpGateway>> Start(
      const HttpGatewayOptions& options, std::shared_ptr<grpc::Channel> channel,
      MemoryBudget* budget);
  ~HttpGateway();
  HttpGateway(const HttpGateway&) = delete;
  HttpGateway& operator=(const HttpGateway&) = delete;

  int port() const { return port_; }
  // requests_in_flight counts the HTTP requests being served (their answers
  // may still be on their way after the call is done); requests_started
  // every request ever started.
  int64_t requests_in_flight() const {
    return requests_in_flight_.load(std::memory_order_acquire);
  }
  int64_t requests_started() const {
    return requests_started_.load(std::memory_order_acquire);
  }
  // Stop closes the listener and returns once every request being served
  // has been answered (idempotent).
  void Stop();

 private:
  // One request on its way: checks, body, call, answer (http_gateway.cc).
  class Call;

  HttpGateway(const HttpGatewayOptions& options,
              std::shared_ptr<grpc::Channel> channel, MemoryBudget* budget,
              CorsPolicy cors);

  // civetweb's begin_request callback: answers every request (any
  // exception becomes a 500 internal error and a log line) and returns
  // its HTTP status.
  static int HandleRequest(mg_connection* connection);

  const HttpGatewayOptions options_;
  const CorsPolicy cors_;
  InProcessCaller caller_;
  MemoryBudget* const budget_;
  mg_context* context_ = nullptr;
  int port_ = 0;
  std::atomic<int64_t> requests_in_flight_{0};
  std::atomic<int64_t> requests_started_{0};
  std::atomic<bool> stopped_{false};
};

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_HTTP_GATEWAY_H_
