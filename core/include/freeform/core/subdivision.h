// Subdivision and refinement: splitting Bezier curves and patches, knot
// insertion into B-spline (NURBS) curves and surfaces, Bezier decomposition,
// and corner cutting (Chaikin, uniform B-spline subdivision) of polygons.
//
// Every operation except polygon subdivision is exact: the result describes
// the same geometry as its input (to rounding). Rational geometry is handled
// in homogeneous form (w P, w) and projected back (see rational.h); a
// resulting weight within rounding of 0 becomes exactly 0 and keeps its
// homogeneous coordinates as a direction.
//
// Inputs are views that the caller has validated (ValidateBezierCurve,
// ValidateBSplineCurve, ValidateBezierSurface, ValidateBSplineSurface,
// ValidateTriangularPatch, ValidatePoints); the functions here check only
// their own arguments and report INVALID_ARGUMENT naming them
// ("parameters[2]", "knots[0]", "levels", ...). Those whose work grows with
// their input take a CancellationToken (may be null), poll it as they go and
// return its CANCELLED / DEADLINE_EXCEEDED status once it stops.
//
// Example, the half circle with a knot inserted at 1/2:
//   absl::StatusOr<BSplineCurveData> refined = InsertKnots(curve, {0.5});
//   if (!refined.ok()) return refined.status();
//   EvaluateBSplineCurve(refined->view(), parameters, output);
//
// All functions are thread-safe and allocate their results per call.
#ifndef FREEFORM_CORE_SUBDIVISION_H_
#define FREEFORM_CORE_SUBDIVISION_H_

#include <vector>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/bezier.h"
#include "freeform/core/bspline.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/elevation.h"
#include "freeform/core/geometry_data.h"
#include "freeform/core/hermite.h"
#include "freeform/core/points.h"
#include "freeform/core/tensor_surface.h"
#include "freeform/core/triangular.h"

