// Degree elevation and reduction of Bezier curves, B-spline (NURBS) curves,
// tensor-product surfaces and triangular patches.
//
// Degree elevation rewrites a curve or surface in a basis of higher degree
// without changing its shape or parametrization: the result evaluates to the
// same points and derivatives everywhere on the domain. Rational geometry is
// elevated in homogeneous form (w P, w) and projected back; a point with
// weight 0 is a point at infinity whose coordinates are its direction (see
// rational.h), and a resulting weight of 0 keeps the homogeneous coordinates
// as that direction. Degree reduction is the approximate inverse for
// polynomial Bezier curves and reports a rigorous bound of its error.
//
// Inputs are views that the caller has validated (ValidateBezierCurve,
// ValidateBSplineCurve, ValidateBezierSurface, ValidateBSplineSurface,
// ValidateTriangularPatch); the functions here only check their own
// arguments ("by", "by_u", "by_v"). Those whose work grows with a curve's
// length or a surface's net take a CancellationToken (may be null), poll it
// as they go and return its CANCELLED / DEADLINE_EXCEEDED status once it
// stops.
//
// Example, a quadratic Bezier curve raised to degree 4:
//   absl::StatusOr<BezierCurveData> quartic = ElevateBezierCurve(curve, 2);
//   if (!quartic.ok()) return quartic.status();
//   EvaluateBezierCurve(quartic->view(), parameters, output);
//
// All functions are thread-safe and allocate their results per call.
#ifndef FREEFORM_CORE_ELEVATION_H_
#define FREEFORM_CORE_ELEVATION_H_

#include <vector>

#include "absl/status/statusor.h"
#include "freeform/core/bezier.h"
#include "freeform/core/bspline.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/geometry_data.h"
#include "freeform/core/tensor_surface.h"
#include "freeform/core/triangular.h"

namespace freeform {

// ElevateBezierCurve returns `curve` raised from degree n to n + by in one
// step by the product formula (The NURBS Book, eq. 5.36; docs/references.md,
// 'Degree elevation by the product formula'):
//   Q_i = sum_{j=max(0,i-by)}^{min(n,i)} C(n,j) C(by,i-j) / C(n+by,i) P_j,
// which for by = 1 is Q_i = i/(n+1) P_{i-1} + (1 - i/(n+1)) P_i. The result is
// rational (weights not empty) exactly when `curve` is. Fails with
// INVALID_ARGUMENT "by" when by < 1.
absl::StatusOr<BezierCurveData> ElevateBezierCurve(const BezierCurveView& curve,
                                                   int by);

// ElevateBSplineCurve returns `curve` raised from degree p to p + by with
// its continuity kept: every distinct knot value inside the domain keeps its
// value and gains `by` in multiplicity, and the result is clamped at the
// domain ends (multiplicity p + by + 1), so a clamped curve with n + 1
// control points and S non-empty spans gets n + 1 + by * S. The result is
// the one of The NURBS Book's A5.9 (Bezier segments elevated by eq. 5.36 and
// joined by knot removal), computed instead by blossoming: each new control
// point is the elevated blossom, the average of the original piece's
// blossom over the p-subsets of its p + by new knots (Ramshaw 1989), built
// with de Boor steps only. A5.9's knot removal extrapolates and lost up to
// 6e-8 of the curve's scale at degree 11 in our tests; this stays at
// rounding level. Cost O(n (p + by) p^2) per coordinate.
// An unclamped knot vector is first clamped at the ends of its domain
// [u_p, u_{n+1}] by knot insertion (The NURBS Book A5.1): knots outside the
// domain are dropped, so the result's knot vector then differs from the
// input's there, while the curve on the domain is unchanged. Fails with
// INVALID_ARGUMENT "by" when by < 1.
absl::StatusOr<BSplineCurveData> ElevateBSplineCurve(
    const BSplineCurveView& curve, int by,
    const CancellationToken* cancel = nullptr);

// The result of ReduceBezierCurve: the curve of lower degree and an upper
// bound of max_{t in [0,1]} |C(t) - R(t)| between the original C and it.
struct ReducedBezierCurve {
  BezierCurveData curve;
  double error_bound = 0;
};

// ReduceBezierCurve returns a polynomial Bezier curve of degree n - by that
// approximates `curve` (degree n). Method: constrained least squares on the
// control points (the discrete l2 version of Eck's reduction, "Degree
// reduction of Bezier curves", CAGD 10 (1993)): the end points are kept
// (for n - by >= 1; degree 0 becomes the centroid), and the inner points R
// minimize sum_i |P_i - (E R)_i|^2, where E is the elevation by `by`
// (eq. 5.36), solved by Householder QR. A curve that is an elevation of a
// degree n - by curve is recovered exactly (to rounding) with error_bound
// ~0. The error bound is max_i |P_i - (E R)_i|: C - R is the Bezier curve of
// the differences P_i - (E R)_i, so by the convex hull property its norm
// never exceeds their largest norm. For random cubics reduced to quadratics
// it is 2 sqrt(3) ~ 3.5 times the true distance.
// Fails with INVALID_ARGUMENT "by" unless 1 <= by <= n, and "weights" for a
// rational curve (reduction of rational curves is not supported).
absl::StatusOr<ReducedBezierCurve> ReduceBezierCurve(
    const BezierCurveView& curve, int by);

// ElevateBezierSurface returns `surface` raised by `by_u` in u and `by_v` in
// v (either may be 0, not both) by applying the curve formula to every row
// and column of the (homogeneous) net. The result has empty knot vectors,
// degree_u = count_u - 1 and degree_v = count_v - 1. Fails with
// INVALID_ARGUMENT "by_u" / "by_v" for a negative value and "by_u" when both
// are 0.
absl::StatusOr<SurfaceData> ElevateBezierSurface(
    const BezierSurfaceView& surface, int by_u, int by_v,
    const CancellationToken* cancel = nullptr);

// ElevateBSplineSurface is ElevateBezierSurface for a B-spline (NURBS)
// surface, with ElevateBSplineCurve's algorithm and knot rules applied in
// each direction (every column of the net is a curve in u, every row a
// curve in v, and all share their knot vector).
absl::StatusOr<SurfaceData> ElevateBSplineSurface(
    const BSplineSurfaceView& surface, int by_u, int by_v,
    const CancellationToken* cancel = nullptr);

// A triangular Bezier patch that owns its data (see triangular.h for the
// storage order); view() hands out the matching TriangularPatchView.
struct TriangularPatchData {
  int degree = 0;
  int dimension = 0;
  std::vector<double> coordinates;
  std::vector<double> weights;
  std::vector<double> domain_triangle;

  TriangularPatchView view() const {
    return {
        .degree = degree,
        .control_points = {.dimension = dimension, .coordinates = coordinates},
        .weights = weights,
        .domain_triangle = domain_triangle};
  }
};

// ElevateTriangularPatch returns `patch` raised from degree n to n + by by
// repeating Farin's elevation step (Farin, CAGD 3 (1986);
// docs/references.md, 'Degree elevation by the product formula'), for
// i + j + k = n + 1:
//   Q_ijk = (i P_{i-1,j,k} + j P_{i,j-1,k} + k P_{i,j,k-1}) / (n + 1),
// in homogeneous form when rational. The domain triangle is kept. Fails with
// INVALID_ARGUMENT "by" when by < 1.
absl::StatusOr<TriangularPatchData> ElevateTriangularPatch(
    const TriangularPatchView& patch, int by);

}  // namespace freeform

#endif  // FREEFORM_CORE_ELEVATION_H_
