#include "cors_policy.h"

#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/strip.h"

namespace freeform::server {
namespace {

// IsOrigin is true for "http://host" or "https://host:port": a host of
// letters, digits, '-', '.', or a bracketed IPv6 address, and an optional
// port of 1 to 65535.
bool IsOrigin(absl::string_view origin) {
  if (!absl::ConsumePrefix(&origin, "https://") &&
      !absl::ConsumePrefix(&origin, "http://")) {
    return false;
  }
  absl::string_view host = origin;
  absl::string_view port;
  if (absl::StartsWith(host, "[")) {
    const size_t close = host.find(']');
    if (close == absl::string_view::npos) return false;
    port = host.substr(close + 1);
    host = host.substr(1, close - 1);
    if (!port.empty() && !absl::ConsumePrefix(&port, ":")) return false;
    if (host.empty() || host.find_first_not_of("0123456789abcdefABCDEF:.") !=
                            absl::string_view::npos) {
      return false;
    }
  } else {
    const size_t colon = host.find(':');
    if (colon != absl::string_view::npos) {
      port = host.substr(colon + 1);
      host = host.substr(0, colon);
      if (port.empty()) return false;
    }
    if (host.empty() ||
        host.find_first_not_of("abcdefghijklmnopqrstuvwxyz"
                               "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-.") !=
            absl::string_view::npos) {
      return false;
    }
  }
  if (port.empty()) return true;
  uint32_t number = 0;
  return port.size() <= 5 &&
         port.find_first_not_of("0123456789") == absl::string_view::npos &&
         absl::SimpleAtoi(port, &number) && number >= 1 && number <= 65535;
}

}  // namespace

absl::StatusOr<CorsPolicy> CorsPolicy::Make(
    const std::vector<std::string>& origins) {
  CorsPolicy policy;
  for (const std::string& origin : origins) {
    if (origin == "*") {
      policy.any_ = true;
    } else if (IsOrigin(origin)) {
      policy.origins_.insert(origin);
    } else {
      return absl::InvalidArgumentError(absl::StrCat(
          "--http_cors_origins: \"", origin,
          "\" is not an origin (scheme://host[:port], http or https, no "
          "path) nor *"));
    }
  }
  if (policy.any_ && !policy.origins_.empty()) {
    return absl::InvalidArgumentError(
        "--http_cors_origins: * allows every origin; list no others with it");
  }
  return policy;
}

std::optional<std::string> CorsPolicy::AllowOriginHeader(
    absl::string_view origin) const {
  if (origin.empty()) return std::nullopt;
  if (any_) return std::string("*");
  if (origins_.contains(origin)) return std::string(origin);
  return std::nullopt;
}

}  // namespace freeform::server
