#include "errors.h"

#include <optional>
#include <string>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "freeform/core/status.h"
#include "google/rpc/error_details.pb.h"
#include "google/rpc/status.pb.h"

namespace freeform::server {

grpc::Status ToGrpcStatus(const absl::Status& status,
                          absl::string_view field_prefix) {
  if (status.ok()) return grpc::Status::OK;
  const absl::Status prefixed = PrefixFieldPath(status, field_prefix);
  const auto code = static_cast<grpc::StatusCode>(prefixed.code());
  const std::string message(prefixed.message());
  std::optional<std::string> field = FieldPathOf(prefixed);
  if (!field.has_value()) return grpc::Status(code, message);

  google::rpc::BadRequest bad_request;
  google::rpc::BadRequest::FieldViolation* violation =
      bad_request.add_field_violations();
  violation->set_field(*field);
  violation->set_description(FieldRuleOf(prefixed));
  google::rpc::Status details;
  details.set_code(static_cast<int>(code));
  details.set_message(message);
  details.add_details()->PackFrom(bad_request);
  return grpc::Status(code, message, details.SerializeAsString());
}

absl::Status PrefixFieldPathExcept(
    const absl::Status& status, absl::string_view prefix,
    std::initializer_list<absl::string_view> top_fields) {
  const std::optional<std::string> path = FieldPathOf(status);
  if (!path.has_value()) return status;
  const absl::string_view field = *path;
  for (absl::string_view top : top_fields) {
    if (field == top ||
        (absl::StartsWith(field, top) &&
         (field[top.size()] == '[' || field[top.size()] == '.'))) {
      return status;
    }
  }
  return PrefixFieldPath(status, prefix);
}

}  // namespace freeform::server
