// The checks that curve tessellation, surface meshing and the subdivision
// queries (intersections, sections) share: the tolerance is positive, finite
// and resolvable in double precision on the geometry, and a result over its
// size limit is refused naming the tolerance, which is what makes a
// tessellation large.
#ifndef FREEFORM_CORE_SRC_BASE_TESSELLATION_CHECKS_H_
#define FREEFORM_CORE_SRC_BASE_TESSELLATION_CHECKS_H_

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "freeform/core/status.h"

namespace freeform::internal {

// The smallest tolerance, relative to the control points' largest
// coordinate, that subdivision can meet in double precision.
inline constexpr double kResolution = 0x1p-48;

inline absl::Status ValidateTolerance(double tolerance) {
  return ValidatePositive(tolerance, "tolerance");
}

// Curve subdivision stops after this many halvings (the parameter interval
// is then near the resolution of a double); the size bounds count on it.
inline constexpr int kMaxSubdivisionDepth = 50;

// CheckResolvableAt refuses, naming `field`, a tolerance below
// kResolution times `size`, the largest magnitude of a coordinate of the
// geometry: double precision does not resolve it there, so no subdivision
// could meet it, and trying would only end at a work or size limit.
inline absl::Status CheckResolvableAt(double tolerance, double size,
                                      absl::string_view field = "tolerance") {
  if (tolerance >= kResolution * size) return absl::OkStatus();
  return InvalidFieldError(
      field, absl::StrCat(tolerance,
                          " is below what double precision resolves on "
                          "geometry of size ",
                          size, " (about ", kResolution * size, ")"));
}

// CheckResolvable is CheckResolvableAt for geometry of the size of
// `coordinates`. Lines (degree < 2) are flat at any tolerance.
inline absl::Status CheckResolvable(double tolerance,
                                    absl::Span<const double> coordinates,
                                    int degree) {
  if (degree < 2) return absl::OkStatus();
  double size = 0.0;
  for (const double c : coordinates) size = std::max(size, std::abs(c));
  return CheckResolvableAt(tolerance, size);
}

// TessellationTooLarge is RESOURCE_EXHAUSTED naming `field`, the option
// that made a tessellation need more than `limit` of `what` (points,
// vertices): the tolerance, or a limit such as max_edge_length.
inline absl::Status TessellationTooLarge(absl::string_view field,
                                         absl::string_view what, size_t limit) {
  return ExhaustedFieldError(
      field, absl::StrCat("the tessellation needs more than ", limit, " ", what,
                          " at this ", field));
}

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_BASE_TESSELLATION_CHECKS_H_
