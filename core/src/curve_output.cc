#include "freeform/core/curve_output.h"

#include "absl/strings/str_cat.h"

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

}  // namespace freeform
