// Tessellation: polylines for curves and triangle meshes for Bezier patches,
// within a given distance of the exact geometry.
//
// Curves are refined by recursive subdivision with a flatness test
// ("subdivide until flat, then draw the chord"; docs/references.md,
// 'Flatness test for curve tessellation'):
// a Bezier piece is split at its parameter midpoint by de Casteljau until
// every control point lies within `tolerance` of the chord from the first to
// the last one. By the convex hull property the piece then lies within
// `tolerance` of its chord, and because the piece runs continuously from one
// chord end to the other, every chord point is within `tolerance` of the
// piece too: the polyline and the curve are within Hausdorff distance
// `tolerance` (up to rounding, about 1e-15 of the control points' scale).
// A rational piece is subdivided in homogeneous form and tested on its
// projected control points once all its weights are positive; with
// nonnegative weights and positive end weights one split makes every weight
// of both halves positive, and a rational curve with positive weights lies
// in the convex hull of its projected control points, so the same bound
// holds exactly (no sampling). B-spline spans are converted to Bezier form
// by blossoming (The NURBS Book, section 5.1; de Boor's algorithm with one
// argument per level), so unclamped knot vectors work too. Flatness
// converges quadratically: a polyline needs O(1/sqrt(tolerance)) points.
//
// Patches are meshed over a uniform interior grid surrounded by a ring that
// conforms to boundary samples. The grid spacing h_u = 1/n_u, h_v = 1/n_v
// comes from the second-difference bounds of the control net (Filip,
// Magedson and Markot, "Surface algorithms using bounds on derivatives",
// CAGD 3, 1986): |S_uu| <= M_uu = p (p - 1) max |D2_u P|, |S_vv| <= M_vv =
// q (q - 1) max |D2_v P|, |S_uv| <= M_uv = p q max |D_u D_v P|. Linear
// interpolation over a parameter triangle whose u and v extents are at most
// e_u and e_v is within (e_u^2 M_uu + 2 e_u e_v M_uv + e_v^2 M_vv) / 8 of the
// surface (Taylor's theorem at the point, with sum_i l_i (u_i - u)^2 <=
// e_u^2 / 4 for barycentric weights l_i). Every triangle here has extents at
// most h_u and h_v (grid cells, and ring triangles zipped between the grid
// and boundary samples at most h apart), and n_u = ceil(sqrt((M_uu + M_uv) /
// (4 tolerance))) (likewise n_v) makes that at most `tolerance`, using
// 2 e_u e_v <= e_u^2 + e_v^2. Each patch side is a boundary curve sampled
// uniformly; sides with identical control points (in either direction) are
// found by exact comparison and share one sampling whose segment count is the
// largest any of their patches needs, quantized as k / n from both sides, so
// their vertices are the same vertices and the mesh is watertight. A side
// whose control points all coincide (the lid apex of the Utah teapot) is one
// vertex. Finally vertices within 1e-12 of the control points' scale are
// welded and triangles that became degenerate are dropped.
//
// All functions are thread-safe and allocate per call.
#ifndef FREEFORM_CORE_TESSELLATION_H_
#define FREEFORM_CORE_TESSELLATION_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/bezier.h"
#include "freeform/core/bspline.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/tensor_surface.h"

