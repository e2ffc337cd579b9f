#include "freeform/core/status.h"

#include <cmath>

#include "absl/strings/cord.h"
#include "absl/strings/str_cat.h"

namespace freeform {
namespace {

constexpr absl::string_view kFieldPathPayload = "type.freeform.dev/field_path";

absl::Status FieldError(absl::StatusCode code, absl::string_view field,
                        absl::string_view rule) {
  absl::Status status(code, absl::StrCat(field, ": ", rule));
  status.SetPayload(kFieldPathPayload, absl::Cord(field));
  return status;
}

}  // namespace

absl::Status InvalidFieldError(absl::string_view field,
                               absl::string_view rule) {
  return FieldError(absl::StatusCode::kInvalidArgument, field, rule);
}

absl::Status ExhaustedFieldError(absl::string_view field,
                                 absl::string_view rule) {
  return FieldError(absl::StatusCode::kResourceExhausted, field, rule);
}

absl::Status ValidatePositive(double value, absl::string_view field) {
  if (std::isfinite(value) && value > 0.0) return absl::OkStatus();
  return InvalidFieldError(field, "must be positive and finite");
}

std::optional<std::string> FieldPathOf(const absl::Status& status) {
  auto path = status.GetPayload(kFieldPathPayload);
  if (!path.has_value()) return std::nullopt;
  return std::string(*path);
}

std::string FieldRuleOf(const absl::Status& status) {
  std::optional<std::string> path = FieldPathOf(status);
  absl::string_view message = status.message();
  if (path.has_value() && message.size() >= path->size() + 2 &&
      message.substr(0, path->size()) == *path) {
    message.remove_prefix(path->size() + 2);
  }
  return std::string(message);
}

absl::Status PrefixFieldPath(const absl::Status& status,
                             absl::string_view prefix) {
  std::optional<std::string> path = FieldPathOf(status);
  if (!path.has_value() || prefix.empty()) return status;
  const absl::string_view separator =
      (path->empty() || path->front() == '[') ? "" : ".";
  const std::string joined = absl::StrCat(prefix, separator, *path);
  return FieldError(status.code(), joined, FieldRuleOf(status));
}

std::string IndexedField(absl::string_view name, size_t index) {
  return absl::StrCat(name, "[", index, "]");
}

}  // namespace freeform
