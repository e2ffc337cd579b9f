// Bezier curves: evaluation with derivatives, polynomial and rational.
//
// A Bezier curve of degree n has n + 1 control points P_i of any dimension
// and lives on t in [0, 1]: C(t) = sum_i B(n,i,t) P_i with the Bernstein
// polynomials B(n,i,t) = binom(n,i) (1-t)^(n-i) t^i. With weights w_i it is
// rational, C(t) = sum_i w_i P_i B(n,i,t) / sum_i w_i B(n,i,t), and is
// evaluated in homogeneous form (w_i P_i, w_i) and projected, with
// derivatives by the quotient rule (The NURBS Book, eq. 4.8). A control
// point with weight 0 is a point at infinity: its coordinates are read as the
// direction P (homogeneous (P, 0)), as in the half circle (1,0,1), (0,1,0),
// (-1,0,1) (docs/references.md,
// 'Worked example: the half circle with a point at infinity').
//
// Batch outputs are one buffer per derivative order (see curve_output.h).
//
// All functions are thread-safe; they allocate per call or per chunk of
// parameters, never per point.
#ifndef FREEFORM_CORE_BEZIER_H_
#define FREEFORM_CORE_BEZIER_H_

#include <cstddef>
#include <vector>

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "freeform/core/curve_output.h"
#include "freeform/core/points.h"
#include "freeform/core/rational.h"
#include "freeform/core/thread_pool.h"

namespace freeform {

// A Bezier curve whose control points (and optional weights) live in caller
// memory.
struct BezierCurveView {
  PointsView control_points;
  // Empty: polynomial. Otherwise one weight per control point.
  absl::Span<const double> weights;

  int degree() const { return static_cast<int>(control_points.size()) - 1; }
  bool rational() const { return !weights.empty(); }
};

// ValidateBezierCurve checks the control points (at least one, finite) and
// the weights: one per control point, finite, >= 0, and the first and last
// positive so that the denominator stays positive on [0, 1] (with
// nonnegative weights it can only vanish at an end). Errors name
// "control_points...", "weights" or "weights[i]".
absl::Status ValidateBezierCurve(const BezierCurveView& curve);

// How EvaluateBezierCurve computes each point. All agree to rounding.
enum class BezierAlgorithm {
  // Warren's ladder up to kLinearMaxAutoDegree, de Casteljau above (chosen
  // by measured accuracy against a long-double reference: see
  // tests/core/bezier_test.cc, AlgorithmsMatchLongDoubleReference; the
  // ladder needs no division, so it is the fastest across parameters).
  kAuto,
  // The de Casteljau triangle, O(n^2) per point; derivatives from forward
  // differences of its intermediate levels.
  kDeCasteljau,
  // Horner's rule in t/(1-t) (or (1-t)/t past t = 1/2) on binom(n,i) P_i,
  // O(n) per point and order; derivatives from the hodographs.
  kHorner,
  // Warren's ladder (docs/references.md, 'Warren's ladder for Bezier
  // curves'), O(n).
  kLadder,
};

// The highest degree kAuto evaluates with an O(n) scheme (the ladder).
// Against a long-double reference all three schemes stay within 3.5e-15 of
// the control points' scale through degree 64
// (AlgorithmsMatchLongDoubleReference prints the figures) and the O(n)
// schemes are 3-7x faster than de Casteljau; above degree 48 the binomial
// coefficients they scale by are no longer exact doubles, so kAuto falls
// back to de Casteljau there.
inline constexpr int kLinearMaxAutoDegree = 48;

// ResolveBezierAlgorithm returns the scheme kAuto picks for `degree`, or
// `algorithm` itself when it is not kAuto.
BezierAlgorithm ResolveBezierAlgorithm(BezierAlgorithm algorithm, int degree);

// EvaluateBezierCurve writes derivatives 0..output.size()-1 of `curve` at
// every parameter into `output` using `algorithm`.
// Parameters must lie in [0, 1]. Derivatives of order above the degree of a
// polynomial curve are zero. Fails with INVALID_ARGUMENT for an invalid
// curve, a parameter outside [0, 1] ("parameters[i]") or wrongly sized
// output, and with CANCELLED / DEADLINE_EXCEEDED when the context's token
// stops the batch (the output is then partly written).
absl::Status EvaluateBezierCurve(
    const BezierCurveView& curve, absl::Span<const double> parameters,
    CurveOutput output, const ExecutionContext& context = {},
    BezierAlgorithm algorithm = BezierAlgorithm::kAuto);

// BezierPointEvaluator evaluates one valid Bezier curve point by point,
// with derivatives 0..max_order: the per-curve work (homogeneous points,
// hodographs) is done once in the constructor. Evaluate() is const and
// thread-safe; each thread passes its own scratch of scratch_size() doubles.
// `curve` must have passed ValidateBezierCurve; the evaluator keeps its own
// copy of what it needs.
class BezierPointEvaluator {
 public:
  BezierPointEvaluator(const BezierCurveView& curve, int max_order,
                       BezierAlgorithm algorithm = BezierAlgorithm::kAuto);

