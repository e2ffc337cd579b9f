#include "triangulation/triangle_mesh_2d.h"

#include "triangulation/predicates.h"

namespace freeform::internal {
namespace {

// Whether `p` is strictly between a and b along one coordinate.
bool StrictlyBetweenValues(double a, double b, double p) {
  return (a < p && p < b) || (b < p && p < a);
}

}  // namespace

bool StrictlyBetween(Point2 a, Point2 b, Point2 p) {
  if (a.x != b.x) return StrictlyBetweenValues(a.x, b.x, p.x);
  return StrictlyBetweenValues(a.y, b.y, p.y);
}

bool TriangleMesh2d::IsGhost(int32_t triangle) const {
  const std::array<int32_t, 3>& v = triangles[triangle].vertices;
  return v[0] == kGhostVertex || v[1] == kGhostVertex || v[2] == kGhostVertex;
}

int TriangleMesh2d::CornerOf(int32_t triangle, int32_t vertex) const {
  const std::array<int32_t, 3>& v = triangles[triangle].vertices;
  for (int corner = 0; corner < 3; ++corner) {
    if (v[corner] == vertex) return corner;
  }
  return -1;
}

int TriangleMesh2d::CornerOpposite(int32_t triangle, int32_t a,
                                   int32_t b) const {
  const std::array<int32_t, 3>& v = triangles[triangle].vertices;
  for (int corner = 0; corner < 3; ++corner) {
    if (v[corner] != a && v[corner] != b) return corner;
  }
  return -1;
}

std::array<int32_t, 2> TriangleMesh2d::Edge(int32_t triangle,
                                            int corner) const {
  const std::array<int32_t, 3>& v = triangles[triangle].vertices;
  return {v[NextCorner(corner)], v[PreviousCorner(corner)]};
}

void TriangleMesh2d::SetTriangle(int32_t triangle,
                                 std::array<int32_t, 3> vertices) {
  triangles[triangle].vertices = vertices;
  for (const int32_t vertex : vertices) {
    if (vertex != kGhostVertex) vertex_triangle[vertex] = triangle;
  }
}

int32_t TriangleMesh2d::AddTriangle(std::array<int32_t, 3> vertices) {
  const auto index = static_cast<int32_t>(triangles.size());
  triangles.push_back(MeshTriangle{vertices});
  SetTriangle(index, vertices);
  return index;
}

void TriangleMesh2d::FlipEdge(int32_t triangle, int corner) {
  const MeshTriangle t = triangles[triangle];
  const int32_t p = t.vertices[corner];
  const int32_t x = t.vertices[NextCorner(corner)];
  const int32_t y = t.vertices[PreviousCorner(corner)];
  const int32_t other = t.neighbors[corner];
  const MeshTriangle o = triangles[other];
  const int other_corner = CornerOpposite(other, x, y);
  const int32_t z = o.vertices[other_corner];
  SetTriangle(triangle, {p, x, z});
  SetTriangle(other, {p, z, y});
  // (x, z) and (z, y) were the other's, (p, x) and (y, p) this one's.
  LinkAcross(triangle, 0, o.neighbors[NextCorner(other_corner)],
             o.segments[NextCorner(other_corner)]);
  LinkAcross(triangle, 2, t.neighbors[PreviousCorner(corner)],
             t.segments[PreviousCorner(corner)]);
  LinkAcross(other, 0, o.neighbors[PreviousCorner(other_corner)],
             o.segments[PreviousCorner(other_corner)]);
  LinkAcross(other, 1, t.neighbors[NextCorner(corner)],
             t.segments[NextCorner(corner)]);
  LinkAcross(triangle, 1, other, kNoSegment);
}

std::pair<int32_t, int> TriangleMesh2d::FindEdge(int32_t a, int32_t b) const {
  const int32_t first = vertex_triangle[a];
  int32_t triangle = first;
  do {
    const int corner = CornerOf(triangle, a);
    const std::array<int32_t, 3>& v = triangles[triangle].vertices;
    if (v[NextCorner(corner)] == b) return {triangle, PreviousCorner(corner)};
    if (v[PreviousCorner(corner)] == b) return {triangle, NextCorner(corner)};
    triangle = triangles[triangle].neighbors[NextCorner(corner)];
  } while (triangle != first);
  return {kNoTriangle, 0};
}

void TriangleMesh2d::LinkAcross(int32_t triangle, int corner, int32_t other,
                                int32_t segment) {
  const std::array<int32_t, 2> edge = Edge(triangle, corner);
  const int other_corner = CornerOpposite(other, edge[0], edge[1]);
  triangles[triangle].neighbors[corner] = other;
  triangles[triangle].segments[corner] = segment;
  triangles[other].neighbors[other_corner] = triangle;
  triangles[other].segments[other_corner] = segment;
}

bool TriangleMesh2d::InsideCircumcircle(int32_t triangle, Point2 point) const {
  const std::array<int32_t, 3>& v = triangles[triangle].vertices;
  const int ghost = CornerOf(triangle, kGhostVertex);
  if (ghost < 0) {
    return InCircle(points[v[0]], points[v[1]], points[v[2]], point) > 0.0;
  }
  const Point2 from = points[v[NextCorner(ghost)]];
  const Point2 to = points[v[PreviousCorner(ghost)]];
  const double side = Orient2d(from, to, point);
  return side > 0.0 || (side == 0.0 && StrictlyBetween(from, to, point));
}

uint32_t NextWalkRandom(uint64_t& state) {
  state ^= state >> 12;
  state ^= state << 25;
  state ^= state >> 27;
  return static_cast<uint32_t>((state * 0x2545F4914F6CDD1Du) >> 32);
}

}  // namespace freeform::internal
