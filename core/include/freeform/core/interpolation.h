// Interpolation and approximation of data by B-spline curves and surfaces.
//
// Global interpolation (The NURBS Book A9.1, eqs. 9.3-9.9;
// docs/references.md, 'Global B-spline interpolation') finds the B-spline curve
// of degree p with one control point per data point (plus one per given end
// derivative) that passes through every point Q_k at its parameter t_k. The
// parameters come from a Parameterization, the knots from a KnotRule; the
// collocation matrix N_{i,p}(t_k) is banded and, for increasing parameters,
// totally nonnegative, so it is solved in O(n) by a banded LU without pivoting
// (de Boor and Pinkus, Numer. Math. 27, 1977). Closed curves give a periodic
// B-spline (cyclic banded system). KnotRule::kAtParameters reproduces
// OpenCASCADE's GeomAPI_Interpolate (knots at the parameters, estimated or
// given end tangents). Cubic splines with the classic end conditions (de
// Boor, "A Practical Guide to Splines", ch. IV), least-squares approximation
// (A9.7) and surface interpolation through a grid (A9.4) come back as
// ordinary B-spline data, so every other operation works on the results.
//
// Example, a cubic through five planar points (docs/references.md,
// 'Worked example: a cubic B-spline through five planar points'):
//   const std::vector<double> xy = {0, 0, 3, 4, -1, 4, -4, 0, -4, -3};
//   absl::StatusOr<CurveInterpolation> result = InterpolateCurve(
//       {.dimension = 2, .coordinates = xy}, CurveInterpolationOptions{});
//   // result->parameters == {0, 5/17, 9/17, 14/17, 1},
//   // result->curve.knots == {0, 0, 0, 0, 28/51, 1, 1, 1, 1}.
//
// Errors are INVALID_ARGUMENT naming the field (status.h); a singular system
// (parameters and knots breaking the Schoenberg-Whitney condition) names
// "parameters". All functions are thread-safe and allocate O(n) memory.
// Each takes a CancellationToken (may be null), polls it as it works and
// returns its CANCELLED / DEADLINE_EXCEEDED status once it stops.
#ifndef FREEFORM_CORE_INTERPOLATION_H_
#define FREEFORM_CORE_INTERPOLATION_H_

#include <vector>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/geometry_data.h"
#include "freeform/core/points.h"
#include "freeform/core/tensor_surface.h"

