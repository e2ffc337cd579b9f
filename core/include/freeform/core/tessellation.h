// Tessellation of curves: polylines within a given distance of the exact
// curve.
//
// Curves are refined by recursive subdivision with a flatness test
// ("subdivide until flat, then draw the chord"; docs/references.md,
// 'Flatness test for curve tessellation'):
// a Bezier piece is split at its parameter midpoint by de Casteljau until
// every control point lies within `tolerance` of the chord from the first to
// the last one. By the convex hull property the piece then lies within
// `tolerance` of its chord, and because the piece runs continuously from one
// chord end to the other, every chord point is within `tolerance` of the
// piece too: the polyline and the curve are within Hausdorff distance
// `tolerance` (up to rounding, about 1e-15 of the control points' scale).
// A rational piece is subdivided in homogeneous form and tested on its
// projected control points once all its weights are positive; with
// nonnegative weights and positive end weights one split makes every weight
// of both halves positive, and a rational curve with positive weights lies
// in the convex hull of its projected control points, so the same bound
// holds exactly (no sampling). B-spline spans are converted to Bezier form
// by blossoming (The NURBS Book, section 5.1; de Boor's algorithm with one
// argument per level), so unclamped knot vectors work too. Flatness
// converges quadratically: a polyline needs O(1/sqrt(tolerance)) points.
//
// Surfaces are meshed by mesh.h.
//
// All functions are thread-safe and allocate per call.
#ifndef FREEFORM_CORE_TESSELLATION_H_
#define FREEFORM_CORE_TESSELLATION_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/bezier.h"
#include "freeform/core/bspline.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/curve.h"

namespace freeform {

// A polyline: points on a curve, in parameter order, with their parameters.
struct Polyline {
  int dimension = 0;
  // point r, coordinate j at points[r * dimension + j].
  std::vector<double> points;
  std::vector<double> parameters;
};

// TessellateBezierCurve returns a polyline within Hausdorff distance
// `tolerance` of `curve` (see the file comment), with points evaluated on
// the curve at dyadic parameters, starting at 0 and ending at 1. Fails with
// INVALID_ARGUMENT for an invalid curve (ValidateBezierCurve) or a tolerance
// that is not positive and finite ("tolerance"), RESOURCE_EXHAUSTED naming
// "tolerance" when more than `max_points` points would be needed, and with
// the token's
// CANCELLED / DEADLINE_EXCEEDED (checked every few hundred pieces).
// A tolerance below 2^-48 (3.6e-15) of the largest control-point
// coordinate cannot be met in double precision: for curves of degree 2 or
// more it is refused at once (INVALID_ARGUMENT naming "tolerance").
absl::StatusOr<Polyline> TessellateBezierCurve(
    const BezierCurveView& curve, double tolerance, size_t max_points,
    const CancellationToken* cancel = nullptr);

// TessellateBSplineCurve is TessellateBezierCurve for a B-spline or NURBS
// curve over its domain [u_p, u_{n+1}]: every non-empty knot span is refined
// separately and the knots are polyline points. Fails as
// TessellateBezierCurve, with ValidateBSplineCurve's errors. (A valid
// curve of degree 0 has a single span: its polyline is the constant point
// at both ends of the domain.)
absl::StatusOr<Polyline> TessellateBSplineCurve(
    const BSplineCurveView& curve, double tolerance, size_t max_points,
    const CancellationToken* cancel = nullptr);

// TessellateCurve tessellates a curve of any kind with the same guarantee:
// Bezier and power-form curves as TessellateBezierCurve (on the curve's
// domain), B-spline and NURBS curves as TessellateBSplineCurve, and
// Lagrange and Hermite curves through their Bezier pieces (DecomposeCurve:
// LagrangeToBezier, the cubic segments of a Hermite curve) refined on their
// breakpoint intervals, with every point evaluated on the curve itself.
// Parameters are the curve's own. Fails as those do.
absl::StatusOr<Polyline> TessellateCurve(
    const Curve& curve, double tolerance, size_t max_points,
    const CancellationToken* cancel = nullptr);

// Bounds on the size of a polyline before it is made, so a server knows
// the size of an answer before the work starts. For a polynomial Bezier
// piece of degree n whose second differences are at most D long, every
// control point of a piece halved d times lies within n^2 D 4^-d / 8 of its
// chord (the control polygon minus the chord's even spacing has second
// differences at most 4^-d D and vanishes at both ends, and a discrete
// Green's function bounds it by i (n - i) / 2 times that). The flatness
// test therefore passes at the first depth where this is at most half the
// tolerance (half, so rounding cannot push one level deeper), and the
// polyline has at most 2^depth segments per piece. A B-spline span of width
// w is bounded through the control points Q of the curve's second
// derivative (The NURBS Book, eq. 3.8): its Bezier form has second
// differences at most w^2 max |Q_i| / (p (p - 1)) over the p - 1 points
// active on the span. A rational piece is subdivided in homogeneous form
// (w P, w) and tested projected. About a centre c, its homogeneous points
// (w_i (P_i - c), w_i) deviate from their evenly spaced chord by e_s in
// the spatial part and e_w in the weight, each bounded as above from the
// spatial and the weight second differences D_s and D_w. The chord
// projects onto the piece's Euclidean chord, so a projected control point
// lies within (e_s + R e_w) / w_min of it, where R bounds |P_i - c| and
// w_min the weights (the hull property: both hold for every subpiece):
// the polynomial bound with D = (D_s + R D_w) / w_min. A B-spline span uses
// its p + 1 active control points for R and w_min. A rational curve with a
// weight of 0 has no bound: these return SIZE_MAX, as they do when the
// bound does not fit a size_t.

// BezierCurvePointBound returns at least the number of points
// TessellateBezierCurve(curve, tolerance, ...) returns. `curve` must be
// valid and `tolerance` positive.
size_t BezierCurvePointBound(const BezierCurveView& curve, double tolerance);

// BSplineCurvePointBound is BezierCurvePointBound for
// TessellateBSplineCurve.
size_t BSplineCurvePointBound(const BSplineCurveView& curve, double tolerance);

// CurvePointBound is BezierCurvePointBound for TessellateCurve: the sum of
// the bounds of a Lagrange or Hermite curve's Bezier pieces (it cuts them,
// at O(degree^2) cost for a Lagrange curve).
size_t CurvePointBound(const Curve& curve, double tolerance);

}  // namespace freeform

#endif  // FREEFORM_CORE_TESSELLATION_H_
