// Meshing: watertight triangle meshes of surfaces of every kind, within a
// given distance of the exact surfaces (docs/references.md, 'Meshing
// surfaces within a tolerance').
//
// Every surface is cut into (rational) Bezier pieces, one per non-empty span
// rectangle: a tensor Bezier surface (also the bicubic interpolating and
// Hermite patches) is one piece, a B-spline or NURBS surface one per span
// rectangle, and a triangular patch of degree n the degenerate tensor piece
// of degrees (n, n) of DecomposeSurface, whose side s = 1 collapses to a
// corner. Each piece is meshed over a uniform interior grid surrounded by a
// ring that conforms to the samples of its four sides. The grid spacing
// comes from bounds on the second partials of the piece (Filip, Magedson and
// Markot, "Surface algorithms using bounds on derivatives", CAGD 3, 1986),
// taken from the control points of the surface's derivative nets active on
// the span rectangle, so the mesh is planned from the input alone: linear
// interpolation over a parameter triangle whose u and v extents are at most
// e_u and e_v is within (e_u^2 M_uu + 2 e_u e_v M_uv + e_v^2 M_vv) / 8 of
// the surface. A rational piece is bounded in homogeneous form (w (P - c),
// w) about the centre c of its active control points: with e_s and e_w the
// interpolation errors of the spatial and the weight part, every point of
// the piece is within (e_s + R e_w) / w_min of the mesh and every mesh
// point within that of the piece (R bounds |P - c|, w_min the weights, which
// must be positive). An optional longest edge adds cells from bounds on the
// first partials.
//
// An optional normal-angle limit is met by checking the plan, not by a
// bound: after the counts above are chosen, PlanMesh cuts the surfaces into
// their pieces (kept in the plan for TessellatePlanned), evaluates the unit
// normals at the two ends of every edge the mesh will have (the planner
// enumerates grid, side and ring edges with the builder's own code) and
// raises the grid of a piece, or the segments of a side, where an edge's
// normals differ by more than the limit, checking again until none does.
// Guaranteed, to rounding: for every triangle, the unit normals of its
// surface at its three corners (Mesh::corner_uv; at a point where S_u x S_v
// vanishes, the limit from inside the triangle's piece) are pairwise within
// the limit. These are the vertex normals (Mesh::normals) except at a vertex
// whose surfaces disagree on the normal, which carries the normal of the
// piece that made it: where surfaces meet at an angle (a crease, or a
// corner point they touch at, as the Utah teapot's handle touches its
// body; also pieces at a knot of multiplicity p, where a B-spline surface
// may be only C0) and on a collapsed side whose limit normal varies along
// it (a cone's apex; a sphere's pole has one normal). Points where the
// surface has no normal at all (a zero normal) are exempt. Refinement ends
// where the normals, limits included, are continuous on every closed piece;
// where they are not (a degenerate corner whose limit depends on the
// direction of approach) the plan reaches the vertex cap. Grids stay
// uniform per piece, so a piece whose normal turns fast in a small part (the
// lip of the teapot's spout) is refined all over.
//
// Sides shared by pieces are sampled once, with the largest segment count
// any of their pieces needs, so the mesh has no T-junctions: neighbouring
// span rectangles of a B-spline surface share their knot lines, and the
// boundary sides of different surfaces (or of one closed surface, such as a
// torus whose first and last control rows coincide) are shared when their
// Bezier control points are equal, in either direction (exact comparison of
// the boundary curves' pieces; boundaries of unclamped knot vectors are not
// compared). A side whose control points all coincide (a sphere's pole, the
// apex of a triangular patch, the Utah teapot's lid) is one vertex.
// Finally vertices within 1e-12 of the control points' scale are welded and
// triangles that became degenerate are dropped.
//
// All functions are thread-safe and allocate per call.
#ifndef FREEFORM_CORE_MESH_H_
#define FREEFORM_CORE_MESH_H_

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/surface.h"

