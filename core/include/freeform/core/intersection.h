// Intersections of two curves and of a curve with a surface, by recursive
// subdivision with hull pruning and Newton refinement.
//
// Both inputs are cut into (rational) Bezier pieces (DecomposeCurve in
// curve.h, DecomposeSurface in surface.h) in homogeneous form, and pairs
// of parts are examined from a stack (docs/references.md, 'Intersections by
// subdivision'):
//   - a pair is dropped when the bounding boxes of the parts' control
//     points are more than `tolerance` apart, or when a fat line (slab)
//     separates them: the slab of one part's control points across its
//     chord, in the direction from the chord towards the other part's
//     control points, holds none of the other's (Sederberg and Nishita's
//     fat-line test, in any dimension; for a 3D surface part also the slab
//     across its corner diagonals' normal). With nonnegative weights a
//     rational part lies in the hull of its projected control points once
//     its weights are positive; until then it is not pruned;
//   - two curve parts whose tangent cones (the cone of a part's control
//     polygon edges holds every tangent, also of a rational part with
//     positive weights) are apart as lines meet at most once: Gauss-Newton
//     on A(s) - B(t), clamped to the pair's parameter box, finds that point
//     or the pair is halved further;
//   - two nearly parallel curve parts (cones under 0.5 rad) whose end points
//     lie on each other are checked for an overlap: the stretch between the
//     end points is sampled, and when every sample lies within `tolerance`
//     of the other curve with tangents within kOverlapAngle of each other,
//     the stretch is an overlap, returned as a pair of parameter intervals
//     (merged with the neighbouring stretches);
//   - parts smaller than the leaf size (max(tolerance, 1e-7 of the
//     control points' extent)) end with Newton from their middle;
//   - otherwise the larger part is halved by de Casteljau.
// Points found twice (from neighbouring pairs, or closer than `separation`)
// are reported once; points inside an overlap are not reported.
//
// Curves cross at an angle below kOverlapAngle (radians) only where they are
// indistinguishable from an overlap within `tolerance`; such crossings are
// reported as overlaps along the stretch where the curves are within
// tolerance.
//
// Thread-safe; allocates per call.
#ifndef FREEFORM_CORE_INTERSECTION_H_
#define FREEFORM_CORE_INTERSECTION_H_

#include <cstddef>
#include <vector>

#include "absl/status/statusor.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/curve.h"
#include "freeform/core/surface.h"

namespace freeform {

// Tangents closer than this angle (radians) along a stretch where two curves
// are within tolerance make it an overlap.
inline constexpr double kOverlapAngle = 1e-8;

struct IntersectionOptions {
  // Points of the two inputs closer than this intersect. Positive, finite.
  double tolerance = 1e-9;
  // Intersection points closer than this are one. >= 0, finite.
  double separation = 1e-7;
  // The most points plus overlaps returned (RESOURCE_EXHAUSTED naming
  // "max_results" beyond).
  size_t max_results = 1024;
  // The most pairs of parts examined (RESOURCE_EXHAUSTED naming "max_pairs"
  // beyond): bounds the work.
  size_t max_pairs = size_t{1} << 20;
};

// The intersections of two curves A (first) and B (second).
struct CurveIntersections {
  int dimension = 0;
  // Point k: A(first_parameters[k]) is within tolerance of
  // B(second_parameters[k]); points[k * dimension ...] is A's point.
  // Sorted by the first parameter.
  std::vector<double> first_parameters;
  std::vector<double> second_parameters;
  std::vector<double> points;
  // Overlap k: A on [first_intervals[2k], first_intervals[2k + 1]]
  // (increasing) runs along B from second_intervals[2k] to
  // second_intervals[2k + 1] (decreasing when B runs the other way).
  std::vector<double> first_intervals;
  std::vector<double> second_intervals;
};

// IntersectCurves returns the intersections of two valid curves. Fails with
// INVALID_ARGUMENT naming "second.dimension" when the dimensions differ,
// "tolerance" or "separation" for bad options, RESOURCE_EXHAUSTED naming
// "max_results" or "max_pairs", and with the token's CANCELLED /
// DEADLINE_EXCEEDED.
absl::StatusOr<CurveIntersections> IntersectCurves(
    const Curve& first, const Curve& second,
    const IntersectionOptions& options = {},
    const CancellationToken* cancel = nullptr);

// The intersections of a curve C and a surface S.
struct CurveSurfaceIntersections {
  int dimension = 0;
  // Point k: C(curve_parameters[k]) is within tolerance of
  // S(surface_parameters[2k], surface_parameters[2k + 1]) (parameters as
  // EvaluateSurface takes them); points[k * dimension ...] is C's point.
  std::vector<double> curve_parameters;
  std::vector<double> surface_parameters;
  std::vector<double> points;
};

// IntersectCurveSurface returns the points where a valid curve meets a
// valid surface (a curve lying in the surface ends in RESOURCE_EXHAUSTED
// naming "max_pairs"). Fails as IntersectCurves, "surface.dimension" naming
// a surface of another dimension.
absl::StatusOr<CurveSurfaceIntersections> IntersectCurveSurface(
    const Curve& curve, const Surface& surface,
    const IntersectionOptions& options = {},
    const CancellationToken* cancel = nullptr);

}  // namespace freeform

#endif  // FREEFORM_CORE_INTERSECTION_H_
