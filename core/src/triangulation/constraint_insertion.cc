#include "triangulation/constraint_insertion.h"

#include "absl/strings/str_cat.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "triangulation/predicates.h"

namespace freeform::internal {
namespace {

absl::Status CrossingError(int32_t segment, int32_t other) {
  return InvalidFieldError(
      IndexedField("segments", static_cast<size_t>(segment)),
      absl::StrCat("crosses or overlaps segments[", other, "]"));
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
    if (x == to)
      return SegmentStart{Kind::kEdgeExists, triangle, PreviousCorner(corner)};
    if (y == to)
      return SegmentStart{Kind::kEdgeExists, triangle, NextCorner(corner)};
    if (!mesh.IsGhost(triangle)) {
      const double x_side = Orient2d(start, end, mesh.points[x]);
      const double y_side = Orient2d(start, end, mesh.points[y]);
      if (x_side == 0.0 && OnRay(start, end, mesh.points[x])) {
        return SegmentStart{Kind::kThroughVertex, triangle,
                            PreviousCorner(corner), x};
      }
      if (y_side == 0.0 && OnRay(start, end, mesh.points[y])) {
        return SegmentStart{Kind::kThroughVertex, triangle, NextCorner(corner),
                            y};
      }
      if (x_side < 0.0 && y_side > 0.0) {
        return SegmentStart{Kind::kCrossesEdge, triangle, corner};
      }
    }
    triangle = mesh.triangles[triangle].neighbors[NextCorner(corner)];
  } while (triangle != first);
  return absl::InternalError(
      "segment insertion: no triangle around a vertex "
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

// CollectCrossedEdges follows the segment from the vertex at `corner` of
// `triangle` towards `to`, listing the edges it crosses in
// scratch.crossing and its cavity in scratch.cavity, up to the first vertex
// on the segment, which it returns.
absl::StatusOr<int32_t> CollectCrossedEdges(const TriangleMesh2d& mesh,
                                            int32_t triangle, int corner,
                                            int32_t to, int32_t segment,
                                            SegmentScratch& scratch) {
  const Point2 start = mesh.points[mesh.triangles[triangle].vertices[corner]];
  const Point2 end = mesh.points[to];
  const std::array<int32_t, 2> first_edge = mesh.Edge(triangle, corner);
  int32_t right = first_edge[0];
  int32_t left = first_edge[1];
  scratch.crossing.clear();
  SegmentCavity& cavity = scratch.cavity;
  cavity.triangles.assign({triangle});
  cavity.left_chain.assign({left});
  cavity.right_chain.assign({right});
  while (true) {
    const MeshTriangle& t = mesh.triangles[triangle];
    if (t.segments[corner] != kNoSegment) {
      return CrossingError(segment, t.segments[corner]);
    }
    scratch.crossing.push_back({right, left});
    const int32_t next = t.neighbors[corner];
    if (mesh.IsGhost(next)) {
      return absl::InternalError("segment insertion left the convex hull");
    }
    cavity.triangles.push_back(next);
    const int32_t z =
        mesh.triangles[next].vertices[mesh.CornerOpposite(next, left, right)];
    if (z == to) return z;
    const double side = Orient2d(start, end, mesh.points[z]);
    if (side == 0.0) return z;
    if (side > 0.0) {
      cavity.left_chain.push_back(z);
      corner = mesh.CornerOf(next, left);
      left = z;
    } else {
      cavity.right_chain.push_back(z);
      corner = mesh.CornerOf(next, right);
      right = z;
    }
    triangle = next;
  }
}

// Whether the open segments ab and cd cross.
bool Crosses(Point2 a, Point2 b, Point2 c, Point2 d) {
  const double c_side = Orient2d(a, b, c), d_side = Orient2d(a, b, d);
  const double a_side = Orient2d(c, d, a), b_side = Orient2d(c, d, b);
  return ((c_side > 0.0 && d_side < 0.0) || (c_side < 0.0 && d_side > 0.0)) &&
         ((a_side > 0.0 && b_side < 0.0) || (a_side < 0.0 && b_side > 0.0));
}

// FlipCrossedEdges flips the edges in scratch.crossing until none crosses
// the segment from `from` to `to` (Sloan's loop); the new edges go to
// scratch.to_check.
absl::Status FlipCrossedEdges(TriangleMesh2d& mesh, int32_t from, int32_t to,
                              SegmentScratch& scratch, size_t& work) {
  const Point2 start = mesh.points[from];
  const Point2 end = mesh.points[to];
  // Every pass over the queue flips at least one edge (Sloan 1993): a whole
  // pass of waits means a broken mesh.
  size_t waits = 0;
  while (!scratch.crossing.empty()) {
    const std::array<int32_t, 2> edge = scratch.crossing.front();
    scratch.crossing.pop_front();
    const auto [triangle, corner] = mesh.FindEdge(edge[0], edge[1]);
    if (triangle == kNoTriangle) {
      return absl::InternalError("segment insertion lost a crossed edge");
    }
    const MeshTriangle& t = mesh.triangles[triangle];
    const int32_t p = t.vertices[corner];
    const int32_t x = t.vertices[NextCorner(corner)];
    const int32_t y = t.vertices[PreviousCorner(corner)];
    const int32_t other = t.neighbors[corner];
    const int32_t z =
        mesh.triangles[other].vertices[mesh.CornerOpposite(other, x, y)];
    const Point2 pp = mesh.points[p], pz = mesh.points[z];
    if (Orient2d(pp, mesh.points[x], pz) <= 0.0 ||
        Orient2d(pp, pz, mesh.points[y]) <= 0.0) {
      if (++waits > scratch.crossing.size()) {
        return absl::InternalError(
            "segment insertion: no crossed edge can "
            "be flipped");
      }
      scratch.crossing.push_back(edge);
      continue;
    }
    mesh.FlipEdge(triangle, corner);
    ++work;
    waits = 0;
    if (Crosses(start, end, pp, pz)) {
      scratch.crossing.push_back({p, z});
    } else {
      scratch.to_check.push_back({p, z});
    }
  }
  return absl::OkStatus();
}

// RestoreDelaunay flips, from the edges in scratch.to_check outwards, every
// edge that carries no segment and is not locally Delaunay (Lawson).
void RestoreDelaunay(TriangleMesh2d& mesh, SegmentScratch& scratch,
                     size_t& work) {
  while (!scratch.to_check.empty()) {
    const std::array<int32_t, 2> edge = scratch.to_check.back();
    scratch.to_check.pop_back();
    const auto [triangle, corner] = mesh.FindEdge(edge[0], edge[1]);
    if (triangle == kNoTriangle) continue;  // flipped away since
    const MeshTriangle& t = mesh.triangles[triangle];
    if (t.segments[corner] != kNoSegment || mesh.IsGhost(triangle)) continue;
    const int32_t other = t.neighbors[corner];
    if (!mesh.InsideCircumcircle(other, mesh.points[t.vertices[corner]])) {
      continue;
    }
    const int32_t p = t.vertices[corner];
    const int32_t x = t.vertices[NextCorner(corner)];
    const int32_t y = t.vertices[PreviousCorner(corner)];
    const int32_t z =
        mesh.triangles[other].vertices[mesh.CornerOpposite(other, x, y)];
    mesh.FlipEdge(triangle, corner);
    ++work;
    scratch.to_check.insert(scratch.to_check.end(),
                            {{p, x}, {x, z}, {z, y}, {y, p}});
  }
}

// InsertPiece inserts the segment from `from` towards `to` up to the first
// vertex on it, which it returns; adds the flips to `work`.
absl::StatusOr<int32_t> InsertPiece(TriangleMesh2d& mesh, int32_t from,
                                    int32_t to, int32_t segment,
                                    SegmentScratch& scratch, size_t& work) {
  ASSIGN_OR_RETURN(const SegmentStart start, FindSegmentStart(mesh, from, to));
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
                   CollectCrossedEdges(mesh, start.triangle, start.corner, to,
                                       segment, scratch));
  work += scratch.crossing.size();
  mesh.last_triangle = mesh.vertex_triangle[from];
  if (HasSimpleChains(mesh, scratch.cavity)) {
    RETURN_IF_ERROR(
        RetriangulateCavity(mesh, from, reached, segment, scratch.cavity));
    return reached;
  }
  scratch.to_check.clear();
  RETURN_IF_ERROR(FlipCrossedEdges(mesh, from, reached, scratch, work));
  const auto [triangle, corner] = mesh.FindEdge(from, reached);
  if (triangle == kNoTriangle) {
    return absl::InternalError(
        "segment insertion: the segment is no edge "
        "after the flips");
  }
  RETURN_IF_ERROR(MarkEdge(mesh, triangle, corner, segment));
  RestoreDelaunay(mesh, scratch, work);
  return reached;
}

}  // namespace

absl::StatusOr<size_t> InsertSegment(TriangleMesh2d& mesh, int32_t a, int32_t b,
                                     int32_t segment, SegmentScratch& scratch) {
  size_t work = 1;
  int32_t from = a;
  while (from != b) {
    ASSIGN_OR_RETURN(from, InsertPiece(mesh, from, b, segment, scratch, work));
    ++work;
  }
  return work;
}

}  // namespace freeform::internal
