// B-spline and NURBS curves: validation, span search, basis functions and
// batch evaluation with derivatives.
//
// A B-spline curve of degree p has n + 1 control points P_i of any dimension
// and a non-decreasing knot vector u_0 <= ... <= u_{n+p+1} (n + p + 2 knots):
// C(u) = sum_i N_{i,p}(u) P_i with the basis functions of the Cox-de Boor
// recurrence (docs/references.md, 'Cox-de Boor recurrence'). The curve lives
// on the domain [u_p, u_{n+1}], where the basis functions sum to one, so
// clamped ([a..a, ..., b..b]) and unclamped knot vectors are both accepted.
// With weights w_i it is a NURBS curve, C(u) = sum_i w_i N_{i,p} P_i /
// sum_i w_i N_{i,p}, evaluated in homogeneous form (w_i P_i, w_i) and
// projected. As for rational Bezier curves (bezier.h), a control point with
// weight 0 is a point at infinity whose coordinates are its direction
// (homogeneous (P, 0)), e.g. the half circle (1,0), (0,1), (-1,0) with
// weights 1, 0, 1 on knots 0,0,0,1,1,1.
//
// At an interior knot every value (and derivative) is the right-hand limit;
// at the end of the domain it is the left-hand limit, so the whole closed
// domain can be evaluated.
//
// Example, a clamped cubic with 5 planar control points on [0, 2]:
//   const std::vector<double> points = {0,0, 1,2, 2,0, 3,2, 4,0};
//   const std::vector<double> knots = {0,0,0,0, 1, 2,2,2,2};
//   BSplineCurveView curve{.degree = 3,
//                          .control_points = {.dimension = 2,
//                                             .coordinates = points},
//                          .knots = knots};
//   std::vector<double> xy(2 * parameters.size());
//   std::vector<absl::Span<double>> output = {absl::MakeSpan(xy)};
//   absl::Status status = EvaluateBSplineCurve(curve, parameters, output);
//
// All functions are thread-safe; the batch evaluators allocate per call or
// per chunk of parameters, never per point, and the single-point helpers
// (FindSpan, BasisFunctions, ...) never allocate.
#ifndef FREEFORM_CORE_BSPLINE_H_
#define FREEFORM_CORE_BSPLINE_H_

#include <cstddef>

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "freeform/core/curve_output.h"
#include "freeform/core/points.h"
#include "freeform/core/thread_pool.h"

namespace freeform {

// A B-spline (NURBS with weights) curve of degree p with n + 1 control
// points and n + p + 2 knots, in caller memory.
struct BSplineCurveView {
  int degree = 0;
  PointsView control_points;
  absl::Span<const double> knots;
  // Empty: non-rational. Otherwise one weight per control point.
  absl::Span<const double> weights;

