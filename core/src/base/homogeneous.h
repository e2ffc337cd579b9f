// The lift of Cartesian control points and weights to homogeneous form
// (w P, w), and the two projections back, which differ on purpose (see
// below). Shared by elevation, subdivision, knot removal, tessellation and
// the Bezier nets of the queries. Internal to the core; thread-safe (pure
// functions).
#ifndef FREEFORM_CORE_SRC_BASE_HOMOGENEOUS_H_
#define FREEFORM_CORE_SRC_BASE_HOMOGENEOUS_H_

#include <vector>

#include "absl/types/span.h"
#include "base/point_array.h"
#include "freeform/core/points.h"

namespace freeform::internal {

// LiftedValues returns the points' values: (w_i P_i, w_i), dimension + 1
// values each, when there are weights (HomogeneousPoints: a zero weight
// keeps P_i as a direction), else a copy of the coordinates.
std::vector<double> LiftedValues(const PointsView& points,
                                 absl::Span<const double> weights);

// Lift returns LiftedValues as a PointArray.
PointArray Lift(const PointsView& points, absl::Span<const double> weights);

// The two projections from homogeneous points back to coordinates and
// weights:
//
// ProjectAllowingDirections serves the algorithms that take zero weights
// (points at infinity, rational.h) and build new points as combinations of
// the old ones (elevation, subdivision, knot insertion). A weight 0 keeps
// the homogeneous coordinates as its direction; other points are divided
// by their weight. Convex combinations (Bezier elevation, subdivision, knot
// insertion: nonnegative coefficients) give 0 exactly from zeros and a
// true positive weight otherwise, however small next to the largest
// (ZeroWeights::kExact); an algorithm that subtracts (B-spline elevation
// removes the knots it inserted) leaves rounding on a weight that should
// be 0, so there a weight within 8 epsilon of the largest becomes 0
// (ZeroWeights::kWithinRounding).
//
// ProjectPositive serves the algorithms that need positive weights (the
// convex hull of the projected points bounds the geometry; knot removal
// divides its error bound by the weights): it divides by the weight, and
// reports a weight that is not positive instead of snapping it to 0, since
// a tiny positive weight is a real, if extreme, point there.

// ProjectAllowingDirections writes `points` (homogeneous when `rational`,
// else copied) back as coordinates and weights (cleared when not rational).
enum class ZeroWeights { kExact, kWithinRounding };
void ProjectAllowingDirections(const PointArray& points, bool rational,
                               std::vector<double>& coordinates,
                               std::vector<double>& weights, ZeroWeights zeros);

// ProjectPositive writes the Cartesian point P = h / w of the homogeneous
// point `homogeneous` (dimension + 1 values, weight last) into `point`;
// returns false, writing nothing, when the weight is not positive.
bool ProjectPositive(const double* homogeneous, int dimension, double* point);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_BASE_HOMOGENEOUS_H_
