#include "triangulation/constraint_insertion.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "freeform/core/status_macros.h"
#include "triangulation/delaunay_insertion.h"
#include "triangulation/predicates.h"

namespace freeform::internal {
namespace {

uint64_t EdgeKey(int32_t from, int32_t to) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(from)) << 32) |
         static_cast<uint32_t>(to);
}

absl::Status CrossingError(int32_t segment, int32_t other) {
  return absl::InvalidArgumentError(
      absl::StrCat("segments[", segment, "] crosses segments[", other, "]"));
}

// Whether `p`, collinear with the segment from `from` to `to`, lies on the
// ray from `from` through `to` (and is not `from`).
bool OnRay(Point2 from, Point2 to, Point2 p) {
  if (from.x != to.x) return p.x != from.x && (p.x > from.x) == (to.x > from.x);
  return p.y != from.y && (p.y > from.y) == (to.y > from.y);
}

// Where a segment leaves its first vertex.
struct SegmentStart {
  enum class Kind { kEdgeExists, kThroughVertex, kCrossesEdge };
  Kind kind;
  int32_t triangle = kNoTriangle;
  // kEdgeExists and kThroughVertex: the corner opposite the edge from
  // `from` along the segment; kCrossesEdge: the corner of `from`.
  int corner = 0;
  int32_t vertex = kGhostVertex;  // kThroughVertex: the edge's other end
};

// FindSegmentStart turns around `from` to the triangle the segment towards
// `to` leaves it through.
absl::StatusOr<SegmentStart> FindSegmentStart(const TriangleMesh2d& mesh,
                                              int32_t from, int32_t to) {
  using Kind = SegmentStart::Kind;
  const Point2 start = mesh.points[from];
  const Point2 end = mesh.points[to];
  const int32_t first = mesh.vertex_triangle[from];
  int32_t triangle = first;
  do {
    const int corner = mesh.CornerOf(triangle, from);
    const std::array<int32_t, 3>& v = mesh.triangles[triangle].vertices;
    const int32_t x = v[NextCorner(corner)];
    const int32_t y = v[PreviousCorner(corner)];
    if (x == to) return SegmentStart{Kind::kEdgeExists, triangle,
                                     PreviousCorner(corner)};
    if (y == to) return SegmentStart{Kind::kEdgeExists, triangle,
                                     NextCorner(corner)};
    if (!mesh.IsGhost(triangle)) {
      const double x_side = Orient2d(start, end, mesh.points[x]);
      const double y_side = Orient2d(start, end, mesh.points[y]);
      if (x_side == 0.0 && OnRay(start, end, mesh.points[x])) {
        return SegmentStart{Kind::kThroughVertex, triangle,
                            PreviousCorner(corner), x};
      }
      if (y_side == 0.0 && OnRay(start, end, mesh.points[y])) {
        return SegmentStart{Kind::kThroughVertex, triangle,
                            NextCorner(corner), y};
      }
      if (x_side < 0.0 && y_side > 0.0) {
        return SegmentStart{Kind::kCrossesEdge, triangle, corner};
      }
    }
    triangle = mesh.triangles[triangle].neighbors[NextCorner(corner)];
  } while (triangle != first);
  return absl::InternalError("segment insertion: no triangle around a vertex "
                             "contains the segment's direction");
}

// MarkEdge makes the edge opposite `corner` of `triangle` carry `segment`.
absl::Status MarkEdge(TriangleMesh2d& mesh, int32_t triangle, int corner,
                      int32_t segment) {
  const int32_t carried = mesh.triangles[triangle].segments[corner];
  if (carried != kNoSegment && carried != segment) {
    return CrossingError(segment, carried);
  }
  mesh.LinkAcross(triangle, corner, mesh.triangles[triangle].neighbors[corner],
                  segment);
  return absl::OkStatus();
}

// WalkCrossedTriangles follows the segment from the vertex at `corner` of
// `triangle` across the triangles it crosses, into scratch.cavity and the
// chains of vertices left and right of it, up to the first vertex on the
// segment, which it returns.
absl::StatusOr<int32_t> WalkCrossedTriangles(const TriangleMesh2d& mesh,
                                             int32_t triangle, int corner,
                                             int32_t to, int32_t segment,
                                             SegmentScratch& scratch) {
  const Point2 start =
      mesh.points[mesh.triangles[triangle].vertices[corner]];
  const Point2 end = mesh.points[to];
  const std::array<int32_t, 2> first_edge = mesh.Edge(triangle, corner);
  int32_t right = first_edge[0];
  int32_t left = first_edge[1];
  scratch.cavity.assign({triangle});
  scratch.left_chain.assign({left});
  scratch.right_chain.assign({right});
  while (true) {
    const MeshTriangle& t = mesh.triangles[triangle];
    if (t.segments[corner] != kNoSegment) {
      return CrossingError(segment, t.segments[corner]);
    }
    const int32_t next = t.neighbors[corner];
    if (mesh.IsGhost(next)) {
      return absl::InternalError("segment insertion left the convex hull");
    }
    scratch.cavity.push_back(next);
    const int32_t z =
        mesh.triangles[next].vertices[mesh.CornerOpposite(next, left, right)];
    if (z == to) return z;
    const double side = Orient2d(start, end, mesh.points[z]);
    if (side == 0.0) return z;
    if (side > 0.0) {
      scratch.left_chain.push_back(z);
      corner = mesh.CornerOf(next, left);
      left = z;
    } else {
      scratch.right_chain.push_back(z);
      corner = mesh.CornerOf(next, right);
      right = z;
    }
    triangle = next;
  }
}

