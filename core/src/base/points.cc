#include "freeform/core/points.h"

#include <cmath>
#include <limits>

#include "absl/strings/str_cat.h"
#include "base/simd/range_simd.h"
#include "freeform/core/status.h"

namespace freeform {

absl::Status ValidatePoints(const PointsView& points, absl::string_view field,
                            size_t min_count) {
  if (points.dimension < 1 || points.dimension > kMaxDimension) {
    return InvalidFieldError(
        absl::StrCat(field, ".dimension"),
        absl::StrCat("dimension must be between 1 and ", kMaxDimension,
                     ", got ", points.dimension));
  }
  const std::string coordinates_field = absl::StrCat(field, ".coordinates");
  const size_t dimension = static_cast<size_t>(points.dimension);
  if (points.coordinates.size() % dimension != 0) {
    return InvalidFieldError(
        coordinates_field,
        absl::StrCat("has ", points.coordinates.size(),
                     " values, not a multiple of the dimension ", dimension));
  }
  if (points.size() < min_count) {
    return InvalidFieldError(
        coordinates_field,
        absl::StrCat("needs at least ", min_count, " point",
                     min_count == 1 ? "" : "s", ", got ", points.size()));
  }
  return ValidateFinite(points.coordinates, coordinates_field);
}

absl::Status ValidateFinite(absl::Span<const double> values,
                            absl::string_view field) {
  // The common case at vector speed; the loop below names the offender.
  constexpr double kLargest = std::numeric_limits<double>::max();
  if (simd::AllInRange(values.data(), values.size(), -kLargest, kLargest)) {
    return absl::OkStatus();
  }
  for (size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      return InvalidFieldError(IndexedField(field, i),
                               absl::StrCat("must be finite, got ", values[i]));
    }
  }
  return absl::OkStatus();
}

absl::Status ValidateInRange(absl::Span<const double> values, double lo,
                             double hi, absl::string_view field) {
  // The common case at vector speed; the loop below names the offender.
  if (std::isfinite(lo) && std::isfinite(hi) &&
      simd::AllInRange(values.data(), values.size(), lo, hi)) {
    return absl::OkStatus();
  }
  for (size_t i = 0; i < values.size(); ++i) {
    const double value = values[i];
    if (!std::isfinite(value)) {
      return InvalidFieldError(IndexedField(field, i),
                               absl::StrCat("must be finite, got ", value));
    }
    if (value < lo || value > hi) {
      return InvalidFieldError(
          IndexedField(field, i),
          absl::StrCat(value, " is outside the domain [", lo, ", ", hi, "]"));
    }
  }
  return absl::OkStatus();
}

}  // namespace freeform
