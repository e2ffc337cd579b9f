// Request checks shared by the knot-removal and fitting RPCs of both
// services (curve_approximation.cc, surface_approximation.cc).
// Thread-compatible.
#ifndef FREEFORM_SERVER_APPROXIMATION_H_
#define FREEFORM_SERVER_APPROXIMATION_H_

#include <algorithm>
#include <climits>
#include <cstdint>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "freeform/core/status.h"
#include "plan.h"
#include "service_limits.h"

namespace freeform::server {

// RemovalTimes returns the core's `times` of a knot-removal request: the
// request's count, or with 0 every copy (INT_MAX: the core stops at the
// knot's multiplicity). Without a knot (simplify) `times` must be 0.
// INVALID_ARGUMENT on "times".
inline absl::StatusOr<int> RemovalTimes(bool has_knot, uint32_t times) {
  if (!has_knot) {
    if (times != 0) {
      return InvalidFieldError(
          "times",
          "applies to one knot; set `knot`, or leave times 0 to simplify");
    }
    return 0;
  }
  if (times == 0) return INT_MAX;
  if (times > static_cast<uint32_t>(INT_MAX)) {
    return InvalidFieldError(
        "times", absl::StrCat("must be at most ", INT_MAX, ", got ", times));
  }
  return static_cast<int>(times);
}

// FitControlCap returns the cap on a fit's control points (in one
// direction): `requested`, or the server's point limit for 0, and never
// more than `data` (the points or grid lines: a fit never uses more).
// RESOURCE_EXHAUSTED on `field` when `requested` is over the server's limit.
inline absl::StatusOr<int> FitControlCap(uint32_t requested, uint64_t data,
                                         const ServiceLimits& limits,
                                         absl::string_view field) {
  const uint64_t server =
      std::min<uint64_t>(limits.max_control_points, INT_MAX);
  if (requested > server) {
    return ExhaustedFieldError(
        field,
        absl::StrCat(requested, " control points exceed the server's limit of ",
                     server, " (--max_control_points)"));
  }
  const uint64_t cap = requested == 0 ? server : requested;
  return static_cast<int>(std::min(cap, std::max<uint64_t>(data, 1)));
}

// CheckSimplifyWork returns RESOURCE_EXHAUSTED on `field` when
// simplifying `knots` interior knots of a net of `values` numbers may move
// more than limits.max_simplify_moves values (service_limits.h).
inline absl::Status CheckSimplifyWork(uint64_t knots, uint64_t values,
                                      const ServiceLimits& limits,
                                      absl::string_view field) {
  const uint64_t moves = SaturatingProduct(knots, values);
  if (moves <= limits.max_simplify_moves) return absl::OkStatus();
  return ExhaustedFieldError(
      field,
      absl::StrCat("simplifying ", knots, " interior knots of ", values,
                   " control-point values may move ", moves,
                   " values, over the server's limit of ",
                   limits.max_simplify_moves,
                   "; split the geometry and simplify the pieces, or remove "
                   "chosen knots (knot)"));
}

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_APPROXIMATION_H_
