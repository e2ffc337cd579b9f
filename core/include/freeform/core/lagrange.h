// Lagrange curves: the polynomial curve of degree n through n + 1 points.
//
// Given points P_0..P_n of any dimension and nodes t_0 < ... < t_n, the
// Lagrange curve is C(t) = sum_i L_i(t) P_i with the Lagrange basis
// L_i(t) = prod_{j != i} (t - t_j) / (t_i - t_j) (docs/references.md,
// 'Lagrange basis and Neville's algorithm'), so C(t_i) = P_i. Its domain
// is [t_0, t_n].
//
// Three single-point evaluators are offered:
//   - NevilleEvaluate: Neville's triangle, O(n^2) per point;
//   - LadderEvaluate: Warren's O(n) ladder (docs/references.md, 'Warren's
//     ladder for Lagrange curves'), which is the first barycentric
//     ("modified Lagrange") form;
//   - BarycentricEvaluate: the second ("true") barycentric form, O(n),
//     exact at the nodes.
// The last two need the barycentric weights, O(n^2) once per set of nodes.
// LagrangeBasis gives every basis function and its derivatives by Warren's
// ladder run in truncated Taylor series arithmetic; the batch evaluators use
// it for positions and derivatives alike. The ladder is backward stable for
// any nodes (Higham, IMA J. Numer. Anal. 24, 2004); the second form's error
// has an extra term Lebesgue function times |C(t)|, which on uniform nodes
// of degree 20 makes it about 1000 times the ladder's.
//
// Example:
//   const std::vector<double> xy = {0, 0, 1, 2, 3, 2, 4, 0};
//   const LagrangeCurveView curve{.points = {.dimension = 2,
//                                            .coordinates = xy}};
//   const std::vector<double> parameters = {0.0, 0.5, 1.0};  // nodes i / 3
//   std::vector<double> positions(2 * parameters.size());
//   const absl::Span<double> output[] = {absl::MakeSpan(positions)};
//   absl::Status status = EvaluateLagrangeCurve(curve, parameters, output);
//
// All functions are thread-safe. The single-point functions never allocate;
// the batch functions allocate per call and per chunk of parameters, never
// per point.
#ifndef FREEFORM_CORE_LAGRANGE_H_
#define FREEFORM_CORE_LAGRANGE_H_

#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/curve_output.h"
#include "freeform/core/points.h"
#include "freeform/core/thread_pool.h"

namespace freeform {

// The polynomial curve of degree n through n + 1 points at nodes
// t_0 < ... < t_n: C(t_i) = P_i. Points and nodes live in caller memory.
struct LagrangeCurveView {
  PointsView points;
  // Empty: uniform nodes t_i = i / n on [0, 1] (t_0 = 0 when n = 0).
  // Otherwise one strictly increasing node per point.
  absl::Span<const double> nodes;

