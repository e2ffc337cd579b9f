// Points and segments of the (u, v) plane shared by the face's checks and
// classification. Internal to the core; thread-safe.
#ifndef FREEFORM_CORE_SRC_FACES_PLANE_GEOMETRY_H_
#define FREEFORM_CORE_SRC_FACES_PLANE_GEOMETRY_H_

#include <algorithm>
#include <array>
#include <cmath>

#include "absl/types/span.h"

namespace freeform::internal {

using Point2 = std::array<double, 2>;

// DistanceToSegment returns the distance from p to the segment [a, b].
inline double DistanceToSegment(const Point2& p, const Point2& a,
                                const Point2& b) {
  const double ab[2] = {b[0] - a[0], b[1] - a[1]};
  const double ab2 = ab[0] * ab[0] + ab[1] * ab[1];
  const double s =
      ab2 > 0.0
          ? std::clamp(((p[0] - a[0]) * ab[0] + (p[1] - a[1]) * ab[1]) / ab2,
                       0.0, 1.0)
          : 0.0;
  return std::hypot(p[0] - (a[0] + s * ab[0]), p[1] - (a[1] + s * ab[1]));
}

// An axis-aligned box of the plane, empty until something is added.
struct Box2 {
  Point2 lo{INFINITY, INFINITY};
  Point2 hi{-INFINITY, -INFINITY};

  void Add(const Point2& p) {
    for (int j = 0; j < 2; ++j) {
      lo[j] = std::min(lo[j], p[j]);
      hi[j] = std::max(hi[j], p[j]);
    }
  }
  void AddBox(const Box2& other) {
    Add(other.lo);
    Add(other.hi);
  }
  double Diagonal() const { return std::hypot(hi[0] - lo[0], hi[1] - lo[1]); }
};

// ControlBox returns the box of 2D points given as u, v, u, v, ...
inline Box2 ControlBox(absl::Span<const double> coordinates) {
  Box2 box;
  for (size_t i = 0; i + 1 < coordinates.size(); i += 2) {
    box.Add(Point2{coordinates[i], coordinates[i + 1]});
  }
  return box;
}

// HasHull reports whether a (rational) piece with these weights lies in the
// hull of its control points: every weight positive (none: polynomial).
inline bool HasHull(absl::Span<const double> weights) {
  return std::all_of(weights.begin(), weights.end(),
                     [](double w) { return w > 0.0; });
}

// Cross returns (b - a) x (p - a): positive when p lies left of a -> b.
inline double Cross(const Point2& a, const Point2& b, const Point2& p) {
  return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
}

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_FACES_PLANE_GEOMETRY_H_
