// Errors that name the offending field.
//
// Core functions report a broken input rule as absl::InvalidArgumentError
// whose message reads "<field path>: <rule>" and which carries the field path
// as a payload. Paths are relative to the value the function was given
// (`control_points.coordinates[5]`); callers that know where that value sits
// in a larger request add a prefix with PrefixFieldPath, so the server can
// report `curve.bezier.control_points.coordinates[5]` without parsing text.
// All functions here are thread-safe.
#ifndef FREEFORM_CORE_STATUS_H_
#define FREEFORM_CORE_STATUS_H_

#include <optional>
#include <string>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"

namespace freeform {

// InvalidFieldError returns INVALID_ARGUMENT for `field` breaking `rule`,
// e.g. InvalidFieldError("knots[4]", "knots must be non-decreasing").
absl::Status InvalidFieldError(absl::string_view field, absl::string_view rule);

// ExhaustedFieldError returns RESOURCE_EXHAUSTED for `field` going over a
// limit, with the field path carried the same way.
absl::Status ExhaustedFieldError(absl::string_view field,
                                 absl::string_view rule);

// ValidatePositive returns INVALID_ARGUMENT naming `field` unless `value`
// is positive and finite.
absl::Status ValidatePositive(double value, absl::string_view field);

// FieldPathOf returns the field path carried by `status`, if any.
std::optional<std::string> FieldPathOf(const absl::Status& status);

// FieldRuleOf returns the rule text of a field error (its message without
// the leading "<path>: "), or the whole message for other errors.
std::string FieldRuleOf(const absl::Status& status);

// PrefixFieldPath returns `status` with `prefix` put in front of its field
// path ("curve.bezier" + "weights[2]" -> "curve.bezier.weights[2]"), in
// the payload and the message, keeping the code. Errors without a field path
// and OK are returned unchanged.
absl::Status PrefixFieldPath(const absl::Status& status,
                             absl::string_view prefix);

// IndexedField returns "name[index]".
std::string IndexedField(absl::string_view name, size_t index);

}  // namespace freeform

#endif  // FREEFORM_CORE_STATUS_H_
