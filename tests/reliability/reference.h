// Reference mathematics for the reliability tests: the blending functions
// and the curves and surfaces built on them, written straight from their
// definitions (docs/references.md) and independent of freeform's core, so
// that answers are checked against the mathematics and not against the
// server's own algorithms. Slow and simple on purpose: direct sums, the
// Cox-de Boor recurrence, products of polynomials.
//
// Points are flat: point i, coordinate j at i * dimension + j. A weight of
// zero makes its control point a direction (homogeneous (D, 0)), as in
// proto/freeform/v1/geometry.proto.
#ifndef FREEFORM_TESTS_RELIABILITY_REFERENCE_H_
#define FREEFORM_TESTS_RELIABILITY_REFERENCE_H_

#include <vector>

#include "absl/types/span.h"

namespace freeform::reliability {

using Values = std::vector<double>;
using Coordinates = absl::Span<const double>;

double Binomial(int n, int k);

// Derivative `order` of the Bernstein polynomial B(n, i, t) (zero for i
// outside 0..n), by B' (n,i) = n (B(n-1,i-1) - B(n-1,i)).
double Bernstein(int n, int i, double t, int order = 0);

// BSplineSpan returns the index m of the non-empty knot span
// [u_m, u_{m+1}) that holds u, within the domain [u_p, u_{n+1}] of the
// n + 1 = knots.size() - p - 1 B-splines of degree p; at the end of the
// domain it is the last non-empty span (left-hand limits there).
int BSplineSpan(int p, Coordinates knots, double u);

// Derivative `order` of N_{i,p}(u) by the Cox-de Boor recurrence and its
// derivative formula (docs/references.md, 'Cox-de Boor recurrence'); u must
// lie in the domain.
double BSpline(int i, int p, Coordinates knots, double u, int order = 0);

// Derivative `order` of the Lagrange polynomial L_i of `nodes`, expanded
// into monomials.
double Lagrange(Coordinates nodes, int i, double t, int order = 0);

// Derivative `order` of the cubic Hermite function H_i (i = 0..3) on [0, 1]:
// H0 = 2t^3 - 3t^2 + 1, H1 = -2t^3 + 3t^2, H2 = t^3 - 2t^2 + t,
// H3 = t^3 - t^2.
double Hermite(int i, double t, int order = 0);

// The blending functions of a curve and their derivatives at one
// parameter: functions[k][i] is derivative k of function i.
using BasisDerivatives = std::vector<Values>;

BasisDerivatives BernsteinBasis(int n, double t, int orders);
BasisDerivatives BSplineBasis(int p, Coordinates knots, double u, int orders);
BasisDerivatives LagrangeBasis(Coordinates nodes, double t, int orders);

// Combine returns the curve's derivatives 0..orders at one parameter:
// sum_i f_i P_i, or with weights the rational curve by the quotient rule
// (NURBS Book, eq. 4.8 and A4.2). result[k] has `dimension` values.
std::vector<Values> Combine(int dimension, Coordinates points,
                            Coordinates weights,
                            const BasisDerivatives& functions);

// Derivatives 0..orders of the (rational) Bezier curve at t.
std::vector<Values> BezierCurveAt(int dimension, Coordinates points,
                                  Coordinates weights, double t,
                                  int orders = 0);

// Derivatives 0..orders of the B-spline (NURBS) curve at u.
std::vector<Values> BSplineCurveAt(int p, Coordinates knots, int dimension,
                                   Coordinates points, Coordinates weights,
                                   double u, int orders = 0);

// Derivatives 0..orders of the Lagrange curve through `points` at `nodes`.
std::vector<Values> LagrangeCurveAt(Coordinates nodes, int dimension,
                                    Coordinates points, double t,
                                    int orders = 0);

// Derivatives 0..orders of the piecewise cubic Hermite curve.
std::vector<Values> HermiteCurveAt(Coordinates nodes, int dimension,
                                   Coordinates points, Coordinates tangents,
                                   double t, int orders = 0);

// Partial (order_u, order_v) of the tensor-product surface whose u and v
// blending functions (with derivatives) are `f` and `g`, over a net of
// count_u x count_v points; rational surfaces only for (0, 0).
Values TensorAt(const BasisDerivatives& f, const BasisDerivatives& g,
                int dimension, Coordinates net, Coordinates weights,
                int order_u, int order_v);

// The (rational) triangular Bezier patch of degree n at barycentric
// (u, v, 1 - u - v), control points in the order of geometry.proto
// (i descending, then j descending).
Values TriangularAt(int n, int dimension, Coordinates points,
                    Coordinates weights, double u, double v);

// The triangular Bernstein polynomials of degree n at (u, v, 1 - u - v), in
// the same order.
Values TriangularBasis(int n, double u, double v);

// Small vector helpers.
double Distance(Coordinates a, Coordinates b);
double Norm(Coordinates a);
Values Cross(Coordinates a, Coordinates b);
double Dot(Coordinates a, Coordinates b);
// The largest absolute coordinate (the scale for relative tolerances).
double Scale(Coordinates values);
// DistanceToSegment is the distance from p to the segment [a, b].
double DistanceToSegment(Coordinates p, Coordinates a, Coordinates b);

}  // namespace freeform::reliability

#endif  // FREEFORM_TESTS_RELIABILITY_REFERENCE_H_
