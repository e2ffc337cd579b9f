#include "freeform/core/curve_output.h"

#include "absl/strings/str_cat.h"
#include "freeform/core/points.h"
#include "freeform/core/status_macros.h"

namespace freeform {

absl::Status ValidateCurveOutput(CurveOutput output, size_t count,
                                 int dimension) {
  if (output.empty()) {
    return absl::InvalidArgumentError("output needs at least one buffer");
  }
  const size_t expected = count * static_cast<size_t>(dimension);
  for (size_t k = 0; k < output.size(); ++k) {
    if (output[k].size() != expected) {
      return absl::InvalidArgumentError(
          absl::StrCat("output[", k, "] holds ", output[k].size(),
                       " values, expected ", expected));
    }
  }
  return absl::OkStatus();
}

absl::Status ValidateBatch(absl::Span<const double> parameters, double start,
                           double end, CurveOutput output,
                           int values_per_point) {
  RETURN_IF_ERROR(ValidateInRange(parameters, start, end, "parameters"));
  return ValidateCurveOutput(output, parameters.size(), values_per_point);
}

}  // namespace freeform
