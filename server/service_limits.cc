#include "service_limits.h"

#include "absl/strings/str_cat.h"
#include "freeform/core/status.h"

namespace freeform::server {

absl::Status CheckDimensionLimit(uint64_t dimension,
                                 const ServiceLimits& limits,
                                 absl::string_view field) {
  if (dimension < 1 ||
      dimension > static_cast<uint64_t>(limits.max_dimension)) {
    // A dimension of 0 is what an unset Points message reads as: say so,
    // since a client that renames fields (proto-loader without keepCase)
    // drops the whole message without an error of its own.
    const absl::string_view hint =
        dimension == 0 ? " (is the points message missing?)" : "";
    return InvalidFieldError(
        absl::StrCat(field, ".dimension"),
        absl::StrCat("dimension must be between 1 and ", limits.max_dimension,
                     ", got ", dimension, hint));
  }
  return absl::OkStatus();
}

absl::Status CheckDegreeLimit(int64_t degree, const ServiceLimits& limits,
                              absl::string_view field) {
  if (degree > limits.max_degree) {
    return InvalidFieldError(
        field,
        absl::StrCat("degree ", degree, " exceeds the server's limit of ",
                     limits.max_degree, " (--max_degree)"));
  }
  return absl::OkStatus();
}

absl::Status CheckPointLimit(uint64_t count, const ServiceLimits& limits,
                             absl::string_view field) {
  if (count > limits.max_control_points) {
    return ExhaustedFieldError(
        field,
        absl::StrCat(count, " points exceed the server's limit of ",
                     limits.max_control_points, " (--max_control_points)"));
  }
  return absl::OkStatus();
}

absl::Status CheckOutputLimit(uint64_t values, const ServiceLimits& limits,
                              absl::string_view field) {
  if (values > limits.max_output_values) {
    return ExhaustedFieldError(
        field,
        absl::StrCat("the answer would hold ", values,
                     " numbers, over the server's limit of ",
                     limits.max_output_values, " (--max_output_values)"));
  }
  return absl::OkStatus();
}

absl::Status CheckMessageLimit(uint64_t values, const ServiceLimits& limits,
                               absl::string_view hint,
                               absl::string_view field) {
  const uint64_t max_values =
      static_cast<uint64_t>(limits.max_message_bytes) / sizeof(double);
  if (values > max_values) {
    return ExhaustedFieldError(
        field,
        absl::StrCat("the answer would take about ", values, " numbers (",
                     values / 131072, " MiB), over the message limit of ",
                     limits.max_message_bytes, " bytes", hint));
  }
  return absl::OkStatus();
}

}  // namespace freeform::server