namespace freeform {

// A triangle mesh of surfaces.
struct Mesh {
  // Vertex r at vertices[3 r .. 3 r + 2], its unit normal at normals[3 r..].
  std::vector<double> vertices;
  std::vector<double> normals;
  // Triangle t is vertices triangles[3 t .. 3 t + 2], counter-clockwise
  // about S_u x S_v of its surface.
  std::vector<uint32_t> triangles;
  // The surface and its parameters (u, v) = uv[2 r], uv[2 r + 1] (as
  // EvaluateSurface takes them) where vertex r was evaluated (the first
  // surface that produced it; a vertex shared by surfaces lies on all of
  // them).
  std::vector<uint32_t> patch;
  std::vector<double> uv;
  // Per triangle: its surface, and its three corners' (u, v) in that surface
  // (6 values per triangle), so attributes can be interpolated per surface.
  std::vector<uint32_t> triangle_patch;
  std::vector<double> corner_uv;
};

// The size of a mesh, known before it is made.
struct MeshSize {
  size_t vertices = 0;
  size_t triangles = 0;
};

// What a mesh must satisfy.
struct MeshOptions {
  // Largest distance between the mesh and the surfaces (> 0).
  double tolerance = 0.0;
  // Longest triangle edge, 0 for no limit (else > 0).
  double max_edge_length = 0.0;
  // Largest angle in radians between the unit normals at the two ends of a
  // triangle edge (see above), 0 for no limit (else in (0, pi)).
  double max_normal_angle = 0.0;
  // More vertices than this are refused (RESOURCE_EXHAUSTED).
  size_t max_vertices = 0;
};

class MeshPlan;

// PlanMesh checks `surfaces` and `options` and chooses every piece's grid
// and every side's sampling, so the size of the mesh is known before any
// vertex is made; costs one pass over the control nets, and with a
// normal-angle limit the Bezier pieces of the surfaces (held by the plan)
// and the normals at a small multiple of the planned vertices. The surfaces
// must outlive the plan. Fails with INVALID_ARGUMENT naming
// "surfaces[i].<kind>.<field>" for a surface that is not 3D
// ("...control_net.dimension" or "...control_points.dimension") or has a
// weight that is not positive ("...weights[k]"), "tolerance" or
// "max_edge_length" (not positive and finite; a tolerance below 2^-48 of a
// surface's largest coordinate cannot be met in double precision) or
// "max_normal_angle" (not in (0, pi)), RESOURCE_EXHAUSTED when more than
// options.max_vertices vertices would be needed, naming "max_normal_angle"
// when the normal-angle refinement needs them and "tolerance" otherwise,
// and with the token's CANCELLED / DEADLINE_EXCEEDED.
absl::StatusOr<std::shared_ptr<const MeshPlan>> PlanMesh(
    absl::Span<const Surface> surfaces, const MeshOptions& options,
    const CancellationToken* cancel = nullptr);

// PlannedMeshSize returns at least the number of vertices and of triangles
// TessellatePlanned(plan) makes.
MeshSize PlannedMeshSize(const MeshPlan& plan);

// PlannedPieceValues returns an upper bound of the doubles of the Bezier
// pieces TessellatePlanned holds while it works (SurfacePieceValues of every
// surface): its working memory beside the mesh. With a normal-angle limit
// the plan holds them from PlanMesh on.
uint64_t PlannedPieceValues(const MeshPlan& plan);

// Whether TessellatePlanned makes Mesh::triangle_patch and
// Mesh::corner_uv (52 bytes per triangle, about half of its memory).
enum class CornerAttributes { kMake, kSkip };

// TessellatePlanned makes the planned mesh: within the tolerance of the
// surfaces, every edge used by at most two triangles, consistently
// oriented, without T-junctions. Normals are the unit normals of the
// owning surface (limits from inside at collapsed sides). With kSkip the
// mesh's triangle_patch and corner_uv stay empty. Fails only with the
// token's CANCELLED / DEADLINE_EXCEEDED.
absl::StatusOr<Mesh> TessellatePlanned(
    const MeshPlan& plan, const CancellationToken* cancel = nullptr,
    CornerAttributes corner_attributes = CornerAttributes::kMake);

// The memory of a planned mesh (upper bounds, in bytes), known before it
// is made: every array TessellatePlanned keeps is sized from the plan up
// front, so these are sums of known sizes. The surfaces are not counted.
struct MeshMemory {
  // The plan's own: its pieces and sides, and with a normal-angle limit the
  // surfaces' Bezier pieces.
  uint64_t plan = 0;
  // What TessellatePlanned allocates at its peak, the mesh it returns
  // included.
  uint64_t tessellation = 0;
  // The mesh it returns.
  uint64_t mesh = 0;
};

// PlannedMeshMemory returns the memory of `plan` and of
// TessellatePlanned(plan, ..., corner_attributes).
MeshMemory PlannedMeshMemory(const MeshPlan& plan,
                             CornerAttributes corner_attributes);

// TessellateSurfaces is PlanMesh followed by TessellatePlanned.
absl::StatusOr<Mesh> TessellateSurfaces(
    absl::Span<const Surface> surfaces, const MeshOptions& options,
    const CancellationToken* cancel = nullptr);

}  // namespace freeform

#endif  // FREEFORM_CORE_MESH_H_