// TriangulatePseudoPolygon appends the constrained Delaunay triangulation of
// the polygon `from`, `chain`..., `to` (the chain left of from -> to) to
// scratch.new_triangles: the chain vertex whose circle through from and to
// holds no other chain vertex makes a triangle, and the two sides recurse.
void TriangulatePseudoPolygon(const TriangleMesh2d& mesh, int32_t from,
                              int32_t to, const std::vector<int32_t>& chain,
                              SegmentScratch& scratch) {
  scratch.polygons.assign({{from, to, 0, chain.size()}});
  while (!scratch.polygons.empty()) {
    const SegmentScratch::Polygon polygon = scratch.polygons.back();
    scratch.polygons.pop_back();
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
    scratch.new_triangles.push_back({polygon.from, polygon.to, chain[apex]});
    scratch.polygons.push_back(
        {polygon.from, chain[apex], polygon.chain_begin, apex});
    scratch.polygons.push_back(
        {chain[apex], polygon.to, apex + 1, polygon.chain_end});
  }
}

// RemoveSpikes cuts every excursion (v, w..., v) out of `chain`, keeping v
// once; the vertices cut out go to scratch.spike_vertices.
void RemoveSpikes(std::vector<int32_t>& chain, SegmentScratch& scratch) {
  std::vector<int32_t>& position = scratch.chain_position;
  size_t kept = 0;
  for (const int32_t vertex : chain) {
    if (position[vertex] < 0) {
      position[vertex] = static_cast<int32_t>(kept);
      chain[kept++] = vertex;
      continue;
    }
    while (kept > static_cast<size_t>(position[vertex]) + 1) {
      const int32_t spike = chain[--kept];
      position[spike] = -1;
      scratch.spike_vertices.push_back(spike);
    }
  }
  chain.resize(kept);
  std::erase_if(scratch.spike_vertices,
                [&position](int32_t v) { return position[v] >= 0; });
  for (const int32_t vertex : chain) position[vertex] = -1;
}

// RecordCavityBoundary keys each edge of the cavity's outline by its
// direction in the cavity, with the triangle outside across it, and lists
// the segments on edges inside the cavity (the spikes').
void RecordCavityBoundary(const TriangleMesh2d& mesh,
                          SegmentScratch& scratch) {
  scratch.in_cavity.resize(mesh.triangles.size(), 0);
  for (const int32_t triangle : scratch.cavity) scratch.in_cavity[triangle] = 1;
  scratch.boundary.clear();
  scratch.inner_segments.clear();
  for (const int32_t triangle : scratch.cavity) {
    const MeshTriangle& t = mesh.triangles[triangle];
    for (int corner = 0; corner < 3; ++corner) {
      const std::array<int32_t, 2> edge = mesh.Edge(triangle, corner);
      if (scratch.in_cavity[t.neighbors[corner]] == 0) {
        scratch.boundary[EdgeKey(edge[0], edge[1])] = {t.neighbors[corner],
                                                       t.segments[corner]};
      } else if (t.segments[corner] != kNoSegment && edge[0] < edge[1]) {
        scratch.inner_segments.push_back(
            {edge[0], edge[1], t.segments[corner]});
      }
    }
  }
  for (const int32_t triangle : scratch.cavity) scratch.in_cavity[triangle] = 0;
}