  // rational returns true when the curve has weights.
  bool rational() const { return !weights.empty(); }
};

// ValidateBSplineCurve checks every rule a curve must follow to be
// evaluated. Errors are INVALID_ARGUMENT naming the field, relative to the
// curve:
//   "degree": negative;
//   "control_points...": see ValidatePoints; "control_points.coordinates"
//     when there are fewer than degree + 1 control points;
//   "knots": not n + p + 2 knots, or an empty domain (u_p == u_{n+1});
//   "knots[i]": not finite, smaller than knots[i-1], or the first knot
//     beyond the allowed multiplicity: a value strictly inside the domain
//     (u_p, u_{n+1}) may appear at most p times (the curve is continuous),
//     any other value at most p + 1 times;
//   "weights": not one weight per control point;
//   "weights[i]": not finite or negative, or (a weight 0 of) a control point
//     that makes the curve infinite: the denominator sum_i w_i N_{i,p} must
//     be positive at both ends of every non-empty knot span, evaluated as
//     the evaluators do (right-hand limit at its start, left-hand limit at
//     its end); with nonnegative weights it is then positive on the whole
//     domain.
absl::Status ValidateBSplineCurve(const BSplineCurveView& curve);

// ValidateBSplineBasis checks a basis of degree `degree` on `knots` (with
// one weight per function, or none) by the rules of ValidateBSplineCurve
// with function_count = knots.size() - degree - 1 in place of the control
// points; fewer than 2 (degree + 1) knots is an error on "knots". Its domain
// is [knots[degree], knots[function_count]].
absl::Status ValidateBSplineBasis(int degree, absl::Span<const double> knots,
                                  absl::Span<const double> weights);

// A closed parameter interval [start, end].
struct ParameterDomain {
  double start = 0.0;
  double end = 0.0;
};

// BSplineDomain returns the domain [u_p, u_{n+1}] of a valid curve.
ParameterDomain BSplineDomain(const BSplineCurveView& curve);

// FindSpan returns the knot span index s in [p, n] with u_s <= u < u_{s+1}
// by binary search (The NURBS Book A2.1, adapted): the span is never empty,
// so at an interior knot it is the span to the right of the knot, and for
// u >= u_{n+1} (the end of the domain) it is the last non-empty span, which
// makes evaluation there a left-hand limit. `knots` holds n + p + 2
// non-decreasing values with u_p < u_{n+1}; u < u_p gives the first
// non-empty span.
int FindSpan(int n, int p, double u, absl::Span<const double> knots);

// FindSpanFrom returns FindSpan(n, p, u, knots), starting from the span
// `hint` (any int): it walks a few spans from the hint and falls back to the
// binary search, so a sorted batch that passes each result as the next hint
// costs O(1) per parameter.
int FindSpanFrom(int hint, int n, int p, double u,
                 absl::Span<const double> knots);

// BasisScratchSize returns how many doubles of scratch BasisFunctions needs
// for degree p: (p + 1) (p + 4) / 2.
constexpr size_t BasisScratchSize(int p) {
  return (static_cast<size_t>(p) + 1) * (static_cast<size_t>(p) + 4) / 2;
}

// BasisFunctions writes the p + 1 basis functions that may be nonzero on
// the non-empty span `span` (e.g. from FindSpan), N_{span-p,p}(u) ..
// N_{span,p}(u), into
// values[0..p] (The NURBS Book A2.2). `scratch` holds at least
// BasisScratchSize(p) doubles. Does not allocate.
void BasisFunctions(int span, double u, int p, absl::Span<const double> knots,
                    absl::Span<double> values, absl::Span<double> scratch);

// BasisDerivativesScratchSize returns how many doubles of scratch
// BasisFunctionDerivatives needs for degree p: (p + 1) (3p + 10) / 2.
constexpr size_t BasisDerivativesScratchSize(int p) {
  return BasisScratchSize(p) +
         (static_cast<size_t>(p) + 1) * (static_cast<size_t>(p) + 3);
}

// BasisFunctionDerivatives writes the k-th derivatives of the p + 1 basis
// functions of span `span`, N^(k)_{span-p+j,p}(u), into
// ders[k * (p + 1) + j] for k = 0..max_order and j = 0..p (The NURBS Book
// A2.3); orders above p are zero. `ders` holds at least
// (max_order + 1) (p + 1) doubles and `scratch` at least
// BasisDerivativesScratchSize(p). Does not allocate.
void BasisFunctionDerivatives(int span, double u, int p, int max_order,
                              absl::Span<const double> knots,
                              absl::Span<double> ders,
                              absl::Span<double> scratch);

// EvaluateBSplineCurve writes derivatives 0..output.size()-1 of `curve` at
// every parameter into `output` (see curve_output.h). Parameters must lie in
// the domain [u_p, u_{n+1}]; sorted parameters are fastest. Derivatives of
// order above the degree of a non-rational curve are zero. Fails with
// INVALID_ARGUMENT for an invalid curve (see ValidateBSplineCurve), a
// parameter outside the domain or not finite ("parameters[i]") or wrongly
// sized output, and with CANCELLED / DEADLINE_EXCEEDED when the context's
// token stops the batch (the output is then partly written).
absl::Status EvaluateBSplineCurve(const BSplineCurveView& curve,
                                  absl::Span<const double> parameters,
                                  CurveOutput output,
                                  const ExecutionContext& context = {});

// EvaluateBSplineBasis writes the dense basis of degree `degree` on `knots`
// at every parameter: with function_count = knots.size() - degree - 1,
// output[k][r * function_count + i] receives the k-th derivative at
// parameters[r] of N_{i,p}, or with weights (one per function) of the
// rational basis R_i = w_i N_{i,p} / sum_j w_j N_{j,p}; functions whose
// support does not contain the parameter's span are 0. Fails like
// EvaluateBSplineCurve, with the basis checked by ValidateBSplineBasis and
// output buffers of count * function_count doubles.
absl::Status EvaluateBSplineBasis(int degree, absl::Span<const double> knots,
                                  absl::Span<const double> weights,
                                  absl::Span<const double> parameters,
                                  CurveOutput output,
                                  const ExecutionContext& context = {});

}  // namespace freeform

#endif  // FREEFORM_CORE_BSPLINE_H_
