// Triangular Bezier patches: evaluation with partial derivatives, polynomial
// and rational, and the triangular Bernstein basis.
//
// A triangular Bezier patch of degree n over barycentric coordinates
// (u, v, w), u + v + w = 1, is
//   S(u,v,w) = sum_{i+j+k=n} n!/(i!j!k!) u^i v^j w^k P(i,j,k)
// (Farin, "Triangular Bernstein-Bezier patches", CAGD 3 (1986);
// docs/references.md, 'Triangular Bezier patches'). It interpolates
// P(n,0,0), P(0,n,0), P(0,0,n) at the corners, and each edge is the Bezier
// curve of the control points on it.
// The (n+1)(n+2)/2 control points are stored with i descending from n to 0,
// then j descending from n-i to 0 (k implied): for n = 2 the order is
// P200, P110, P101, P020, P011, P002 (TriangularIndex gives the position).
//
// With weights the patch is rational and is evaluated in homogeneous form
// (see rational.h; a zero weight makes the point a direction).
//
// Parameters are (u, v) pairs with w = 1 - u - v, or, when the patch has a
// domain triangle A, B, C, Cartesian points (x, y) of its plane converted to
// barycentric coordinates with respect to A, B, C. Partials are taken with
// respect to (u, v) with w = 1 - u - v (the directional derivatives along
// (1,0,-1) and (0,1,-1)) or, with a domain triangle, with respect to (x, y).
// Outputs follow surface_output.h.
//
// All functions are thread-safe; they allocate per call or per chunk of
// points, never per point.
#ifndef FREEFORM_CORE_TRIANGULAR_H_
#define FREEFORM_CORE_TRIANGULAR_H_

#include <cstddef>

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "freeform/core/points.h"
#include "freeform/core/surface_output.h"
#include "freeform/core/thread_pool.h"

namespace freeform {

// How far a parameter may stray outside the triangle (in barycentric
// coordinates) and still be accepted; such points are clamped onto it.
inline constexpr double kTriangleTolerance = 1e-12;

// A triangular Bezier patch whose data lives in caller memory.
struct TriangularPatchView {
  int degree = 0;
  // (n+1)(n+2)/2 points in the documented order.
  PointsView control_points;
  // Empty: polynomial. Otherwise one weight per control point.
  absl::Span<const double> weights;
  // Empty, or 6 values: the 2D vertices A, B, C (x, y each).
  absl::Span<const double> domain_triangle;

  bool rational() const { return !weights.empty(); }
};

// TriangularIndex returns the storage position of P(i, j, n-i-j):
// (n-i)(n-i+1)/2 + (n-i-j). Requires 0 <= i, 0 <= j, i + j <= n.
constexpr size_t TriangularIndex(int n, int i, int j) {
  const size_t rest = static_cast<size_t>(n - i);
  return rest * (rest + 1) / 2 + static_cast<size_t>(n - i - j);
}

// TriangularPointCount returns (n+1)(n+2)/2, the number of control points
// of a degree-n patch (0 for n < 0).
constexpr size_t TriangularPointCount(int n) {
  if (n < 0) return 0;
  const size_t m = static_cast<size_t>(n);
  return (m + 1) * (m + 2) / 2;
}

// ValidateTriangularPatch checks:
// - "degree": n >= 0;
// - "control_points...": ValidatePoints, and exactly (n+1)(n+2)/2 points
//   ("control_points.coordinates");
// - "weights": one per control point; "weights[i]": finite and >= 0, and the
//   three corner weights positive. With nonnegative weights the denominator
//   sum w_ijk B_ijk is positive at a point iff some weight whose basis
//   function is nonzero there is positive. At a corner only the corner's
//   function is nonzero, on an open edge exactly the edge's functions, inside
//   all of them; so positive corner weights are necessary and sufficient for
//   a positive denominator on the closed triangle (they also make every edge
//   carry a positive weight).
// - "domain_triangle": empty or 6 values, not degenerate (area <= 1e-14 *
//   longest edge^2); "domain_triangle[i]": finite.
absl::Status ValidateTriangularPatch(const TriangularPatchView& patch);

// EvaluateTriangularPatch writes every partial d^(k+l) S / da^k db^l with
// k + l <= MaxOrderOf(output) at each parameter pair of `uv` into `output`
// (see surface_output.h), where (a, b) is (u, v) with w = 1 - u - v, or
// (x, y) when the patch has a domain triangle. Partials of order above the
// degree of a polynomial patch are zero. Barycentric pairs must satisfy
// u, v >= -1e-12 and u + v <= 1 + 1e-12; Cartesian points must convert to
// barycentric coordinates >= -1e-12; tiny excursions are clamped onto the
// triangle. Fails with INVALID_ARGUMENT for an invalid patch, an odd number
// of values ("uv"), a point outside the triangle or not finite ("uv[2r]"
// for the pair, "uv[2r+1]" when only v is at fault) or wrongly sized
// output, and with CANCELLED / DEADLINE_EXCEEDED when the context's token
// stops the batch (the output is then partly written).
//
// Uses the triangular de Casteljau algorithm; the partials of order r are
// n!/(n-r)! times the r-fold directional differences of the level n-r
// points (Farin 1986, section 3).
absl::Status EvaluateTriangularPatch(const TriangularPatchView& patch,
                                     absl::Span<const double> uv,
                                     SurfaceOutput output,
                                     const ExecutionContext& context = {});

// EvaluateTriangularBasis writes the (n+1)(n+2)/2 triangular Bernstein
// polynomials B(i,j,k) = n!/(i!j!k!) u^i v^j w^k, w = 1 - u - v, at each
// (u, v) pair: values[r * count + f] for function f in storage order. Fails
// with INVALID_ARGUMENT for n < 0 ("degree"), pairs as for
// EvaluateTriangularPatch ("uv", "uv[i]") or a `values` of the wrong size
// ("values"), and with CANCELLED / DEADLINE_EXCEEDED from the token.
absl::Status EvaluateTriangularBasis(int n, absl::Span<const double> uv,
                                     absl::Span<double> values,
                                     const ExecutionContext& context = {});

}  // namespace freeform

#endif  // FREEFORM_CORE_TRIANGULAR_H_
