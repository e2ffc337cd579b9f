// Transport: the door a call came in by, gRPC's own listener or the HTTP
// gateway (http_gateway.h), for the metrics' transport label and the
// access log.
//
// The gateway calls the server's services in-process and marks each call
// with two metadata entries: kGatewayMetadataKey, the process's gateway
// token (128 random bits drawn at the first use, never sent off the
// process), and kHttpClientMetadataKey, the HTTP client's address. Only a
// call with the token counts as HTTP, so a remote gRPC client that sends
// the same keys is still "grpc", with its own peer.
#ifndef FREEFORM_SERVER_TRANSPORT_H_
#define FREEFORM_SERVER_TRANSPORT_H_

#include <grpcpp/server_context.h>

#include <array>
#include <string>

#include "absl/strings/string_view.h"

namespace freeform::server {

enum class Transport { kGrpc = 0, kHttp = 1 };

inline constexpr std::array<Transport, 2> kTransports = {Transport::kGrpc,
                                                         Transport::kHttp};

// The metadata entries by which the gateway marks its calls.
inline constexpr char kGatewayMetadataKey[] = "freeform-gateway";
inline constexpr char kHttpClientMetadataKey[] = "freeform-http-client";

// GatewayToken returns the value of kGatewayMetadataKey on the gateway's
// calls: 32 hex digits, the same for the process's lifetime.
const std::string& GatewayToken();

// TransportName returns the label value: "grpc" or "http".
absl::string_view TransportName(Transport transport);

// Where a call came from: its transport and the address the access log
// names (gRPC's peer, or the HTTP client's "ipv4:127.0.0.1:40000").
struct CallOrigin {
  Transport transport = Transport::kGrpc;
  std::string peer;
};

// OriginOf returns the origin of the call of `context`.
CallOrigin OriginOf(const grpc::ServerContextBase& context);

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_TRANSPORT_H_
