// CorsPolicy: which browser origins may call the HTTP gateway
// (--http_cors_origins), and the CORS headers of its answers.
//
// No origins: no CORS header is ever sent, so browsers keep other sites'
// pages from reading the answers. "*": any origin (Access-Control-Allow-
// Origin: *; no credentials are involved). Otherwise exact origins
// ("https://app.example:8443"), echoed back with Vary: Origin. Thread-safe.
#ifndef FREEFORM_SERVER_CORS_POLICY_H_
#define FREEFORM_SERVER_CORS_POLICY_H_

#include <optional>
#include <string>
#include <vector>

#include "absl/container/flat_hash_set.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace freeform::server {

// The request headers a preflight may ask for: Connect's and the content
// type.
inline constexpr char kCorsAllowedHeaders[] =
    "Content-Type, Connect-Protocol-Version, Connect-Timeout-Ms, "
    "Connect-Accept-Encoding, Connect-Content-Encoding, Accept-Encoding, "
    "Content-Encoding, X-User-Agent";
inline constexpr char kCorsAllowedMethods[] = "POST, OPTIONS";
// How long a browser may keep a preflight's answer, in seconds.
inline constexpr char kCorsMaxAgeSeconds[] = "7200";

class CorsPolicy {
 public:
  // Make checks `origins`: "*" alone, or each "scheme://host[:port]" with
  // http or https and nothing after; INVALID_ARGUMENT naming
  // --http_cors_origins otherwise.
  static absl::StatusOr<CorsPolicy> Make(
      const std::vector<std::string>& origins);

  // AllowOriginHeader returns the Access-Control-Allow-Origin value for a
  // request from `origin` (the Origin header; empty when it had none), or
  // nullopt when that origin is not allowed.
  std::optional<std::string> AllowOriginHeader(absl::string_view origin) const;

 private:
  bool any_ = false;
  absl::flat_hash_set<std::string> origins_;
};

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_CORS_POLICY_H_
