#include "transport.h"

#include <cstdint>

#include "absl/random/random.h"
#include "absl/strings/str_format.h"

namespace freeform::server {
namespace {

// MetadataValue returns the value of `key` in the client's metadata, or ""
// when it has none.
absl::string_view MetadataValue(const grpc::ServerContextBase& context,
                                absl::string_view key) {
  const auto& metadata = context.client_metadata();
  const auto found = metadata.find(grpc::string_ref(key.data(), key.size()));
  if (found == metadata.end()) return "";
  return absl::string_view(found->second.data(), found->second.size());
}

}  // namespace

const std::string& GatewayToken() {
  // absl::BitGen is seeded from the operating system's entropy.
  static const std::string* const token = [] {
    absl::BitGen bits;
    return new std::string(absl::StrFormat("%016x%016x",
                                           absl::Uniform<uint64_t>(bits),
                                           absl::Uniform<uint64_t>(bits)));
  }();
  return *token;
}

absl::string_view TransportName(Transport transport) {
  return transport == Transport::kHttp ? "http" : "grpc";
}

CallOrigin OriginOf(const grpc::ServerContextBase& context) {
  std::string peer = context.peer();
  if (MetadataValue(context, kGatewayMetadataKey) != GatewayToken()) {
    return {.transport = Transport::kGrpc, .peer = std::move(peer)};
  }
  const absl::string_view client =
      MetadataValue(context, kHttpClientMetadataKey);
  return {.transport = Transport::kHttp,
          .peer = client.empty() ? std::move(peer) : std::string(client)};
}

}  // namespace freeform::server