  size_t scratch_size() const;
  // Evaluate writes C^(k)(t) into derivatives[k * dimension + j].
  void Evaluate(double t, double* scratch, double* derivatives) const;

 private:
  int degree_;
  int dimension_;
  int max_order_;
  bool rational_;
  BezierAlgorithm algorithm_;
  std::vector<double> control_;                  // homogeneous when rational
  std::vector<std::vector<double>> hodographs_;  // O(n) schemes only
};

// DeCasteljauDerivatives evaluates one point: it writes C^(k)(t) for
// k = 0..max_order of the polynomial curve with n + 1 control points of
// `dimension` coordinates at `control` into derivatives[k * dimension + j].
// `scratch` must hold 2 * (n + 1) * dimension doubles. The k-th derivative
// is n!/(n-k)! times the k-th forward difference of the de Casteljau points
// of level n - k (Farin, "Curves and Surfaces for CAGD", section 5.3).
void DeCasteljauDerivatives(const double* control, int n, int dimension,
                            double t, int max_order, double* scratch,
                            double* derivatives);

// HornerBezierPoint writes the point of the degree-n Bezier curve whose
// control points, each multiplied by binom(n, i), are `scaled`.
void HornerBezierPoint(const double* scaled, int n, int dimension, double t,
                       double* point);

// LadderBezierPoint is HornerBezierPoint by Warren's ladder:
// S_0 = Q_0, S_k = (1-t) S_{k-1} + t^k Q_k, C(t) = S_n with Q_k the scaled
// control points.
void LadderBezierPoint(const double* scaled, int n, int dimension, double t,
                       double* point);

// PowerToBezier returns the Bezier control points of the power-form curve
// C(t) = sum_j A_j t^j on [0, 1] (A_j = `coefficients`): the inverse of the
// Bezier geometry matrix, P_i = sum_{j<=i} binom(i,j) / binom(n,j) A_j.
std::vector<double> PowerToBezier(const PointsView& coefficients);

// BezierToPower returns the power-form coefficients A = M_B P with the
// Bezier geometry matrix M_B[j][i] = (-1)^(j-i) binom(n,j) binom(j,i)
// (for n = 3 the rows are 1 0 0 0 / -3 3 0 0 / 3 -6 3 0 / -1 3 -3 1;
// docs/references.md, 'The Bezier geometry matrix').
std::vector<double> BezierToPower(const PointsView& control_points);

// EvaluateBernsteinBasis writes the Bernstein polynomials B(n,i,t) of degree
// n (or, with n + 1 weights, the rational basis w_i B_i / sum_j w_j B_j) and
// their derivatives: output[k][r * (n + 1) + i] is the k-th derivative of
// function i at parameters[r], from the triangle of Bernstein values of
// degrees 0..n and B(m,i)' = m (B(m-1,i-1) - B(m-1,i)); rational functions
// by the quotient rule (rational.h). Any degree n >= 0 ("degree"); weights
// follow the Bezier rules ("weights", "weights[i]"); parameters must lie in
// [0, 1] ("parameters[i]"). O(n^2) per parameter and order.
absl::Status EvaluateBernsteinBasis(int n, absl::Span<const double> weights,
                                    absl::Span<const double> parameters,
                                    CurveOutput output,
                                    const ExecutionContext& context = {});

// BernsteinBasis writes B(n,i,t), i = 0..n, into values (n + 1 doubles) by
// the triangular recurrence B(j,i) = (1-t) B(j-1,i) + t B(j-1,i-1).
void BernsteinBasis(int n, double t, absl::Span<double> values);

}  // namespace freeform

#endif  // FREEFORM_CORE_BEZIER_H_
