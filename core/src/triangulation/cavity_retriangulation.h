// The fast path of segment insertion: the triangles a segment crosses form
// a cavity, which is removed, and the two polygons left on either side of
// the segment are retriangulated by Anglada's recursion (the chain vertex
// whose circle through the segment's ends holds no other chain vertex
// makes a triangle, and the two sides recurse; Anglada 1997,
// docs/references.md): constrained Delaunay at once, in time about the
// cavity's size. It needs each side's chain to be simple; a chain that
// meets a vertex twice (the cavity pinched, or a vertex whose whole star
// the segment crosses) is left to the flips of constraint_insertion.h.
// Internal to the core.
#ifndef FREEFORM_CORE_SRC_TRIANGULATION_CAVITY_RETRIANGULATION_H_
#define FREEFORM_CORE_SRC_TRIANGULATION_CAVITY_RETRIANGULATION_H_

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/status/status.h"
#include "triangulation/triangle_mesh_2d.h"

namespace freeform::internal {

// A segment's cavity and the working memory of its retriangulation, kept
// between segments.
struct SegmentCavity {
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
  // The triangles the segment crosses, in order, and the vertices left and
  // right of it, from its start to its end.
  std::vector<int32_t> triangles;
  std::vector<int32_t> left_chain;
  std::vector<int32_t> right_chain;

  std::vector<std::array<int32_t, 3>> new_triangles;
  std::vector<Polygon> polygons;
  std::vector<uint8_t> marks;  // per triangle or per point, zero between uses
  absl::flat_hash_map<uint64_t, Link> boundary;
  absl::flat_hash_map<uint64_t, int32_t> new_edges;
};

// HasSimpleChains returns whether no vertex repeats in either chain.
bool HasSimpleChains(const TriangleMesh2d& mesh, SegmentCavity& cavity);

// RetriangulateCavity replaces the cavity of the segment piece from `from`
// to `to` (simple chains) by the constrained Delaunay triangulation of its
// two polygons, with the edge from `from` to `to` carrying `segment`.
absl::Status RetriangulateCavity(TriangleMesh2d& mesh, int32_t from, int32_t to,
                                 int32_t segment, SegmentCavity& cavity);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_TRIANGULATION_CAVITY_RETRIANGULATION_H_