namespace freeform {

// SplitBezierCurve cuts `curve` at the strictly increasing `parameters`, all
// in (0, 1), into parameters.size() + 1 pieces, each reparameterized to
// [0, 1]: piece k is the original on [t_{k-1}, t_k] (t_{-1} = 0, t_K = 1).
// Each piece comes from two de Casteljau subdivisions of the original
// polygon (at t_k, then at t_{k-1} / t_k of the left part), so errors do
// not accumulate from piece to piece; for one t the left piece is
// P_0^0..P_0^n and the right P_0^n..P_n^0 (docs/references.md,
// 'de Casteljau evaluation and subdivision'). Rational curves are split in
// homogeneous form. Fails with INVALID_ARGUMENT "parameters[i]"
// for a value not finite, not in (0, 1) or not above its predecessor.
absl::StatusOr<std::vector<BezierCurveData>> SplitBezierCurve(
    const BezierCurveView& curve, absl::Span<const double> parameters,
    const CancellationToken* cancel = nullptr);

// InsertKnots returns `curve` with every value of `knots` inserted once (a
// value repeated r times is inserted r times), by Boehm's knot refinement
// (The NURBS Book A5.4; A5.1 for one knot). The curve, its domain and its
// parametrization are unchanged; the result has knots.size() more control
// points. Rational curves are refined in homogeneous form.
// Fails with INVALID_ARGUMENT "knots[i]" when a value is not finite, lies
// outside the domain [u_p, u_{n+1}], is smaller than knots[i-1], or is the
// first copy that raises a value's multiplicity (existing plus inserted)
// above what ValidateBSplineCurve allows: p strictly inside the domain,
// p + 1 at the domain ends (so an unclamped curve may be clamped by
// inserting its domain ends).
absl::StatusOr<BSplineCurveData> InsertKnots(
    const BSplineCurveView& curve, absl::Span<const double> knots,
    const CancellationToken* cancel = nullptr);

// The Bezier pieces of a B-spline curve: segments[k] is the curve on
// [breakpoints[k], breakpoints[k + 1]], reparameterized to [0, 1].
struct BezierDecomposition {
  std::vector<BezierCurveData> segments;
  std::vector<double> breakpoints;
};

// DecomposeBSplineCurve returns one (rational when `curve` is) Bezier
// segment of degree p per non-empty knot span inside the domain, and the
// distinct knot values in the domain as breakpoints. It gives the result of
// The NURBS Book A5.6, computed by refining (A5.4) every distinct knot value
// in the domain to multiplicity p, after which the p + 1 control points of
// each span are its Bezier points. Never fails for a valid curve.
absl::StatusOr<BezierDecomposition> DecomposeBSplineCurve(
    const BSplineCurveView& curve, const CancellationToken* cancel = nullptr);

// The Bezier patches of a B-spline surface: patches[i * (breakpoints_v.size()
// - 1) + j] is the surface on [breakpoints_u[i], breakpoints_u[i + 1]] x
// [breakpoints_v[j], breakpoints_v[j + 1]], reparameterized to [0, 1]^2
// (empty knot vectors, degree_u = count_u - 1, degree_v = count_v - 1).
struct BezierPatchDecomposition {
  std::vector<SurfaceData> patches;
  std::vector<double> breakpoints_u;
  std::vector<double> breakpoints_v;
};

// DecomposeBSplineSurface returns one (rational when `surface` is) Bezier
// patch per non-empty span rectangle of the domain: DecomposeBSplineCurve's
// refinement applied in u and then in v (InsertSurfaceKnots), after which the
// (p + 1) x (q + 1) active control points of every span rectangle are its
// Bezier net. Fails only with the token's CANCELLED / DEADLINE_EXCEEDED for
// a valid surface.
absl::StatusOr<BezierPatchDecomposition> DecomposeBSplineSurface(
    const BSplineSurfaceView& surface,
    const CancellationToken* cancel = nullptr);

// DecomposeHermiteCurve returns the cubic Bezier segment of every piece of
// a valid Hermite curve (HermiteSegmentBezier) with its nodes as
// breakpoints.
BezierDecomposition DecomposeHermiteCurve(const HermiteCurveView& curve);

// Corner-cutting schemes for SubdividePolygon.
enum class SubdivisionScheme {
  // Chaikin (1974): the points at 1/4 and 3/4 of every edge. The same as
  // kUniformBSpline of degree 2.
  kChaikin,
  // Lane-Riesenfeld uniform B-spline subdivision of degree d >= 1 with the
  // mask s_k = binom(d + 1, k) / 2^d, k = 0..d+1, from the refinement
  // equation of the uniform B-spline of degree d (docs/references.md,
  // 'Uniform B-spline subdivision (Chaikin, Lane-Riesenfeld)'):
  // Q_j = sum_i s_{j-2i} P_i.
  // Degree 1 inserts edge midpoints, 2 is Chaikin, 3 uses (1,4,6,4,1)/8.
  kUniformBSpline,
};

// The largest degree SubdividePolygon accepts.
inline constexpr int kMaxSubdivisionDegree = 64;

// SubdividePolygon refines `polygon` `levels` times and returns the polygon
// of every level, flat coordinates as in PointsView, the last one final.
// Level k converges to the uniform B-spline of degree d (2 for Chaikin,
// whose `degree` is ignored) with control points `polygon` on integer knots,
// the distance falling about 4x per level.
// Closed polygons are periodic: each level has twice the points, starting
// with Q_d (for Chaikin, the 1/4 point of the edge P_0 P_1).
// Open polygons keep only the refined points whose stencil lies inside the
// polygon, Q_d..Q_{2m-1} for m points: m -> 2m - d points, and the refined
// polygon defines exactly the same uniform B-spline on the natural domain
// [d, m] of the original (for Chaikin the 1/4 and 3/4 points of every edge,
// 2m - 2 points; for degree 1 the ends are kept). In both cases point r of
// level k is the control point of the B-spline of knot spacing 2^-k whose
// support starts at (r + d (2^k - 1)) / 2^k.
// Fails with INVALID_ARGUMENT "levels" (< 1), "degree" (kUniformBSpline
// outside [1, kMaxSubdivisionDegree]) or "polygon.coordinates" (fewer than
// d + 1 points when open, 3 when closed).
absl::StatusOr<std::vector<std::vector<double>>> SubdividePolygon(
    const PointsView& polygon, bool closed, SubdivisionScheme scheme,
    int degree, int levels, const CancellationToken* cancel = nullptr);

// InsertSurfaceKnots inserts `knots` into the u (in_u) or v knot vector of
// `surface` by InsertKnots' refinement applied to all columns (rows) of the
// net at once; rules and errors ("knots[i]") as for InsertKnots, against the
// degree and domain of that direction.
absl::StatusOr<SurfaceData> InsertSurfaceKnots(
    const BSplineSurfaceView& surface, bool in_u,
    absl::Span<const double> knots, const CancellationToken* cancel = nullptr);

// SplitBezierSurface cuts `surface` at u = t (in_u) or v = t into two Bezier
// surfaces, each reparameterized to [0, 1]^2: first the part with u (v) in
// [0, t], then [t, 1]; de Casteljau on every column (row) of the
// (homogeneous) net. Results have empty knot vectors. Fails with
// INVALID_ARGUMENT "parameter" unless 0 < t < 1.
absl::StatusOr<std::vector<SurfaceData>> SplitBezierSurface(
    const BezierSurfaceView& surface, bool in_u, double t);

// SplitTriangularPatch cuts `patch` at the interior point X with barycentric
// coordinates (u, v, 1 - u - v) into three patches: patch i (i = 1, 2, 3)
// covers the triangle formed by X and the edge opposite vertex i, with X
// taking the place of vertex i (vertex 1 is u = 1, 2 is v = 1, 3 is w = 1).
// So patch 1 at (a, b) is the original at (a u, a v + b), patch 2 at
// (a + b u, b v), patch 3 at (a + c u, b + c v) with c = 1 - a - b. Its
// control points are faces of the triangular de Casteljau pyramid at X,
// P1(a,b,c) = R^a(0,b,c), P2 = R^b(a,0,c), P3 = R^c(a,b,0) (blossoming;
// Farin 1986). (u, v) are barycentric even when the patch has a domain
// triangle; each piece then gets the triangle with vertex i replaced by X.
// Fails with INVALID_ARGUMENT "u" (not finite or <= 0) or "v" (not finite,
// <= 0, or u + v >= 1).
absl::StatusOr<std::vector<TriangularPatchData>> SplitTriangularPatch(
    const TriangularPatchView& patch, double u, double v);

// BisectTriangularPatch cuts `patch` at the midpoint X of the edge opposite
// vertex `edge` (0, 1, 2: the vertices u = 1, v = 1, w = 1) into two
// patches: those SplitTriangularPatch's rule gives at X for the other two
// vertices (the third would be flat), in increasing vertex order, each with
// X in place of its vertex. Halving an edge this way, always the one
// opposite the newest vertex, keeps the pieces' shapes bounded while their
// size halves every two steps (newest vertex bisection). Fails with
// INVALID_ARGUMENT "edge" outside 0..2.
absl::StatusOr<std::vector<TriangularPatchData>> BisectTriangularPatch(
    const TriangularPatchView& patch, int edge);

}  // namespace freeform

#endif  // FREEFORM_CORE_SUBDIVISION_H_
