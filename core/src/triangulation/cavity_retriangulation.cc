#include "triangulation/cavity_retriangulation.h"

#include <algorithm>

#include "triangulation/predicates.h"

namespace freeform::internal {
namespace {

uint64_t EdgeKey(int32_t from, int32_t to) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(from)) << 32) |
         static_cast<uint32_t>(to);
}

// Whether `chain` meets a vertex twice (marks per point, left zero).
bool RepeatsAVertex(const std::vector<int32_t>& chain,
                    std::vector<uint8_t>& marks) {
  bool repeats = false;
  for (const int32_t vertex : chain) {
    repeats = repeats || marks[vertex] != 0;
    marks[vertex] = 1;
  }
  for (const int32_t vertex : chain) marks[vertex] = 0;
  return repeats;
}

// TriangulatePseudoPolygon appends the constrained Delaunay triangulation of
// the polygon `from`, `chain`..., `to` (the chain left of from -> to) to
// cavity.new_triangles.
void TriangulatePseudoPolygon(const TriangleMesh2d& mesh, int32_t from,
                              int32_t to, const std::vector<int32_t>& chain,
                              SegmentCavity& cavity) {
  cavity.polygons.assign({{from, to, 0, chain.size()}});
  while (!cavity.polygons.empty()) {
    const SegmentCavity::Polygon polygon = cavity.polygons.back();
    cavity.polygons.pop_back();
    if (polygon.chain_begin == polygon.chain_end) continue;
    const Point2 a = mesh.points[polygon.from];
    const Point2 b = mesh.points[polygon.to];
    size_t apex = polygon.chain_begin;
    for (size_t i = apex + 1; i < polygon.chain_end; ++i) {
      if (InCircle(a, b, mesh.points[chain[apex]], mesh.points[chain[i]]) >
          0.0) {
        apex = i;
      }
    }
    cavity.new_triangles.push_back({polygon.from, polygon.to, chain[apex]});
    cavity.polygons.push_back(
        {polygon.from, chain[apex], polygon.chain_begin, apex});
    cavity.polygons.push_back(
        {chain[apex], polygon.to, apex + 1, polygon.chain_end});
  }
}

// RecordCavityBoundary keys each edge of the cavity's outline by its
// direction in the cavity, with the triangle outside across it.
void RecordCavityBoundary(const TriangleMesh2d& mesh, SegmentCavity& cavity) {
  cavity.marks.resize(std::max(mesh.triangles.size(), mesh.points.size()), 0);
  for (const int32_t triangle : cavity.triangles) cavity.marks[triangle] = 1;
  cavity.boundary.clear();
  for (const int32_t triangle : cavity.triangles) {
    const MeshTriangle& t = mesh.triangles[triangle];
    for (int corner = 0; corner < 3; ++corner) {
      if (cavity.marks[t.neighbors[corner]] != 0) continue;
      const std::array<int32_t, 2> edge = mesh.Edge(triangle, corner);
      cavity.boundary[EdgeKey(edge[0], edge[1])] = {t.neighbors[corner],
                                                    t.segments[corner]};
    }
  }
  for (const int32_t triangle : cavity.triangles) cavity.marks[triangle] = 0;
}

// ReplaceCavity writes cavity.new_triangles into the cavity's slots and
// links them to each other and to the outline.
absl::Status ReplaceCavity(TriangleMesh2d& mesh, int32_t from, int32_t to,
                           int32_t segment, SegmentCavity& cavity) {
  cavity.new_edges.clear();
  for (size_t i = 0; i < cavity.triangles.size(); ++i) {
    const int32_t triangle = cavity.triangles[i];
    mesh.SetTriangle(triangle, cavity.new_triangles[i]);
    for (int corner = 0; corner < 3; ++corner) {
      const std::array<int32_t, 2> edge = mesh.Edge(triangle, corner);
      cavity.new_edges[EdgeKey(edge[0], edge[1])] = triangle;
    }
  }
  for (const int32_t triangle : cavity.triangles) {
    for (int corner = 0; corner < 3; ++corner) {
      const std::array<int32_t, 2> edge = mesh.Edge(triangle, corner);
      const auto inside = cavity.new_edges.find(EdgeKey(edge[1], edge[0]));
      if (inside != cavity.new_edges.end()) {
        const bool is_segment = (edge[0] == from && edge[1] == to) ||
                                (edge[0] == to && edge[1] == from);
        mesh.LinkAcross(triangle, corner, inside->second,
                        is_segment ? segment : kNoSegment);
        continue;
      }
      const auto outside = cavity.boundary.find(EdgeKey(edge[0], edge[1]));
      if (outside == cavity.boundary.end()) {
        return absl::InternalError(
            "segment insertion: the retriangulation does not fit the cavity");
      }
      mesh.LinkAcross(triangle, corner, outside->second.triangle,
                      outside->second.segment);
    }
  }
  return absl::OkStatus();
}

}  // namespace

bool HasSimpleChains(const TriangleMesh2d& mesh, SegmentCavity& cavity) {
  cavity.marks.resize(std::max(mesh.triangles.size(), mesh.points.size()), 0);
  return !RepeatsAVertex(cavity.left_chain, cavity.marks) &&
         !RepeatsAVertex(cavity.right_chain, cavity.marks);
}

absl::Status RetriangulateCavity(TriangleMesh2d& mesh, int32_t from, int32_t to,
                                 int32_t segment, SegmentCavity& cavity) {
  RecordCavityBoundary(mesh, cavity);
  cavity.new_triangles.clear();
  TriangulatePseudoPolygon(mesh, from, to, cavity.left_chain, cavity);
  std::reverse(cavity.right_chain.begin(), cavity.right_chain.end());
  TriangulatePseudoPolygon(mesh, to, from, cavity.right_chain, cavity);
  if (cavity.new_triangles.size() != cavity.triangles.size()) {
    return absl::InternalError(
        "segment insertion: the cavity's "
        "retriangulation has the wrong size");
  }
  return ReplaceCavity(mesh, from, to, segment, cavity);
}

}  // namespace freeform::internal
