// Segment insertion into a (constrained) Delaunay TriangleMesh2d. A walk
// from one end finds the triangles the segment crosses, up to the first
// vertex on it (a segment through a vertex is split there). When the
// vertices beside them form simple chains, the cavity is retriangulated
// (cavity_retriangulation.h); otherwise (Sloan 1993, docs/references.md)
// the crossed edges are flipped while their quadrilateral is strictly
// convex (an edge whose quadrilateral is not waits for its neighbours)
// until none crosses, so the segment is an edge; then Lawson's flips of
// every edge that is not locally Delaunay and carries no segment, from the
// new edges outwards, make the mesh constrained Delaunay again. A segment
// through a vertex is split there. Internal to the core.
#ifndef FREEFORM_CORE_SRC_TRIANGULATION_CONSTRAINT_INSERTION_H_
#define FREEFORM_CORE_SRC_TRIANGULATION_CONSTRAINT_INSERTION_H_

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "absl/status/statusor.h"
#include "triangulation/cavity_retriangulation.h"
#include "triangulation/triangle_mesh_2d.h"

namespace freeform::internal {

// The working memory of segment insertion, kept between segments.
struct SegmentScratch {
  // The edges still crossing the segment piece, as vertex pairs.
  std::deque<std::array<int32_t, 2>> crossing;
  // The edges to check for the Delaunay property.
  std::vector<std::array<int32_t, 2>> to_check;
  SegmentCavity cavity;
};

// InsertSegment makes the vertices a and b (distinct, in the mesh) joined
// by a chain of edges carrying `segment`. Returns the number of flips and
// pieces it took (the work done), or INVALID_ARGUMENT "segments[segment]:
// crosses or overlaps segments[j]" when it crosses or overlaps an edge
// carrying segment j.
absl::StatusOr<size_t> InsertSegment(TriangleMesh2d& mesh, int32_t a, int32_t b,
                                     int32_t segment, SegmentScratch& scratch);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_TRIANGULATION_CONSTRAINT_INSERTION_H_