  int degree() const { return static_cast<int>(points.size()) - 1; }
};

// ValidateLagrangeCurve checks the points (at least one, finite; errors name
// "points...") and, when given, the nodes: one per point ("nodes"), finite
// and strictly increasing ("nodes[i]" names the first node that is not
// finite or not greater than its predecessor), with a finite span
// t_n - t_0 ("nodes").
absl::Status ValidateLagrangeCurve(const LagrangeCurveView& curve);

// LagrangeNodes returns the curve's nodes: a copy of curve.nodes, or the
// uniform nodes i / n when they are empty ({0} for a single point).
std::vector<double> LagrangeNodes(const LagrangeCurveView& curve);

// LagrangeDomain returns the parameter interval [t_0, t_n] of a valid curve:
// [0, 1] with uniform nodes (even for a single point), [t_0, t_0] for a
// single point with a given node.
std::pair<double, double> LagrangeDomain(const LagrangeCurveView& curve);

// BarycentricWeights returns the barycentric weights of distinct `nodes`
// t_0 < ... < t_n, w_i = c^n / prod_{j != i} (t_i - t_j), scaled by the
// n-th power of c = (t_n - t_0) / 4 (c = 1 for one node), the logarithmic
// capacity of [t_0, t_n]: the scaling keeps the weights from overflowing or
// underflowing on long or short intervals (Berrut & Trefethen, "Barycentric
// Lagrange Interpolation", SIAM Review 46(3), 2004), and the products are
// formed without intermediate overflow. So
// L_i(t) = w_i prod_{j != i} ((t - t_j) / c). O(n^2).
std::vector<double> BarycentricWeights(absl::Span<const double> nodes);

// NevilleEvaluate writes C(t) into `point` (points.dimension doubles) by
// Neville's algorithm P_{i..j}(t) = ((t - t_i) P_{i+1..j}(t) -
// (t - t_j) P_{i..j-1}(t)) / (t_j - t_i) (docs/references.md, 'Lagrange
// basis and Neville's algorithm'). `nodes` holds one node per point; `scratch`
// at least points.coordinates.size() doubles. O(n^2) per coordinate.
void NevilleEvaluate(const PointsView& points, absl::Span<const double> nodes,
                     double t, absl::Span<double> scratch,
                     absl::Span<double> point);

// LadderEvaluate writes C(t) into `point` (points.dimension doubles) by
// Warren's ladder (docs/references.md, 'Warren's ladder for Lagrange
// curves'): a left rail of products prod_{j<k} ((t - t_j) / c), rungs
// w_k P_k and a right rail multiplied by (t - t_k) / c. `weights` must be
// BarycentricWeights(nodes) (which fixes c). 3n + 1 multiplications per
// coordinate; at a node exact only to rounding.
void LadderEvaluate(const PointsView& points, absl::Span<const double> nodes,
                    absl::Span<const double> weights, double t,
                    absl::Span<double> point);

// BarycentricEvaluate writes C(t) into `point` (points.dimension doubles) by
// the second barycentric form C(t) = sum_i (w_i / (t - t_i)) P_i /
// sum_i (w_i / (t - t_i)) (Berrut & Trefethen 2004); returns P_i exactly
// when t is the node t_i. `weights` must be BarycentricWeights(nodes) (or
// any common multiple of them). O(n) per coordinate.
void BarycentricEvaluate(const PointsView& points,
                         absl::Span<const double> nodes,
                         absl::Span<const double> weights, double t,
                         absl::Span<double> point);

// LagrangeBasis writes the derivatives of order k = 0..max_order of all
// n + 1 Lagrange basis functions of `nodes` at t into
// values[k * (n + 1) + i] = L_i^(k)(t); orders above n are zero. At a node
// the order-0 values are exactly the cardinal L_i(t_j) = delta_ij. `weights`
// must be BarycentricWeights(nodes); `values` holds (max_order + 1) * (n + 1)
// doubles and `scratch` at least max_order + 1. O(n max_order^2).
//
// Example: nodes {0, 1, 2, 3} at t = 0.5 give values[0..3] =
// {0.3125, 0.9375, -0.3125, 0.0625} (docs/references.md,
// 'Worked example: the cubic Lagrange basis on the nodes 0, 1, 2, 3').
void LagrangeBasis(absl::Span<const double> nodes,
                   absl::Span<const double> weights, double t, int max_order,
                   absl::Span<double> scratch, absl::Span<double> values);

// EvaluateLagrangeCurve writes derivatives 0..output.size()-1 of `curve` at
// every parameter into `output` (see curve_output.h) as
// sum_i L_i^(k)(t) P_i with LagrangeBasis; C(t_i) = P_i exactly, and orders
// above the degree are zero. Parameters must lie in LagrangeDomain(curve).
// Degrees up to about 1000 are safe; beyond, the ladder's partial products
// may overflow. Fails with INVALID_ARGUMENT for an invalid curve, a
// parameter outside the domain ("parameters[i]") or wrongly sized output,
// and with CANCELLED / DEADLINE_EXCEEDED when the context's token stops the
// batch (the output is then partly written).
absl::Status EvaluateLagrangeCurve(const LagrangeCurveView& curve,
                                   absl::Span<const double> parameters,
                                   CurveOutput output,
                                   const ExecutionContext& context = {});

// LagrangeToBezier returns the Bezier control points (flat, as in
// PointsView) of a valid `curve` on its domain [t_0, t_n], reparameterized
// to [0, 1]: the same polynomial in Bernstein form, b_k = sum_i [B_k] L_i
// P_i. Each basis polynomial L_i is the product of its linear factors
// (t - t_j) / (t_i - t_j), multiplied in Bernstein form in double-double
// arithmetic (the conversion's condition number grows exponentially with
// the degree: 1e6 for 17 uniform nodes, 1e26 for 65), from exact node
// differences, so that the result is the exact Bernstein form to within
// a proven bound (docs/references.md, 'The Bernstein form of a Lagrange
// curve'). The ends are P_0 and P_n exactly; a single point is its own
// degree-0 curve. Fails with INVALID_ARGUMENT naming "nodes" when that
// bound exceeds 2^-53 of the largest point coordinate (CheckLagrangeBezierForm)
// and naming "points" when a Bezier point overflows. O(n^3) operations.
absl::StatusOr<std::vector<double>> LagrangeToBezier(
    const LagrangeCurveView& curve);

// CheckLagrangeBezierForm returns LagrangeToBezier's refusal of `curve`
// ("nodes": the conversion's error bound exceeds 2^-53 of the largest point
// coordinate) without converting: O(n^3) operations in double. Uniform
// nodes pass to degree 31, Chebyshev points to degree 42, nodes whose gaps
// differ by ten orders of magnitude hardly at all. Evaluation needs no
// Bezier form, so only the work on Bezier pieces is refused.
absl::Status CheckLagrangeBezierForm(const LagrangeCurveView& curve);

// EvaluateLagrangeBasis writes the dense Lagrange basis of `nodes` (the
// EvaluateBasis RPC): output[k][r * (n + 1) + i] = L_i^(k)(parameters[r]),
// so each output buffer holds parameters.size() * (n + 1) doubles. The
// nodes must be given ("nodes": at least one) and finite and strictly
// increasing ("nodes[i]"), with a finite span ("nodes"); parameters must lie
// in [t_0, t_n] ("parameters[i]"). Fails like EvaluateLagrangeCurve.
absl::Status EvaluateLagrangeBasis(absl::Span<const double> nodes,
                                   absl::Span<const double> parameters,
                                   CurveOutput output,
                                   const ExecutionContext& context = {});

}  // namespace freeform

#endif  // FREEFORM_CORE_LAGRANGE_H_