namespace freeform {

// A polyline: points on a curve, in parameter order, with their parameters.
struct Polyline {
  int dimension = 0;
  // point r, coordinate j at points[r * dimension + j].
  std::vector<double> points;
  std::vector<double> parameters;
};

// TessellateBezierCurve returns a polyline within Hausdorff distance
// `tolerance` of `curve` (see the file comment), with points evaluated on
// the curve at dyadic parameters, starting at 0 and ending at 1. Fails with
// INVALID_ARGUMENT for an invalid curve (ValidateBezierCurve) or a tolerance
// that is not positive and finite ("tolerance"), RESOURCE_EXHAUSTED naming
// "tolerance" when more than `max_points` points would be needed, and with
// the token's
// CANCELLED / DEADLINE_EXCEEDED (checked every few hundred pieces).
// A tolerance below 2^-48 (3.6e-15) of the largest control-point
// coordinate cannot be met in double precision: for curves of degree 2 or
// more it is refused at once (INVALID_ARGUMENT naming "tolerance").
absl::StatusOr<Polyline> TessellateBezierCurve(
    const BezierCurveView& curve, double tolerance, size_t max_points,
    const CancellationToken* cancel = nullptr);

// TessellateBSplineCurve is TessellateBezierCurve for a B-spline or NURBS
// curve over its domain [u_p, u_{n+1}]: every non-empty knot span is refined
// separately and the knots are polyline points. Fails as
// TessellateBezierCurve, with ValidateBSplineCurve's errors. (A valid
// curve of degree 0 has a single span: its polyline is the constant point
// at both ends of the domain.)
absl::StatusOr<Polyline> TessellateBSplineCurve(
    const BSplineCurveView& curve, double tolerance, size_t max_points,
    const CancellationToken* cancel = nullptr);

// Bounds on the size of a polyline before it is made, so a server knows
// the size of an answer before the work starts. For a polynomial Bezier
// piece of degree n whose second differences are at most D long, every
// control point of a piece halved d times lies within n^2 D 4^-d / 8 of its
// chord (the control polygon minus the chord's even spacing has second
// differences at most 4^-d D and vanishes at both ends, and a discrete
// Green's function bounds it by i (n - i) / 2 times that). The flatness
// test therefore passes at the first depth where this is at most half the
// tolerance (half, so rounding cannot push one level deeper), and the
// polyline has at most 2^depth segments per piece. A B-spline span of width
// w is bounded through the control points Q of the curve's second
// derivative (The NURBS Book, eq. 3.8): its Bezier form has second
// differences at most w^2 max |Q_i| / (p (p - 1)) over the p - 1 points
// active on the span. A rational piece is subdivided in homogeneous form
// (w P, w) and tested projected. About a centre c, its homogeneous points
// (w_i (P_i - c), w_i) deviate from their evenly spaced chord by e_s in
// the spatial part and e_w in the weight, each bounded as above from the
// spatial and the weight second differences D_s and D_w. The chord
// projects onto the piece's Euclidean chord, so a projected control point
// lies within (e_s + R e_w) / w_min of it, where R bounds |P_i - c| and
// w_min the weights (the hull property: both hold for every subpiece):
// the polynomial bound with D = (D_s + R D_w) / w_min. A B-spline span uses
// its p + 1 active control points for R and w_min. A rational curve with a
// weight of 0 has no bound: these return SIZE_MAX, as they do when the
// bound does not fit a size_t.

// BezierCurvePointBound returns at least the number of points
// TessellateBezierCurve(curve, tolerance, ...) returns. `curve` must be
// valid and `tolerance` positive.
size_t BezierCurvePointBound(const BezierCurveView& curve, double tolerance);

// BSplineCurvePointBound is BezierCurvePointBound for
// TessellateBSplineCurve.
size_t BSplineCurvePointBound(const BSplineCurveView& curve, double tolerance);

// A triangle mesh of Bezier patches.
struct Mesh {
  // Vertex r at vertices[3 r .. 3 r + 2], its unit normal at normals[3 r..].
  std::vector<double> vertices;
  std::vector<double> normals;
  // Triangle t is vertices triangles[3 t .. 3 t + 2], counter-clockwise
  // about S_u x S_v of its patch.
  std::vector<uint32_t> triangles;
  // The patch and (u, v) = uv[2 r], uv[2 r + 1] where vertex r was evaluated
  // (the first patch that produced it; a vertex shared by patches lies on
  // all of them).
  std::vector<uint32_t> patch;
  std::vector<double> uv;
  // Per triangle: its patch, and its three corners' (u, v) in that patch
  // (6 values per triangle), so attributes can be interpolated per patch.
  std::vector<uint32_t> triangle_patch;
  std::vector<double> corner_uv;
};

// TessellateBezierPatches returns a watertight mesh within `tolerance` of
// the 3D polynomial Bezier patches (any degrees; see the file comment).
// Normals are ComputeUnitNormals of the owning patch (limits from inside
// the patch at collapsed sides). Fails with INVALID_ARGUMENT naming
// "surfaces[i].bezier.<field>" for an invalid patch, a dimension other than
// 3 ("surfaces[i].bezier.control_net.dimension") or weights (rational
// patches are not supported: "surfaces[i].bezier.weights"), "tolerance" as
// for curves (also below the resolution of a patch's coordinates),
// RESOURCE_EXHAUSTED naming "tolerance" when more than `max_vertices` vertices
// would be generated (counted before welding, which only merges vertices
// that coincide without sharing control points), and with the token's
// CANCELLED / DEADLINE_EXCEEDED (checked between patches).
absl::StatusOr<Mesh> TessellateBezierPatches(
    absl::Span<const BezierSurfaceView> patches, double tolerance,
    size_t max_vertices, const CancellationToken* cancel = nullptr);

// The size of a mesh, known before it is made.
struct MeshSize {
  size_t vertices = 0;
  size_t triangles = 0;
};

// BezierPatchesMeshBound returns at least the number of vertices and of
// triangles TessellateBezierPatches(patches, tolerance, max_vertices)
// makes: the mesh is planned before any vertex is made. Fails as
// TessellateBezierPatches does for invalid patches or tolerance, or a mesh
// over max_vertices. Costs one pass over the control nets.
absl::StatusOr<MeshSize> BezierPatchesMeshBound(
    absl::Span<const BezierSurfaceView> patches, double tolerance,
    size_t max_vertices);

}  // namespace freeform

#endif  // FREEFORM_CORE_TESSELLATION_H_
