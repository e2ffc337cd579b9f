// Knot insertion (Boehm, CAD 12 (1980)) for B-splines whose control points
// are blocks of values: Cartesian points, homogeneous points of rational
// geometry (the insertion is linear, so it acts on (w P, w) alike) or whole
// rows of a surface's net. One routine inserts any number of knots at once
// (The NURBS Book A5.4, RefineKnotVectCurve), so many insertions cost
// O(n + r p) rather than O(r n). Subdivision inserts and decomposes with it,
// elevation clamps unclamped knots, and the not-a-knot cubic spline puts
// back its two knots. Internal to the core; thread-safe (pure functions).
#ifndef FREEFORM_CORE_SRC_REFINE_KNOT_INSERTION_H_
#define FREEFORM_CORE_SRC_REFINE_KNOT_INSERTION_H_

#include <vector>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "base/point_array.h"
#include "freeform/core/cancellation.h"

namespace freeform::internal {

// A B-spline of degree `degree`: its knots and its control points (each
// points.dim values).
struct Spline {
  int degree = 0;
  std::vector<double> knots;
  PointArray points;
};

// RefineKnots returns `spline` with the non-decreasing knots `x` inserted:
// the same curve (and, outside its domain, the same piecewise polynomials)
// on the merged knot vector. Every x lies in the domain [u_p, u_{n+1}] and
// no knot may end up with multiplicity above p + 1 (the callers check
// that). Polls `cancel` (may be null) as it inserts and fails only with its
// status.
absl::StatusOr<Spline> RefineKnots(const Spline& spline,
                                   absl::Span<const double> x,
                                   const CancellationToken* cancel);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_REFINE_KNOT_INSERTION_H_
