// Fitting B-spline curves and surfaces to data by least squares: curves and
// gridded surfaces refined until they meet a tolerance, and surfaces through
// scattered points with a smoothing term.
//
// A fit to a tolerance (docs/references.md, 'Least-squares fitting to a
// tolerance') starts from the Bezier basis (degree + 1 control points),
// fits by least squares with the end points interpolated (The NURBS Book
// A9.7 on the current knots: banded symmetric positive definite normal
// equations, solved by a banded Cholesky factorization), measures
// |C(t_k) - Q_k| at every data parameter and inserts one knot in every knot
// span whose largest error exceeds the tolerance, halfway between the two
// middle parameters of the span, then fits again, until the largest error
// is within the tolerance. A span is split only while it holds at least
// four data points, and never into more control points than data points,
// so every span keeps two data points and the system stays nonsingular
// (Schoenberg-Whitney) and well conditioned. Each round costs O(N p^2) for
// N points; splitting every failing span at once makes the number of
// rounds logarithmic in the number of control points.
//
// A scattered fit (docs/references.md, 'Scattered-data surface fitting')
// minimises (1/N) sum_k |S(u_k, v_k) - Q_k|^2 + lambda E(P) over the control
// net P of a B-spline surface with clamped uniform knots on [0, 1]^2, E a
// discrete thin-plate energy (second differences of the net), with (u_k,
// v_k) given or taken from the points' best-fit plane.
//
// Example, a cubic through 10^5 samples to 1e-4:
//   absl::StatusOr<CurveFit> fit = FitCurve(
//       {.dimension = 3, .coordinates = xyz},
//       {.degree = 3, .tolerance = 1e-4});
//   // fit->max_residual <= 1e-4; fit->curve is ordinary B-spline data.
//
// Errors are INVALID_ARGUMENT naming the field with its full path
// (status.h), and RESOURCE_EXHAUSTED when a fit needs more than its caps
// allow. All functions are thread-safe. Each takes a CancellationToken (may
// be null), polls it as it works and returns its CANCELLED /
// DEADLINE_EXCEEDED status once it stops.
#ifndef FREEFORM_CORE_FITTING_H_
#define FREEFORM_CORE_FITTING_H_

#include <cstddef>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/geometry_data.h"
#include "freeform/core/interpolation.h"
#include "freeform/core/points.h"
#include "freeform/core/tensor_surface.h"