namespace freeform {

// How data points get their parameters t_0 < ... < t_n in [0, 1].
enum class Parameterization {
  // t_k = k / n.
  kUniform,
  // Proportional to the distances |Q_k - Q_{k-1}| (eq. 9.5).
  kChordLength,
  // Proportional to sqrt(|Q_k - Q_{k-1}|) (eq. 9.6).
  kCentripetal,
  // The "universal" method (Lim 1999; docs/references.md, 'Universal
  // parameterization'): uniform clamped knots, and the parameters are the
  // maxima of the basis functions on them. Fixes the knots too (the
  // KnotRule is ignored) and is affine invariant.
  kUniversal,
};

// How interior knots follow from the parameters.
enum class KnotRule {
  // u_{j+p} = (t_j + ... + t_{j+p-1}) / p (eq. 9.8).
  kAveraging,
  // Equally spaced on [t_0, t_n].
  kUniform,
  // OpenCASCADE's GeomAPI_Interpolate rule (docs/references.md,
  // 'Interpolation with knots at the parameters (OpenCASCADE rule)'): for N
  // points at t_0 < ... < t_{N-1} the knots are the parameters, t_0 (x4),
  // t_1, ..., t_{N-2}, t_{N-1} (x4), of a cubic with N + 2 control points,
  // the two extra equations being the end derivatives C'(t_0), C'(t_{N-1}).
  // An end derivative not given is estimated: the derivative at that end of
  // the Lagrange cubic through the four end points at their parameters (the
  // parabola through all three when N = 3, the line when N = 2). Without
  // end derivatives, two points give the line (degree 1) and three the
  // parabola (degree 2, no interior knot), as OpenCASCADE does. Closed
  // curves: see InterpolateCurve. Only InterpolateCurve takes this rule.
  kAtParameters,
};

// InterpolationParameters returns one parameter per point of an open curve,
// t_0 = 0 < ... < t_n = 1. For kUniversal the parameters are the maxima of
// N_{i,degree} on the clamped uniform knots with interior knots
// j / (n - degree + 1), found by a safeguarded Newton iteration on N' inside
// the support (to about 1e-16); e.g. degree 3 and five points give 0,
// 0.226541..., 1/2, 0.773459..., 1. Fails with INVALID_ARGUMENT on "points..."
// (see ValidatePoints; fewer than degree + 1 points is
// "points.coordinates"), "degree" (< 1), and for chord length or centripetal
// on a point equal to its predecessor: "points.coordinates[k]" with k the
// first coordinate index of the repeated point.
absl::StatusOr<std::vector<double>> InterpolationParameters(
    const PointsView& points, int degree, Parameterization parameterization);

// Options of InterpolateCurve.
struct CurveInterpolationOptions {
  int degree = 3;
  Parameterization parameterization = Parameterization::kChordLength;
  // Explicit strictly increasing parameters ("parameters[i]"), one per point;
  // overrides `parameterization`. For closed curves one more value may be
  // given: the parameter where the curve returns to the first point (else
  // the closing interval is the mean of the others).
  absl::Span<const double> parameters = {};
  KnotRule knot_rule = KnotRule::kAveraging;
  // Each empty or `dimension` values: the first derivative C'(t_0) / C'(t_n).
  // Each adds one control point (A9.2-style extra equation, knots by
  // averaging over the parameters with t_0 / t_n doubled); needs degree >= 2
  // and an open curve. With KnotRule::kAtParameters they are the rule's end
  // derivatives, estimated when empty, and a closed curve takes
  // start_derivative as C'(t_0) where it closes.
  absl::Span<const double> start_derivative = {};
  absl::Span<const double> end_derivative = {};
  // Only with KnotRule::kAtParameters: take the given end derivatives as
  // directions and set their lengths as GeomAPI_Interpolate::Load(...,
  // Scale = true) does: D times |L'|_1 / |D|_1 (1-norms, the sums of
  // absolute coordinates), with L the parabola through the first three
  // points (the line through two) evaluated at the derivative's end, at
  // t_{N-1} for the end derivative too. False (Scale = false) takes them as
  // they are.
  bool scale_end_derivatives = false;
  // Interpolate a closed curve through the points (the first point is not
  // repeated at the end).
  bool closed = false;
  // Polled while the system is built, solved and checked (may be null); the
  // call then returns the token's CANCELLED / DEADLINE_EXCEEDED status.
  const CancellationToken* cancel = nullptr;
};

// A curve through data points.
struct CurveInterpolation {
  BSplineCurveData curve;
  // The parameter of each data point (inside the curve's domain).
  std::vector<double> parameters;
  // max_k |C(t_k) - Q_k|, measured with EvaluateBSplineCurve.
  double max_residual = 0;
};

// InterpolateCurve returns the B-spline of degree options.degree through
// every point (A9.1): clamped knots on [t_0, t_n] by the KnotRule (universal:
// its own uniform knots), end derivatives matched when given. A closed curve
// with N points is a periodic B-spline with N + p control points (the first
// p repeated at the end) on an unclamped knot vector whose domain
// [u_p, u_{N+p}] is one period, C^(p-1) where it closes; its parameters are
// those of the open sequence closed by one more chord, taken modulo the
// period into the domain (so the last ones may wrap to its start). Open
// systems are solved by a banded LU without pivoting, closed ones by
// bordering a banded LU with a p x p Schur complement.
// Fails with INVALID_ARGUMENT on "points..." (ValidatePoints with at least
// degree + 1 points), "degree" (< 1), "parameters" / "parameters[i]" (count,
// finiteness, not strictly increasing, or a singular system),
// "start_derivative" / "end_derivative" (size, not finite, degree 1 or
// closed) and "points.coordinates[k]" for a repeated point (chord length,
// centripetal).
//
// With KnotRule::kAtParameters (GeomAPI_Interpolate; docs/references.md,
// 'Interpolation with knots at the parameters (OpenCASCADE rule)') the
// degree must be the rule's: 3, or 1 for two points and 2 for three points
// when no end derivative is given. Parameters are chord length (the
// default), centripetal, uniform or explicit, normalized to [0, 1] when
// computed: the knots are then OpenCASCADE's (cumulative chord lengths)
// divided by the polygon's length L and the control points are the same,
// provided a derivative D given to OpenCASCADE with Scale = false is given
// here as L D (estimated and scaled derivatives need no conversion); pass
// OpenCASCADE's parameters explicitly to get its knots too. A closed curve
// (GeomAPI_Interpolate with PeriodicFlag) is a cubic whose knots are the
// N + 1 parameters of the closed sequence, t_0 doubled: N + 3 control
// points, the first two repeated at the end, on the N + 7 knots
// t_{N-2} - T, t_{N-1} - T, t_0, t_0, t_1, ..., t_{N-1}, t_N, t_N,
// t_1 + T, t_2 + T (T = t_N - t_0 the period), C2 except at t_0 where it is
// C1 with C'(t_0) = start_derivative (estimated from the first four points
// as for open curves when empty). Two points without a derivative give the
// closed polygon of degree 1 (knots t_1 - T, t_0, t_1, t_2, t_1 + T).
// Errors as above, and "degree" (not the rule's degree),
// "parameterization" (kUniversal), "end_derivative" (given for a closed
// curve: its one derivative is start_derivative), "start_derivative" /
// "end_derivative" (a zero vector with scale_end_derivatives),
// "scale_end_derivatives" (set with another knot rule), and "points..."
// (fewer than two points).
absl::StatusOr<CurveInterpolation> InterpolateCurve(
    const PointsView& points, const CurveInterpolationOptions& options);

// End conditions of a cubic spline (de Boor, "A Practical Guide to Splines",
// ch. IV; docs/references.md, 'Cubic spline end conditions').
enum class SplineEnd {
  // s''(x_0) = s''(x_n) = 0.
  kNatural,
  // Given s'(x_0) and s'(x_n) (the complete spline).
  kClamped,
  // s''' continuous at x_1 and x_{n-1}.
  kNotAKnot,
  // s, s', s'' equal at both ends; needs y_0 == y_n.
  kPeriodic,
};

// InterpolateCubicSpline returns the C2 cubic spline s with s(x_k) = y_k
// (values of any dimension at strictly increasing x) as a cubic B-spline with
// a simple knot at every interior x_k: clamped knots x_0 (x4), x_1, ...,
// x_{n-1}, x_n (x4) for the non-periodic ends; for kPeriodic the periodic
// unclamped knots ..., x_{n-1} - T, x_0, ..., x_n, x_1 + T, ... (T = x_n -
// x_0) with domain [x_0, x_n] and N + 3 control points for the N = n distinct
// points. Needs at least 2 points (3 for kPeriodic). kNotAKnot with 2 or 3
// points gives the interpolating line or parabola (the not-a-knot
// conditions then leave no cubic freedom), as de Boor and SciPy do; with 4 or
// more it interpolates on the knots without x_1 and x_{n-1} and inserts them
// back. Fails with INVALID_ARGUMENT on "points..." (too few points for the
// end condition: "points.coordinates"; kPeriodic with y_0 != y_n beyond
// 1e-12 relative: "points"), "parameters" / "parameters[i]",
// "start_derivative" / "end_derivative" (required with exactly `dimension`
// finite values for kClamped, must be empty otherwise).
absl::StatusOr<CurveInterpolation> InterpolateCubicSpline(
    const PointsView& values, absl::Span<const double> x, SplineEnd end,
    absl::Span<const double> start_derivative,
    absl::Span<const double> end_derivative,
    const CancellationToken* cancel = nullptr);

// A least-squares approximation of data points.
struct CurveApproximation {
  BSplineCurveData curve;
  std::vector<double> parameters;
  // Largest and root-mean-square distance |C(t_k) - Q_k| over all points.
  double max_residual = 0;
  double rms_residual = 0;
};

// ApproximateCurve returns the B-spline of degree `degree` with
// `control_point_count` control points that interpolates the first and last
// point and fits the others in the least-squares sense (The NURBS Book A9.7,
// knots by eq. 9.69, normal equations solved by a banded LU, which is safe
// since they are symmetric positive definite). `parameters` (one per point,
// strictly increasing) overrides `parameterization`; kUniversal uses the
// universal parameters of the points with eq. 9.69 knots. Fails with
// INVALID_ARGUMENT on "points..." (at least degree + 1 points), "degree",
// "control_point_count" (outside [degree + 1, point count]),
// "parameters"/"parameters[i]" and a repeated point as InterpolateCurve.
absl::StatusOr<CurveApproximation> ApproximateCurve(
    const PointsView& points, int degree, int control_point_count,
    Parameterization parameterization, absl::Span<const double> parameters,
    const CancellationToken* cancel = nullptr);

// A surface through a grid of points.
struct SurfaceInterpolation {
  SurfaceData surface;
  std::vector<double> parameters_u, parameters_v;
  // max |S(u_k, v_l) - Q[k][l]|, measured with EvaluateBSplineSurface.
  double max_residual = 0;
};

// InterpolateSurface returns the B-spline surface of degrees (degree_u,
// degree_v) with S(u_k, v_l) = Q[k][l] for the count_u x count_v grid
// `points` (The NURBS Book A9.4; docs/references.md, 'Global B-spline
// interpolation'): u parameters are averaged over the columns Q[.][l] (for
// chord length and centripetal, columns of zero length are skipped as in
// A9.3), v parameters over the rows, knots by the KnotRule (universal:
// uniform), then curves are interpolated through the columns and through the
// rows of the result with one banded factorization per direction reused for
// every right-hand side. Fails with
// INVALID_ARGUMENT on "points..." (ValidateControlNet with at least degree + 1
// points each way), "degree_u" / "degree_v" (< 1), "knot_rule"
// (kAtParameters, which needs end derivatives), and "points" when the
// averaged parameters are not strictly increasing (a whole grid row or column
// repeated).
absl::StatusOr<SurfaceInterpolation> InterpolateSurface(
    const ControlNetView& points, int degree_u, int degree_v,
    Parameterization parameterization, KnotRule knot_rule,
    const CancellationToken* cancel = nullptr);

}  // namespace freeform

#endif  // FREEFORM_CORE_INTERPOLATION_H_
