// Incremental Delaunay insertion into a TriangleMesh2d: point location by a
// stochastic visibility walk from the last triangle (which terminates in
// any triangulation, Devillers, Pion & Teillaud 2002), then Lawson's
// flips, which never flip an edge carrying a segment, so that a
// constrained Delaunay triangulation stays constrained Delaunay
// (docs/references.md). A point on an edge splits it (a segment's edge
// into two edges carrying the same segment); an exact duplicate of a
// vertex is merged into it. Internal to the core.
#ifndef FREEFORM_CORE_SRC_TRIANGULATION_DELAUNAY_INSERTION_H_
#define FREEFORM_CORE_SRC_TRIANGULATION_DELAUNAY_INSERTION_H_

#include <cstdint>

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "freeform/core/cancellation.h"
#include "triangulation/triangle_mesh_2d.h"

namespace freeform::internal {

struct PointLocation {
  enum class Kind {
    kInside,   // strictly inside the real triangle
    kOnEdge,   // on the open edge opposite `corner` of the real triangle
    kVertex,   // equal to the vertex at `corner`
    kOutside,  // strictly outside the hull, in the ghost triangle
  };
  Kind kind = Kind::kInside;
  int32_t triangle = kNoTriangle;
  int corner = 0;
};

// Locate finds `point` in a mesh with at least one real triangle, walking
// from `start`; `random_state` drives the walk's choices.
PointLocation Locate(const TriangleMesh2d& mesh, Point2 point, int32_t start,
                     uint64_t& random_state);

// InsertLocatedVertex inserts mesh.points[vertex] (not yet a vertex, not a
// duplicate: `location` is not kVertex) found at `location`, and restores
// the (constrained) Delaunay property.
void InsertLocatedVertex(TriangleMesh2d& mesh, int32_t vertex,
                         const PointLocation& location);

// InsertVertex inserts mesh.points[vertex] (not yet a vertex) and restores
// the (constrained) Delaunay property. Returns the vertex it is now: itself,
// or the vertex it duplicates.
int32_t InsertVertex(TriangleMesh2d& mesh, int32_t vertex);

// BuildDelaunay makes `mesh` (points and representative set, no
// triangles) the Delaunay triangulation of its points, setting the
// representative of duplicates. Fails with INVALID_ARGUMENT when all points
// are collinear or fewer than 3 are distinct, or with the token's status.
absl::Status BuildDelaunay(TriangleMesh2d& mesh,
                           const CancellationToken* cancel);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_TRIANGULATION_DELAUNAY_INSERTION_H_
