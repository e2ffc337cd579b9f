// Bezier pieces of every curve and surface kind: the step that the geometric
// queries (closest points, intersections, sections) share.
//
// A query that relies on the convex hull property first cuts the geometry
// into (rational) Bezier pieces: a Bezier or power-form curve is one piece;
// a B-spline (NURBS) curve one piece per non-empty knot span
// (DecomposeBSplineCurve); a Hermite curve one cubic per segment
// (DecomposeHermiteCurve); a Lagrange curve one piece on [t_0, t_n]
// (LagrangeToBezier). A tensor Bezier surface (also the bicubic
// interpolating and Hermite patches, which are Bezier surfaces already) is
// one piece; a B-spline (NURBS) surface one piece per non-empty span
// rectangle, found by raising every knot value in the domain to
// multiplicity p (q) with InsertSurfaceKnots. A triangular patch of degree n
// becomes the degenerate tensor patch of degrees (n, n) of
// S(s, (1 - s) t) on [0, 1]^2 (docs/references.md, 'A triangular patch as a
// degenerate tensor patch'): with u = s, v = (1 - s) t, w = (1 - s)(1 - t),
// row i of the net is the row P(i, j, n - i - j), j = 0..n - i, of the
// triangle raised by i degrees (ElevateBezierCurve), and the edge s = 1
// collapses to the corner P(n, 0, 0).
//
// Thread-safe; allocates per call.
#ifndef FREEFORM_CORE_BEZIER_PIECES_H_
#define FREEFORM_CORE_BEZIER_PIECES_H_

#include <array>
#include <cstddef>
#include <vector>

#include "absl/status/statusor.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/curve.h"
#include "freeform/core/geometry_data.h"
#include "freeform/core/subdivision.h"
#include "freeform/core/surface.h"

namespace freeform {

// CurveBezierPieces returns the Bezier pieces of a valid curve: segments[k]
// is the curve on [breakpoints[k], breakpoints[k + 1]] reparameterized to
// [0, 1] (rational when the curve is). Fails only with the token's
// CANCELLED / DEADLINE_EXCEEDED.
absl::StatusOr<BezierDecomposition> CurveBezierPieces(
    const Curve& curve, const CancellationToken* cancel = nullptr);

// The Bezier pieces of a surface. patches[i * (breakpoints_v.size() - 1) +
// j] is a Bezier net (empty knot vectors) of the surface on
// [breakpoints_u[i], breakpoints_u[i + 1]] x [breakpoints_v[j],
// breakpoints_v[j + 1]], reparameterized to [0, 1]^2; for a triangular
// patch the single piece is its degenerate tensor form and the breakpoints
// are {0, 1} (SurfacePieceParameters maps its parameters).
struct SurfacePieces {
  std::vector<SurfaceData> patches;
  std::vector<double> breakpoints_u;
  std::vector<double> breakpoints_v;
  bool triangular = false;
  // The triangular patch's domain triangle (6 values), or empty.
  std::vector<double> domain_triangle;
};

// SurfaceBezierPieces returns the Bezier pieces of a valid surface. Fails
// only with the token's CANCELLED / DEADLINE_EXCEEDED.
absl::StatusOr<SurfacePieces> SurfaceBezierPieces(
    const Surface& surface, const CancellationToken* cancel = nullptr);

// SurfacePieceParameters returns the surface parameters, as EvaluateSurface
// takes them, of the point (s, t) in [0, 1]^2 of piece `index`: the affine
// image in the piece's span rectangle, or for a triangular patch the
// barycentric (u, v) = (s, (1 - s) t), or the point u A + v B + w C of its
// domain triangle.
std::array<double, 2> SurfacePieceParameters(const SurfacePieces& pieces,
                                             size_t index, double s, double t);

}  // namespace freeform

#endif  // FREEFORM_CORE_BEZIER_PIECES_H_
