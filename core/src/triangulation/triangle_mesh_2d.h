// TriangleMesh2d: a planar triangulation as triangles with neighbour links,
// closed by a ghost vertex at infinity: every hull edge x -> y (the
// outside on its left) carries a ghost triangle (x, y, ghost), so that the
// hull needs no special case in point location, insertion and flips. Each
// edge records the index of the segment it carries, if any. Mesh vertex
// indices are point indices. Not thread-safe to modify. Internal to the
// core.
#ifndef FREEFORM_CORE_SRC_TRIANGULATION_TRIANGLE_MESH_2D_H_
#define FREEFORM_CORE_SRC_TRIANGULATION_TRIANGLE_MESH_2D_H_

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "freeform/core/constrained_delaunay.h"

namespace freeform::internal {

inline constexpr int32_t kGhostVertex = -1;
inline constexpr int32_t kNoTriangle = -1;
inline constexpr int32_t kNoSegment = -1;

// The corner after and before `corner` in counter-clockwise order.
inline int NextCorner(int corner) { return corner == 2 ? 0 : corner + 1; }
inline int PreviousCorner(int corner) { return corner == 0 ? 2 : corner - 1; }

struct MeshTriangle {
  // Counter-clockwise; at most one is kGhostVertex.
  std::array<int32_t, 3> vertices;
  // neighbors[i] lies across the edge opposite vertices[i], which runs
  // from vertices[i + 1] to vertices[i + 2].
  std::array<int32_t, 3> neighbors = {kNoTriangle, kNoTriangle, kNoTriangle};
  // The segment index the edge opposite vertices[i] carries, or
  // kNoSegment.
  std::array<int32_t, 3> segments = {kNoSegment, kNoSegment, kNoSegment};
};

struct TriangleMesh2d {
  std::vector<Point2> points;
  // Per input point: the vertex it merged into.
  std::vector<int32_t> representative;
  std::vector<MeshTriangle> triangles;
  // Per point: a triangle incident to it, or kNoTriangle while it is not a
  // vertex (not inserted yet, or merged into another).
  std::vector<int32_t> vertex_triangle;
  // Where the next point location starts.
  int32_t last_triangle = 0;
  // The edges left to check after an insertion (kept between insertions).
  std::vector<int32_t> flip_stack;
  // The state of the walks' random choices (deterministic).
  uint64_t walk_state = 0x9E3779B97F4A7C15u;

  bool IsGhost(int32_t triangle) const;
  // CornerOf returns the corner of `triangle` holding `vertex`, or -1.
  int CornerOf(int32_t triangle, int32_t vertex) const;
  // CornerOpposite returns the corner of `triangle` holding neither `a`
  // nor `b`.
  int CornerOpposite(int32_t triangle, int32_t a, int32_t b) const;
  // Edge returns the edge opposite `corner` as {from, to}.
  std::array<int32_t, 2> Edge(int32_t triangle, int corner) const;

  // SetTriangle writes the vertices (and keeps vertex_triangle pointing at
  // a triangle of each); links and segments are set separately.
  void SetTriangle(int32_t triangle, std::array<int32_t, 3> vertices);
  // AddTriangle appends a triangle and returns its index.
  int32_t AddTriangle(std::array<int32_t, 3> vertices);
  // LinkAcross makes `triangle` and `other` neighbours across the edge
  // opposite `corner` of `triangle` (which `other` must share), carrying
  // `segment` on both sides.
  void LinkAcross(int32_t triangle, int corner, int32_t other, int32_t segment);

  // FlipEdge replaces `triangle` (p, x, y), p at `corner`, and the
  // triangle (z, y, x) across its edge opposite p by (p, x, z), kept in
  // `triangle`, and (p, z, y), both with p at corner 0. The quadrilateral
  // p, x, z, y must be strictly convex.
  void FlipEdge(int32_t triangle, int corner);

  // FindEdge returns a triangle with the edge between a and b and the
  // corner opposite it, or {kNoTriangle, 0} when they are not joined.
  std::pair<int32_t, int> FindEdge(int32_t a, int32_t b) const;

  // InsideCircumcircle returns whether `point` lies strictly inside the
  // circumcircle of `triangle`; for a ghost triangle (x, y, ghost) the
  // "circle" is the open half-plane left of x -> y and the open segment
  // between them.
  bool InsideCircumcircle(int32_t triangle, Point2 point) const;
};

// NextWalkRandom advances `state` and returns a pseudo-random number
// (xorshift64*): the walks' choices are deterministic.
uint32_t NextWalkRandom(uint64_t& state);

// StrictlyBetween returns whether `p`, collinear with a and b, lies on the
// open segment between them.
bool StrictlyBetween(Point2 a, Point2 b, Point2 p);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_TRIANGULATION_TRIANGLE_MESH_2D_H_
