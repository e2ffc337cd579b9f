// Segment insertion into a Delaunay TriangleMesh2d: the segment's walk from
// one end collects the triangles it crosses, which are removed, and the two
// pseudo-polygons left on either side are retriangulated by Anglada's
// recursion (the vertex whose circle with the segment is empty first;
// Anglada 1997, Shewchuk & Brown 2015, docs/references.md), so that the
// result is constrained Delaunay. A vertex all of whose triangles the
// segment crosses (without passing through it) is a spike of a chain
// (v, w, v): it is taken out, the polygon retriangulated without it, and
// then inserted again with the segments it carried. A segment through a
// vertex is split there. Internal to the core.
#ifndef FREEFORM_CORE_SRC_TRIANGULATION_CONSTRAINT_INSERTION_H_
#define FREEFORM_CORE_SRC_TRIANGULATION_CONSTRAINT_INSERTION_H_

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/status/statusor.h"
#include "triangulation/triangle_mesh_2d.h"

namespace freeform::internal {

// The working memory of segment insertion, kept between segments.
struct SegmentScratch {
  struct Link {
    int32_t triangle;
    int32_t segment;
  };
  struct Polygon {
    int32_t from;
    int32_t to;
    size_t chain_begin;
    size_t chain_end;
  };
  std::vector<int32_t> cavity;
  std::vector<int32_t> left_chain;
  std::vector<int32_t> right_chain;
  std::vector<std::array<int32_t, 3>> new_triangles;
  std::vector<Polygon> polygons;
  std::vector<uint8_t> in_cavity;
  // Per point: its position in the chain being cleaned of spikes, or -1.
  std::vector<int32_t> chain_position;
  // The vertices taken out of the cavity, and the segments {from, to,
  // index} on edges inside it, to put back.
  std::vector<int32_t> spike_vertices;
  std::vector<std::array<int32_t, 3>> inner_segments;
  // Directed edge -> the triangle outside the cavity across it.
  absl::flat_hash_map<uint64_t, Link> boundary;
  // Directed edge -> the new triangle that has it.
  absl::flat_hash_map<uint64_t, int32_t> new_edges;
};

// InsertSegment makes the vertices a and b (distinct, in the mesh) joined
// by a chain of edges carrying `segment`. Returns the number of triangles
// it replaced (the work done), or INVALID_ARGUMENT "segments[segment]
// crosses segments[j]" when it crosses or overlaps an edge carrying
// segment j.
absl::StatusOr<size_t> InsertSegment(TriangleMesh2d& mesh, int32_t a,
                                     int32_t b, int32_t segment,
                                     SegmentScratch& scratch);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_TRIANGULATION_CONSTRAINT_INSERTION_H_
