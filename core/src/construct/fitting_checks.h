// Argument checks that the fitting functions (fitting.h) share, each
// naming the offending field with its path (status.h). Internal to the
// core.
#ifndef FREEFORM_CORE_SRC_CONSTRUCT_FITTING_CHECKS_H_
#define FREEFORM_CORE_SRC_CONSTRUCT_FITTING_CHECKS_H_

#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"

namespace freeform::internal {

// ValidateTolerance checks that "tolerance" is positive and finite.
absl::Status ValidateTolerance(double tolerance);

// ValidateIncreasing checks that `values` are finite and strictly
// increasing; the error names "field[i]".
absl::Status ValidateIncreasing(absl::Span<const double> values,
                                absl::string_view field);

// ValidateDegreeAndCount checks "degree_<direction>" >= 1 and `count` >=
// degree + 1, the error on `count_field` saying what the count is `of`
// ("points", "control points").
absl::Status ValidateDegreeAndCount(int degree, int count,
                                    absl::string_view direction,
                                    absl::string_view count_field,
                                    absl::string_view of);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_CONSTRUCT_FITTING_CHECKS_H_
