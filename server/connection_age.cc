#include "connection_age.h"

#include <grpc/grpc.h>

#include <cstdint>
#include <limits>

#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"

namespace freeform::server {
namespace {

// The longest duration gRPC's int argument of milliseconds holds (INT_MAX
// itself means "unlimited" to gRPC, so one less).
constexpr int64_t kMaxArgumentMilliseconds =
    std::numeric_limits<int>::max() - int64_t{1};

bool HasAge(const ConnectionAgeOptions& options) {
  return options.max_age > absl::ZeroDuration() &&
         options.max_age != absl::InfiniteDuration();
}

// CheckFinite returns INVALID_ARGUMENT naming --`flag` when `value` is
// negative or finite and over what gRPC's argument holds.
absl::Status CheckFinite(absl::string_view flag, absl::Duration value) {
  if (value < absl::ZeroDuration()) {
    return absl::InvalidArgumentError(absl::StrCat(
        "--", flag, "=", absl::FormatDuration(value), " is negative"));
  }
  if (value != absl::InfiniteDuration() &&
      absl::ToInt64Milliseconds(value) > kMaxArgumentMilliseconds) {
    return absl::InvalidArgumentError(absl::StrCat(
        "--", flag, "=", absl::FormatDuration(value),
        " is over the longest gRPC accepts (",
        absl::FormatDuration(absl::Milliseconds(kMaxArgumentMilliseconds)),
        "); inf means no limit"));
  }
  return absl::OkStatus();
}

}  // namespace

absl::Status CheckConnectionAge(const ConnectionAgeOptions& options) {
  if (absl::Status status = CheckFinite("max_connection_age", options.max_age);
      !status.ok()) {
    return status;
  }
  if (absl::Status status =
          CheckFinite("max_connection_age_grace", options.grace);
      !status.ok()) {
    return status;
  }
  if (HasAge(options) && options.max_age < kMinConnectionAge) {
    return absl::InvalidArgumentError(absl::StrCat(
        "--max_connection_age=", absl::FormatDuration(options.max_age),
        " is under the shortest age, ", absl::FormatDuration(kMinConnectionAge),
        " (every client would reconnect more often than that); 0 keeps "
        "connections open"));
  }
  if (!HasAge(options) && options.grace != absl::InfiniteDuration()) {
    return absl::InvalidArgumentError(absl::StrCat(
        "--max_connection_age_grace=", absl::FormatDuration(options.grace),
        " needs --max_connection_age: without an age no connection is "
        "closed"));
  }
  return absl::OkStatus();
}

std::vector<std::pair<std::string, int>> ConnectionAgeArguments(
    const ConnectionAgeOptions& options) {
  std::vector<std::pair<std::string, int>> arguments;
  if (!HasAge(options)) return arguments;
  arguments.emplace_back(
      GRPC_ARG_MAX_CONNECTION_AGE_MS,
      static_cast<int>(absl::ToInt64Milliseconds(options.max_age)));
  if (options.grace != absl::InfiniteDuration()) {
    arguments.emplace_back(
        GRPC_ARG_MAX_CONNECTION_AGE_GRACE_MS,
        static_cast<int>(absl::ToInt64Milliseconds(options.grace)));
  }
  return arguments;
}

}  // namespace freeform::server
