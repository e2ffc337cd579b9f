#include "construct/fitting_checks.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "freeform/core/points.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"

namespace freeform::internal {

absl::Status ValidateTolerance(double tolerance) {
  if (!(tolerance > 0) || !std::isfinite(tolerance)) {
    return InvalidFieldError(
        "tolerance",
        absl::StrCat("must be positive and finite, got ", tolerance));
  }
  return absl::OkStatus();
}

absl::Status ValidateIncreasing(absl::Span<const double> values,
                                absl::string_view field) {
  RETURN_IF_ERROR(ValidateFinite(values, field));
  const auto repeat =
      std::adjacent_find(values.begin(), values.end(),
                         [](double a, double b) { return !(b > a); });
  if (repeat == values.end()) return absl::OkStatus();
  return InvalidFieldError(
      IndexedField(field, static_cast<size_t>(repeat - values.begin()) + 1),
      "must be strictly increasing");
}

absl::Status ValidateDegreeAndCount(int degree, int count,
                                    absl::string_view direction,
                                    absl::string_view count_field,
                                    absl::string_view of) {
  if (degree < 1) {
    return InvalidFieldError(absl::StrCat("degree_", direction),
                             absl::StrCat("must be >= 1, got ", degree));
  }
  if (count <= degree) {
    return InvalidFieldError(
        count_field, absl::StrCat("needs at least degree_", direction,
                                  " + 1 = ", static_cast<long long>(degree) + 1,
                                  " ", of, ", got ", count));
  }
  return absl::OkStatus();
}

}  // namespace freeform::internal
