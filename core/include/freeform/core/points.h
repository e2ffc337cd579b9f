// Read-only views of point sets in caller memory, and their validation.
//
// A point set is a dimension plus a flat array of count * dimension doubles,
// point after point. Views never own memory: the caller keeps the array alive
// while the view is used. Views are cheap to copy and safe to share between
// threads for reading.
#ifndef FREEFORM_CORE_POINTS_H_
#define FREEFORM_CORE_POINTS_H_

#include <cmath>
#include <cstddef>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"

namespace freeform {

// The largest point dimension the core accepts. Servers may set a lower
// limit; the product promises at least 16.
inline constexpr int kMaxDimension = 64;

// PointsView is `dimension` coordinates per point over a flat array.
struct PointsView {
  int dimension = 0;
  absl::Span<const double> coordinates;

  // size returns the number of whole points.
  size_t size() const {
    return dimension > 0 ? coordinates.size() / static_cast<size_t>(dimension)
                         : 0;
  }
  // point returns a pointer to the first coordinate of point `index`.
  const double* point(size_t index) const {
    return coordinates.data() + index * static_cast<size_t>(dimension);
  }
};

// PointDistance returns |a - b| for two points of `dimension` coordinates.
inline double PointDistance(const double* a, const double* b,
                            size_t dimension) {
  double sum = 0.0;
  for (size_t c = 0; c < dimension; ++c) sum += (a[c] - b[c]) * (a[c] - b[c]);
  return std::sqrt(sum);
}

// ValidatePoints checks that `points` has a dimension in [1, kMaxDimension],
// a whole number of at least `min_count` points and only finite coordinates.
// Errors name `field` ("field.dimension", "field.coordinates[7]", ...).
absl::Status ValidatePoints(const PointsView& points, absl::string_view field,
                            size_t min_count = 1);

// ValidateFinite checks that every value is finite; the error names
// "field[index]" of the first value that is not.
absl::Status ValidateFinite(absl::Span<const double> values,
                            absl::string_view field);

// ValidateInRange checks that every value lies in [lo, hi]; the error names
// "field[index]" of the first value that is NaN, infinite or outside.
absl::Status ValidateInRange(absl::Span<const double> values, double lo,
                             double hi, absl::string_view field);

}  // namespace freeform

#endif  // FREEFORM_CORE_POINTS_H_