namespace freeform {

// The default cap on the control points of a fit to a tolerance (per
// direction for surfaces).
inline constexpr int kDefaultMaxFitControlPoints = 1 << 16;

// The most parameter-correction rounds a curve fit may ask for.
inline constexpr int kMaxParameterCorrections = 100;

// ------------------------------------------------------------ curves --

struct CurveFitOptions {
  int degree = 3;
  // The largest accepted distance |C(t_k) - Q_k|; positive and finite.
  double tolerance = 0;
  // How parameters are computed (InterpolationParameters) when
  // `parameters` is empty.
  Parameterization parameterization = Parameterization::kChordLength;
  // Explicit strictly increasing parameters, one per point.
  absl::Span<const double> parameters = {};
  // The most control points the fit may use, >= degree + 1 (it never uses
  // more than there are points).
  int max_control_points = kDefaultMaxFitControlPoints;
  // Rounds of parameter correction after every fit (Hoschek 1988): one
  // Newton step of every interior t_k towards the closest point of the
  // curve to Q_k, kept when it stays between its neighbours and off the
  // knots, then a new fit; a round that does not lower the max residual,
  // or leaves a knot span with fewer than two parameters, is undone and
  // ends the corrections of that fit. When corrected parameters bunch up so
  // that no failing span can be split, the fit goes back to the initial
  // parameters and refines by them. 0 (off) to kMaxParameterCorrections.
  int parameter_corrections = 0;
  const CancellationToken* cancel = nullptr;
};

// A curve fitted to a tolerance.
struct CurveFit {
  // Clamped, of the requested degree, on [t_0, t_m].
  BSplineCurveData curve;
  // The parameter of each point (after the corrections, if any).
  std::vector<double> parameters;
  // Largest and root-mean-square |C(t_k) - Q_k| over all points.
  double max_residual = 0;
  double rms_residual = 0;
  // How many times knots were inserted and the curve fitted again.
  int refinement_rounds = 0;
};

// FitCurve returns a B-spline curve of options.degree through the first and
// last point with max_k |C(t_k) - Q_k| <= options.tolerance, refined from
// one span as described at the top of this file. Fails with
// INVALID_ARGUMENT on "degree" (< 1), "points..." (ValidatePoints with at
// least degree + 1 points; a repeated point for chord length or centripetal,
// as InterpolationParameters), "tolerance", "parameters" (count) /
// "parameters[i]" (not finite, not strictly increasing),
// "max_control_points" (< degree + 1) and "parameter_corrections" (outside
// [0, kMaxParameterCorrections]); with RESOURCE_EXHAUSTED on "tolerance"
// when the cap is reached first (the message gives the residual achieved
// and the cap), or when every span above the tolerance holds fewer than
// four points (data too sparse for the tolerance: interpolate them).
absl::StatusOr<CurveFit> FitCurve(const PointsView& points,
                                  const CurveFitOptions& options);

// FitCurveToKnots returns the least-squares B-spline of degree `degree` on
// the given clamped `knots` that interpolates the first and last point
// (A9.7 with any knots): knots[0] == parameters.front() and knots.back() ==
// parameters.back(). Fails with INVALID_ARGUMENT on "degree", "points..."
// (at least as many points as control points and degree + 1), "parameters"
// / "parameters[i]" (one per point, strictly increasing; "parameters" also
// for a singular system, where the data break the Schoenberg-Whitney
// condition) and "knots" / "knots[i]" (ValidateBSplineBasis, not clamped,
// ends not at the first and last parameter).
absl::StatusOr<CurveApproximation> FitCurveToKnots(
    const PointsView& points, int degree, absl::Span<const double> knots,
    absl::Span<const double> parameters,
    const CancellationToken* cancel = nullptr);

// ----------------------------------------------------- gridded surfaces --

struct GridFitOptions {
  int degree_u = 3;
  int degree_v = 3;
  // The largest accepted |S(u_k, v_l) - Q[k][l]|; positive and finite.
  double tolerance = 0;
  // How missing parameters are computed: the grid parameters that
  // InterpolateSurface averages over the grid lines for these degrees.
  Parameterization parameterization = Parameterization::kChordLength;
  // Explicit strictly increasing parameters: count_u values for u, count_v
  // for v (each may be given alone).
  absl::Span<const double> parameters_u = {};
  absl::Span<const double> parameters_v = {};
  // The most control points in each direction, >= degree + 1 (never more
  // than the grid lines in that direction).
  int max_control_points_u = kDefaultMaxFitControlPoints;
  int max_control_points_v = kDefaultMaxFitControlPoints;
  const CancellationToken* cancel = nullptr;
};

// A surface fitted to a grid within a tolerance.
struct SurfaceFit {
  SurfaceData surface;
  std::vector<double> parameters_u, parameters_v;
  // Largest and root-mean-square |S(u_k, v_l) - Q[k][l]| over the grid.
  double max_residual = 0;
  double rms_residual = 0;
  int refinement_rounds = 0;
};

// FitSurfaceToGrid returns a B-spline surface with |S(u_k, v_l) - Q[k][l]|
// <= options.tolerance over the count_u x count_v grid `points` (layout of
// InterpolateSurface). Each round is a tensor-product least-squares fit:
// every column Q[.][l] is fitted on the common u knots with its ends
// interpolated (one factorization for all columns), then every row of that
// intermediate net on the common v knots (one factorization for all rows),
// so the surface interpolates the four corner points. Errors are split by
// direction: the column fits' error e_u(k, l) and the row fits' error
// e_v(i, l) bound the total by max_k e_u + max_i e_v (the u basis is a
// partition of unity); u spans whose e_u exceeds tolerance / 2 and v spans
// whose e_v exceeds tolerance / 2 are split by the curve fit's rule. Fails
// with INVALID_ARGUMENT on "degree_u" / "degree_v" (< 1), "points..."
// (ValidateControlNet; "points.count_u" / "points.count_v" with fewer than
// degree + 1 points; "points" when a whole grid line repeats, as
// InterpolateSurface), "tolerance", "parameters_u" / "parameters_u[i]" (and
// v), "max_control_points_u" / "max_control_points_v" (< degree + 1); with
// RESOURCE_EXHAUSTED on "tolerance" as FitCurve.
absl::StatusOr<SurfaceFit> FitSurfaceToGrid(const ControlNetView& points,
                                            const GridFitOptions& options);

// ---------------------------------------------------- scattered points --

// The default smoothing weight lambda of a scattered fit: small enough to
// change a fit to data that cover the net by less than 1e-5 of the net's
// size even for a net of random control points (smooth nets change far
// less), large enough to fix the control points that no data reach.
inline constexpr double kDefaultScatteredSmoothing = 1e-12;

// The default cap on the operations of a scattered fit (about ten seconds).
inline constexpr size_t kDefaultMaxScatteredOperations = size_t{1} << 34;

struct ScatteredFitOptions {
  int degree_u = 3;
  int degree_v = 3;
  // Control points in each direction, >= degree + 1; at most
  // point count control points in all.
  int control_count_u = 8;
  int control_count_v = 8;
  // Explicit parameters in [0, 1], (u, v) per point: u_0, v_0, u_1, ...
  // Empty: PlaneParameters of the points.
  absl::Span<const double> parameters = {};
  // The weight lambda of the smoothing energy; >= 0 and finite. 0 needs
  // data in the support of every control point.
  double smoothing = kDefaultScatteredSmoothing;
  // The most operations (EstimateScatteredFit) the fit may take.
  size_t max_operations = kDefaultMaxScatteredOperations;
  const CancellationToken* cancel = nullptr;
};

// The cost of a scattered fit, known before any work.
struct ScatteredFitWork {
  // Sub-diagonals of the normal equations in the chosen ordering of the
  // unknowns.
  size_t bandwidth = 0;
  // Bytes of working memory (the band, right-hand sides, parameters).
  size_t memory_bytes = 0;
  // Multiply-adds: assembly, factorization, solve and residuals.
  size_t operations = 0;
  // Of `operations`, those that grow with the number of points.
  size_t point_operations = 0;
};

// EstimateScatteredFit returns the work of FitScatteredSurface for
// `point_count` points of `dimension` coordinates with the degrees and
// control counts of `options` (saturating at SIZE_MAX; negative values
// count as 0). The unknowns are ordered u-major (bandwidth
// max(degree_u count_v + degree_v, 2 count_v)) or v-major, whichever band
// is narrower; the factorization takes about count_u count_v bandwidth^2 / 2
// operations.
ScatteredFitWork EstimateScatteredFit(size_t point_count, int dimension,
                                      const ScatteredFitOptions& options);

// A surface fitted to scattered points.
struct ScatteredFit {
  // Clamped uniform knots on [0, 1] in both directions.
  SurfaceData surface;
  // (u, v) per point, given or computed.
  std::vector<double> parameters;
  // |S(u_k, v_k) - Q_k| per point, measured with EvaluateBSplineSurface.
  std::vector<double> residuals;
  double max_residual = 0;
  double rms_residual = 0;
};

// FitScatteredSurface returns the B-spline surface of the given degrees and
// control counts on [0, 1]^2 that minimises
//   (1/N) sum_k |S(u_k, v_k) - Q_k|^2 + lambda E(P),
//   E(P) = sum A [ |D_uu P|^2 + 2 |D_uv P|^2 + |D_vv P|^2 ],
// D_uu, D_uv, D_vv the second divided differences of the control net over
// its Greville abscissae and A the parameter area each one stands for: a
// discrete thin-plate energy, zero exactly on planes (so a plane is
// reproduced for every lambda), about the integral of |S_uu|^2 +
// 2 |S_uv|^2 + |S_vv|^2 for fine nets, so lambda does not depend on the
// number of points or control points. Fails with INVALID_ARGUMENT on
// "degree_u" / "degree_v" (< 1), "control_count_u" / "control_count_v" (<
// degree + 1), "points..." (ValidatePoints; "points" with fewer points than
// control points; PlaneParameters' errors when parameters are computed),
// "parameters" (not 2 per point) / "parameters[i]" (not finite or outside
// [0, 1]; "parameters" also when the system is singular: lambda = 0 and a
// control point without data), "smoothing" (negative or not finite); with
// RESOURCE_EXHAUSTED when EstimateScatteredFit exceeds
// options.max_operations, on "points" when the per-point work alone does,
// else on the larger of "control_count_u" / "control_count_v".
absl::StatusOr<ScatteredFit> FitScatteredSurface(
    const PointsView& points, const ScatteredFitOptions& options);

// PlaneParameters returns (u, v) in [0, 1]^2 for each point: the
// coordinates in the best-fit plane through the centroid (spanned by the
// eigenvectors of the two largest eigenvalues of the points' covariance,
// found by cyclic Jacobi rotations, each oriented with its largest
// component positive), scaled so that each runs over exactly [0, 1]. For
// points on a plane they are an affine function of any in-plane
// coordinates. Fails with INVALID_ARGUMENT on "points..." (ValidatePoints
// with at least 3 points), "points.dimension" (1: give parameters) and
// "points" when the points lie on a line (the second extent below 1e-12
// of the first).
absl::StatusOr<std::vector<double>> PlaneParameters(
    const PointsView& points, const CancellationToken* cancel = nullptr);

}  // namespace freeform

#endif  // FREEFORM_CORE_FITTING_H_
