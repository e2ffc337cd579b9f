// Meshing one trimmed face (trimmed_surface.h) within a guaranteed 3D
// tolerance: a constrained Delaunay triangulation (constrained_delaunay.h)
// of the trims' samples and an interior grid in (u, v), refined until an
// a-priori bound of every triangle's distance to the surface meets the
// tolerance.
//
//   ASSIGN_OR_RETURN(FaceMesh mesh,
//                    TessellateFace(face, {.tolerance = 1e-3}, cancel));
//
// The bound (docs/references.md, 'Meshing a trimmed face within a
// tolerance'): with M_uu, M_uv, M_vv bounds of the second partials of the
// surface over the span rectangles that a triangle's (u, v) box meets (from
// the control points of the derivative nets, meshing/piece_bounds.h), and
// A = M_uu + M_uv, B = M_vv + M_uv (2 |d_u d_v| <= d_u^2 + d_v^2), the
// linear interpolation L of the vertex positions differs from S at x by at
// most 1/2 sum_i lambda_i(x) Q(x_i - x) with Q(d) = A d_u^2 + B d_v^2
// (Taylor at x with the remainder along each segment to a vertex), which is
// at most R^2 / 2, R the radius of the smallest circle enclosing the
// triangle after u is scaled by sqrt(A) and v by sqrt(B). For a rational
// surface the bounds are those of the homogeneous form (w (P - c), w) in
// one frame for the whole net (its centre c, radius R_c and least weight
// w_min), summed over the span rectangles the box meets: every point of a
// triangle is then within the bound of the surface over the triangle and
// every such surface point within it of the triangle (mesh.h's
// (e_s + R e_w) / w_min). A and B are raised to at least 1/100 of the
// larger of them, which only loosens the bound, so that triangles stay
// within an aspect ratio of about 10 where the surface is flat in one
// direction (a cylinder along its axis).
//
// The bound needs the homogeneous surface to be C^1 inside the triangle:
// across a knot line of multiplicity at least the degree (a C^0 line, as at
// the double knots of the 9-point NURBS circle) a triangle has no bound, so
// boundary chords are split where their curve crosses such a line (by
// bisection, the point put on the line) and a triangle across one gets its
// edges' crossings as Steiner points: every triangle lies in a closed span
// strip on either side. A box inside one span rectangle uses the
// rectangle's own frame (the planner's bound).
//
// Thread-safe: TessellateFace allocates per call and only reads the face.
#ifndef FREEFORM_CORE_FACE_MESH_H_
#define FREEFORM_CORE_FACE_MESH_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/trimmed_surface.h"

namespace freeform {

struct FaceMeshOptions {
  // The largest distance between the mesh and the face's surface (3D,
  // absolute, positive and finite).
  double tolerance = 0.0;
  // More vertices than this are refused (RESOURCE_EXHAUSTED).
  size_t max_vertices = size_t{1} << 24;
};

// A triangle mesh of one face.
struct FaceMesh {
  // x, y, z per vertex, each S(u, v) of its uv.
  std::vector<double> vertices;
  // Unit normals, reversed with the face.
  std::vector<double> normals;
  // (u, v) per vertex.
  std::vector<double> uv;
  // 3 per triangle, counter-clockwise seen from the face's normal side.
  std::vector<uint32_t> triangles;
  // The smallest angle of a triangle in 3D, in degrees.
  double min_angle_degrees = 0.0;
  // The largest per-triangle a-priori bound (at most the tolerance).
  double deviation_bound = 0.0;
};

// TessellateFace meshes `face`:
//   1. each trim curve (the parameter rectangle's sides without an outer
//      loop) sampled by SampleTrimCurve at tolerance / 2, each chord then
//      halved at the curve's parameter midpoint until its own bound
//      (A e_u^2 + B e_v^2) / 8 is at most tolerance / 2; one vertex at each
//      junction of curves, zero-length chords skipped;
//   2. a uniform grid per span rectangle whose cells meet the planner's
//      bound (NeededCells), the nodes kept where ClassifyPoints says inside
//      with a boundary tolerance of 0.3 grid spacings (no slivers);
//   3. the constrained Delaunay triangulation of both, the chords as
//      segments, Region::kInsideSegments (the face with its holes);
//   4. every triangle whose bound exceeds the tolerance gets a Steiner
//      point (its circumcentre in the scaled metric when that lies inside
//      it, else its centroid, else a point halfway to a vertex, the first
//      inside the face), round after round, until every triangle meets it.
// Vertices are S(u, v) with unit normals (EvaluateSurface), oriented by
// face.reversed() (the winding too).
//
// Fails with INVALID_ARGUMENT naming "tolerance" (not positive and finite,
// a trim that cannot be sampled to it, or a triangle over the bound with
// no Steiner point inside the face) or "surface" (not 3D, a weight not
// positive, or second partials without a finite bound),
// RESOURCE_EXHAUSTED naming
// "max_vertices" when the boundary and the grid (counted before any work)
// or the refinement (checked before each round) need more vertices, and
// with the token's CANCELLED / DEADLINE_EXCEEDED (polled per piece and per
// round).
absl::StatusOr<FaceMesh> TessellateFace(
    const TrimmedSurface& face, const FaceMeshOptions& options,
    const CancellationToken* cancel = nullptr);

}  // namespace freeform

#endif  // FREEFORM_CORE_FACE_MESH_H_