// ReplaceCavity writes scratch.new_triangles into the first of the
// cavity's slots (freeing the others) and links them to each other and to
// the outline; the edge from `from` to `to` carries `segment`.
absl::Status ReplaceCavity(TriangleMesh2d& mesh, int32_t from, int32_t to,
                           int32_t segment, SegmentScratch& scratch) {
  scratch.new_edges.clear();
  const size_t count = scratch.new_triangles.size();
  for (size_t i = 0; i < count; ++i) {
    const int32_t triangle = scratch.cavity[i];
    mesh.SetTriangle(triangle, scratch.new_triangles[i]);
    for (int corner = 0; corner < 3; ++corner) {
      const std::array<int32_t, 2> edge = mesh.Edge(triangle, corner);
      scratch.new_edges[EdgeKey(edge[0], edge[1])] = triangle;
    }
  }
  mesh.free_triangles.insert(mesh.free_triangles.end(),
                             scratch.cavity.begin() + count,
                             scratch.cavity.end());
  for (size_t i = 0; i < count; ++i) {
    const int32_t triangle = scratch.cavity[i];
    for (int corner = 0; corner < 3; ++corner) {
      const std::array<int32_t, 2> edge = mesh.Edge(triangle, corner);
      const auto inside = scratch.new_edges.find(EdgeKey(edge[1], edge[0]));
      if (inside != scratch.new_edges.end()) {
        const bool is_segment = (edge[0] == from && edge[1] == to) ||
                                (edge[0] == to && edge[1] == from);
        mesh.LinkAcross(triangle, corner, inside->second,
                        is_segment ? segment : kNoSegment);
        continue;
      }
      const auto outside = scratch.boundary.find(EdgeKey(edge[0], edge[1]));
      if (outside == scratch.boundary.end()) {
        return absl::InternalError(
            "segment insertion: the retriangulation does not fit the cavity");
      }
      mesh.LinkAcross(triangle, corner, outside->second.triangle,
                      outside->second.segment);
    }
  }
  return absl::OkStatus();
}

// PutSpikesBack inserts the vertices taken out of the last cavity again,
// then the segments they carried.
absl::Status PutSpikesBack(TriangleMesh2d& mesh, SegmentScratch& scratch,
                           size_t& work) {
  if (scratch.spike_vertices.empty()) return absl::OkStatus();
  const std::vector<int32_t> spikes = scratch.spike_vertices;
  const std::vector<std::array<int32_t, 3>> segments = scratch.inner_segments;
  for (const int32_t vertex : spikes) {
    mesh.vertex_triangle[vertex] = kNoTriangle;
    if (InsertVertex(mesh, vertex) != vertex) {
      return absl::InternalError("segment insertion: a vertex taken out of "
                                 "a cavity came back as a duplicate");
    }
  }
  for (const auto& [from, to, segment] : segments) {
    ASSIGN_OR_RETURN(const size_t done,
                     InsertSegment(mesh, from, to, segment, scratch));
    work += done;
  }
  return absl::OkStatus();
}

// InsertPiece inserts the segment from `from` towards `to` up to the first
// vertex on it, which it returns; adds the triangles replaced to `work`.
absl::StatusOr<int32_t> InsertPiece(TriangleMesh2d& mesh, int32_t from,
                                    int32_t to, int32_t segment,
                                    SegmentScratch& scratch, size_t& work) {
  ASSIGN_OR_RETURN(const SegmentStart start,
                   FindSegmentStart(mesh, from, to));
  switch (start.kind) {
    case SegmentStart::Kind::kEdgeExists:
      RETURN_IF_ERROR(MarkEdge(mesh, start.triangle, start.corner, segment));
      return to;
    case SegmentStart::Kind::kThroughVertex:
      RETURN_IF_ERROR(MarkEdge(mesh, start.triangle, start.corner, segment));
      return start.vertex;
    case SegmentStart::Kind::kCrossesEdge:
      break;
  }
  ASSIGN_OR_RETURN(const int32_t reached,
                   WalkCrossedTriangles(mesh, start.triangle, start.corner, to,
                                        segment, scratch));
  scratch.chain_position.resize(mesh.points.size(), -1);
  scratch.spike_vertices.clear();
  RemoveSpikes(scratch.left_chain, scratch);
  RemoveSpikes(scratch.right_chain, scratch);
  RecordCavityBoundary(mesh, scratch);
  scratch.new_triangles.clear();
  TriangulatePseudoPolygon(mesh, from, reached, scratch.left_chain, scratch);
  std::reverse(scratch.right_chain.begin(), scratch.right_chain.end());
  TriangulatePseudoPolygon(mesh, reached, from, scratch.right_chain, scratch);
  if (scratch.new_triangles.size() + 2 * scratch.spike_vertices.size() !=
      scratch.cavity.size()) {
    return absl::InternalError("segment insertion: the cavity's "
                               "retriangulation has the wrong size");
  }
  RETURN_IF_ERROR(ReplaceCavity(mesh, from, reached, segment, scratch));
  mesh.last_triangle = scratch.cavity.front();
  work += scratch.cavity.size();
  RETURN_IF_ERROR(PutSpikesBack(mesh, scratch, work));
  return reached;
}

}  // namespace

absl::StatusOr<size_t> InsertSegment(TriangleMesh2d& mesh, int32_t a,
                                     int32_t b, int32_t segment,
                                     SegmentScratch& scratch) {
  size_t work = 1;
  int32_t from = a;
  while (from != b) {
    ASSIGN_OR_RETURN(from, InsertPiece(mesh, from, b, segment, scratch, work));
    ++work;
  }
  return work;
}

}  // namespace freeform::internal
