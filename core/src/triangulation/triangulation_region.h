// The triangles of a region of a TriangleMesh2d, and the mesh as a
// PlanarTriangulation: the convex hull, or the triangles inside the
// segments by the even-odd rule (a flood from the hull, one depth deeper
// across each edge that carries a segment). Internal to the core.
#ifndef FREEFORM_CORE_SRC_TRIANGULATION_TRIANGULATION_REGION_H_
#define FREEFORM_CORE_SRC_TRIANGULATION_TRIANGULATION_REGION_H_

#include <cstdint>
#include <vector>

#include "freeform/core/constrained_delaunay.h"
#include "triangulation/triangle_mesh_2d.h"

namespace freeform::internal {

// SegmentDepths returns, per triangle, how many segment-carrying edges a
// path from outside the hull must cross at least to reach it (-1 for the
// ghosts).
std::vector<int32_t> SegmentDepths(const TriangleMesh2d& mesh);

// ExtractTriangulation returns the real triangles of `region`, the points,
// the representatives and the edges carrying segments.
PlanarTriangulation ExtractTriangulation(
    const TriangleMesh2d& mesh, ConstrainedTriangulationOptions::Region region);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_TRIANGULATION_TRIANGULATION_REGION_H_
