// Intersections of two curves and of a curve with a surface, by recursive
// subdivision with hull pruning and Newton refinement.
//
// Both inputs are cut into (rational) Bezier pieces (DecomposeCurve in
// curve.h, DecomposeSurface in surface.h) in homogeneous form, divided by a
// power of two (exact) to coordinates of about 1, and pairs of parts are
// examined from a stack (docs/references.md, 'Intersections by
// subdivision'):
//   - a pair is dropped when the bounding boxes of the parts' control
//     points are more than `tolerance` apart, or when a fat line (slab)
//     separates them: the slab of one part's control points across its
//     chord, in the direction from the chord towards the other part's
//     control points, holds none of the other's (Sederberg and Nishita's
//     fat-line test, in any dimension; for a 3D surface part also the slab
//     across its corner diagonals' normal). Both tests allow 64 rounding
//     errors of the largest coordinate on top of the tolerance. With
//     nonnegative weights a rational part lies in the hull of its projected
//     control points once its weights are positive; until then it is not
//     pruned;
//   - two curve parts whose tangent cones (the cone of a part's control
//     polygon edges holds every tangent, also of a rational part with
//     positive weights) are apart as lines meet at most once: Gauss-Newton
//     on A(s) - B(t), clamped to the pair's parameter box, finds that point
//     or the pair is halved further;
//   - a flat curve part (tangent cone under 0.5 rad) against a flat curve
//     part or a surface part is checked for a stretch (for a 3D surface,
//     only where the curve part's chord lies within 0.5 rad of the plane
//     of the surface part's corners): from end to end (for two curves,
//     between the end points of either that lie on the other part; for a
//     surface, the curve part's ends projected onto the part's whole
//     piece), samples (2 (n + m) + 3 for control nets of n and
//     m points) all within `tolerance` of the other make the pair a stretch
//     of contact, and an overlap when also the tangents agree within
//     kOverlapAngle at every sample (the curve's tangent within that of the
//     surface's tangent plane); where they agree at some samples but not
//     all, the pair is halved instead; a stretch that is not an overlap
//     gives its nearest sample, refined by a few Newton steps, as a point;
//   - parts smaller than the leaf size (max(tolerance, 1e-7 of the
//     control points' extent)) end with Newton from their middle;
//   - otherwise the larger part is halved by de Casteljau.
// The points and stretches found are then merged into runs, in the order of
// the first curve's parameter: one joins the run before it when it starts
// inside a stretch of it (the second's parameters meeting too), when its
// point is within max(separation, tolerance) of the run's end, or when the
// first curve stays within tolerance of the second between them (7 samples,
// on one piece of the first curve or two neighbouring ones). A run holding
// an overlap is an overlap over the whole run; any other run is one point:
// the nearest found in it. So a tangency, or a crossing at a small angle,
// gives one point (also where it falls on a knot): the one of least
// distance, whose parameters are only as accurate as the stretch within
// tolerance is short (about sqrt(tolerance / curvature) for a tangency);
// what holds is that the inputs at the returned parameters are within
// tolerance.
//
// Curves cross at an angle below kOverlapAngle (radians) only where they are
// indistinguishable from an overlap within tolerance; such crossings are
// reported as overlaps along the stretch where the curves are within
// tolerance.
//
// The work is bounded before it starts: every pair, halving and Newton
// evaluation is charged to IntersectionOptions::max_work by the size of the
// control nets it touches, and the search stops once that is spent.
//
// Thread-safe; allocates per call.
#ifndef FREEFORM_CORE_INTERSECTION_H_
#define FREEFORM_CORE_INTERSECTION_H_

#include <cstddef>
#include <cstdint>
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
  // "max_results" beyond, also during the search once its candidates merge
  // into more than max_results + 1024 runs: IntersectionCandidateBytes).
  size_t max_results = 1024;
  // The most work the search does, in units of about one multiply-add on a
  // double (RESOURCE_EXHAUSTED naming "max_work" beyond): each pair
  // examined, halving and evaluation is charged by the size of the control
  // nets it touches.
  uint64_t max_work = uint64_t{1} << 28;
};

// IntersectionCandidateBytes returns an upper bound of the memory of the
// candidates (points and stretches found, merged into runs) that a search
// of inputs of `dimension` with `max_results` keeps.
uint64_t IntersectionCandidateBytes(size_t max_results, int dimension);

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
// "tolerance" or "separation" for bad options ("tolerance" also below what
// double precision resolves on the inputs: kResolution (2^-48) times their
// largest control point coordinate, tessellation_checks.h), "first" or
// "second" for an intersection whose parameters double precision cannot
// resolve (at the nearest doubles, a point or an overlap's end, that input
// moves beyond the tolerance: knot spans a few ulps of their position,
// extreme weights), RESOURCE_EXHAUSTED naming "max_results" or "max_work",
// and with the token's CANCELLED / DEADLINE_EXCEEDED.
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
  // Overlap k: C on [curve_intervals[2k], curve_intervals[2k + 1]] lies
  // within tolerance of the surface, its tangent within kOverlapAngle of
  // the surface's tangent plane along a stretch of it (a curve lying in
  // the surface). Points inside an overlap are not listed.
  std::vector<double> curve_intervals;
};

// IntersectCurveSurface returns the points and overlaps where a valid curve
// meets a valid surface. Fails as IntersectCurves, "surface.dimension"
// naming a surface of another dimension, and "curve" or "surface" (not
// "first" or "second") for parameters double precision cannot resolve.
absl::StatusOr<CurveSurfaceIntersections> IntersectCurveSurface(
    const Curve& curve, const Surface& surface,
    const IntersectionOptions& options = {},
    const CancellationToken* cancel = nullptr);

}  // namespace freeform

#endif  // FREEFORM_CORE_INTERSECTION_H_
