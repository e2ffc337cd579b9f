#include "triangulation/delaunay_insertion.h"

#include <algorithm>
#include <array>
#include <numeric>
#include <tuple>
#include <utility>
#include <vector>

#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "triangulation/insertion_order.h"
#include "triangulation/predicates.h"

namespace freeform::internal {
namespace {

// Delaunay insertion polls the token once per this many points.
constexpr size_t kPointsPerPoll = 4096;

double SideOfEdge(const TriangleMesh2d& mesh, int32_t triangle, int corner,
                  Point2 point) {
  const std::array<int32_t, 2> edge = mesh.Edge(triangle, corner);
  return Orient2d(mesh.points[edge[0]], mesh.points[edge[1]], point);
}

// Classify places `point`, on no edge's outer side, in the real `triangle`.
PointLocation Classify(const TriangleMesh2d& mesh, int32_t triangle,
                       Point2 point) {
  int zeros = 0;
  int zero_corner = 0;
  int nonzero_corner = 0;
  for (int corner = 0; corner < 3; ++corner) {
    if (SideOfEdge(mesh, triangle, corner, point) == 0.0) {
      ++zeros;
      zero_corner = corner;
    } else {
      nonzero_corner = corner;
    }
  }
  using Kind = PointLocation::Kind;
  if (zeros >= 2) return {Kind::kVertex, triangle, nonzero_corner};
  if (zeros == 1) return {Kind::kOnEdge, triangle, zero_corner};
  return {Kind::kInside, triangle, 0};
}

// The triangle's saved link across one edge.
struct Across {
  int32_t neighbor;
  int32_t segment;
};

Across AcrossCorner(const TriangleMesh2d& mesh, int32_t triangle, int corner) {
  const MeshTriangle& t = mesh.triangles[triangle];
  return {t.neighbors[corner], t.segments[corner]};
}

// LinkOutside links the edge opposite corner 0 of a new triangle (the
// edge away from the new vertex) to the triangle it had across.
void LinkOutside(TriangleMesh2d& mesh, int32_t triangle, Across across) {
  mesh.LinkAcross(triangle, 0, across.neighbor, across.segment);
}

// SplitTriangle replaces triangle (a, b, c) by (v, b, c), (v, c, a) and
// (v, a, b); a ghost triangle splits into one real and two ghosts alike.
void SplitTriangle(TriangleMesh2d& mesh, int32_t triangle, int32_t vertex,
                   std::vector<int32_t>& flips) {
  const std::array<int32_t, 3> v = mesh.triangles[triangle].vertices;
  const Across across_a = AcrossCorner(mesh, triangle, 0);
  const Across across_b = AcrossCorner(mesh, triangle, 1);
  const Across across_c = AcrossCorner(mesh, triangle, 2);
  mesh.SetTriangle(triangle, {vertex, v[1], v[2]});
  const int32_t second = mesh.AddTriangle({vertex, v[2], v[0]});
  const int32_t third = mesh.AddTriangle({vertex, v[0], v[1]});
  LinkOutside(mesh, triangle, across_a);
  LinkOutside(mesh, second, across_b);
  LinkOutside(mesh, third, across_c);
  mesh.LinkAcross(triangle, 1, second, kNoSegment);
  mesh.LinkAcross(triangle, 2, third, kNoSegment);
  mesh.LinkAcross(second, 1, third, kNoSegment);
  flips.insert(flips.end(), {triangle, second, third});
}

// SplitEdge splits the edge opposite `corner` of the real `triangle`, and
// the triangle across it, at `vertex`: four triangles, the two halves of
// the edge keep its segment.
void SplitEdge(TriangleMesh2d& mesh, int32_t triangle, int corner,
               int32_t vertex, std::vector<int32_t>& flips) {
  const std::array<int32_t, 3> tv = mesh.triangles[triangle].vertices;
  const int32_t c = tv[corner];
  const int32_t a = tv[NextCorner(corner)];
  const int32_t b = tv[PreviousCorner(corner)];
  const int32_t other = mesh.triangles[triangle].neighbors[corner];
  const int32_t segment = mesh.triangles[triangle].segments[corner];
  const int other_corner = mesh.CornerOpposite(other, a, b);
  const int32_t d = mesh.triangles[other].vertices[other_corner];
  const Across across_ca = AcrossCorner(mesh, triangle, PreviousCorner(corner));
  const Across across_bc = AcrossCorner(mesh, triangle, NextCorner(corner));
  const Across across_ad = AcrossCorner(mesh, other, NextCorner(other_corner));
  const Across across_db =
      AcrossCorner(mesh, other, PreviousCorner(other_corner));
  mesh.SetTriangle(triangle, {vertex, c, a});
  const int32_t triangle_half = mesh.AddTriangle({vertex, b, c});
  mesh.SetTriangle(other, {vertex, d, b});
  const int32_t other_half = mesh.AddTriangle({vertex, a, d});
  LinkOutside(mesh, triangle, across_ca);
  LinkOutside(mesh, triangle_half, across_bc);
  LinkOutside(mesh, other, across_db);
  LinkOutside(mesh, other_half, across_ad);
  mesh.LinkAcross(triangle, 1, other_half, segment);
  mesh.LinkAcross(triangle, 2, triangle_half, kNoSegment);
  mesh.LinkAcross(triangle_half, 2, other, segment);
  mesh.LinkAcross(other, 2, other_half, kNoSegment);
  flips.insert(flips.end(), {triangle, triangle_half, other, other_half});
}

// Legalize flips, from the triangles in `flips` (each with the new point at
// corner 0), every edge opposite the point that carries no segment and
// whose other triangle has the point inside its circumcircle.
void Legalize(TriangleMesh2d& mesh, std::vector<int32_t>& flips) {
  while (!flips.empty()) {
    const int32_t triangle = flips.back();
    flips.pop_back();
    const MeshTriangle& t = mesh.triangles[triangle];
    if (t.segments[0] != kNoSegment) continue;
    const int32_t other = t.neighbors[0];
    if (!mesh.InsideCircumcircle(other, mesh.points[t.vertices[0]])) continue;
    mesh.FlipEdge(triangle, 0);
    flips.insert(flips.end(), {triangle, other});
  }
}

// The three points of the first triangle: the first point of `order`, the
// next different one and the next not collinear with both, moved to the
// front of `order` (counter-clockwise). False when there is none.
bool MoveSeedTriangleToFront(const TriangleMesh2d& mesh,
                             std::vector<int32_t>& order) {
  const auto point = [&](size_t i) { return mesh.points[order[i]]; };
  size_t second = 1;
  while (second < order.size() && point(second) == point(0)) ++second;
  size_t third = second + 1;
  while (third < order.size() &&
         Orient2d(point(0), point(second), point(third)) == 0.0) {
    ++third;
  }
  if (third >= order.size()) return false;
  std::swap(order[1], order[second]);
  std::swap(order[2], order[third]);
  if (Orient2d(point(0), point(1), point(2)) < 0.0) {
    std::swap(order[1], order[2]);
  }
  return true;
}

// AddSeedTriangle makes the mesh the triangle (a, b, c) and its three
// ghosts.
void AddSeedTriangle(TriangleMesh2d& mesh, int32_t a, int32_t b, int32_t c) {
  const int32_t real = mesh.AddTriangle({a, b, c});
  const int32_t ghost_bc = mesh.AddTriangle({c, b, kGhostVertex});
  const int32_t ghost_ca = mesh.AddTriangle({a, c, kGhostVertex});
  const int32_t ghost_ab = mesh.AddTriangle({b, a, kGhostVertex});
  mesh.LinkAcross(real, 0, ghost_bc, kNoSegment);
  mesh.LinkAcross(real, 1, ghost_ca, kNoSegment);
  mesh.LinkAcross(real, 2, ghost_ab, kNoSegment);
  mesh.LinkAcross(ghost_bc, 0, ghost_ab, kNoSegment);
  mesh.LinkAcross(ghost_bc, 1, ghost_ca, kNoSegment);
  mesh.LinkAcross(ghost_ca, 1, ghost_ab, kNoSegment);
  mesh.last_triangle = real;
}

// MergeDuplicates sets each point's representative to the smallest index
// of the points equal to it.
void MergeDuplicates(TriangleMesh2d& mesh) {
  const std::vector<Point2>& points = mesh.points;
  std::vector<int32_t> sorted(points.size());
  std::iota(sorted.begin(), sorted.end(), 0);
  const auto by_coordinates = [&points](int32_t a, int32_t b) {
    return std::tuple(points[a].x, points[a].y, a) <
           std::tuple(points[b].x, points[b].y, b);
  };
  std::sort(sorted.begin(), sorted.end(), by_coordinates);
  mesh.representative.assign(points.size(), 0);
  for (size_t i = 0; i < sorted.size(); ++i) {
    const bool repeats = i > 0 && points[sorted[i]] == points[sorted[i - 1]];
    mesh.representative[sorted[i]] =
        repeats ? mesh.representative[sorted[i - 1]] : sorted[i];
  }
}

}  // namespace

PointLocation Locate(const TriangleMesh2d& mesh, Point2 point, int32_t start,
                     uint64_t& random_state) {
  int32_t triangle = start;
  if (mesh.IsGhost(triangle)) {
    triangle = mesh.triangles[triangle]
                   .neighbors[mesh.CornerOf(triangle, kGhostVertex)];
  }
  while (true) {
    if (mesh.IsGhost(triangle)) {
      return {PointLocation::Kind::kOutside, triangle, 0};
    }
    const int first = static_cast<int>(NextWalkRandom(random_state) % 3);
    int32_t next = kNoTriangle;
    for (int k = 0; k < 3 && next == kNoTriangle; ++k) {
      const int corner = (first + k) % 3;
      if (SideOfEdge(mesh, triangle, corner, point) < 0.0) {
        next = mesh.triangles[triangle].neighbors[corner];
      }
    }
    if (next == kNoTriangle) return Classify(mesh, triangle, point);
    triangle = next;
  }
}

void InsertLocatedVertex(TriangleMesh2d& mesh, int32_t vertex,
                         const PointLocation& location) {
  std::vector<int32_t>& flips = mesh.flip_stack;
  flips.clear();
  switch (location.kind) {
    case PointLocation::Kind::kVertex:
      return;
    case PointLocation::Kind::kOnEdge:
      SplitEdge(mesh, location.triangle, location.corner, vertex, flips);
      break;
    case PointLocation::Kind::kInside:
    case PointLocation::Kind::kOutside:
      SplitTriangle(mesh, location.triangle, vertex, flips);
      break;
  }
  Legalize(mesh, flips);
  mesh.last_triangle = mesh.vertex_triangle[vertex];
}

int32_t InsertVertex(TriangleMesh2d& mesh, int32_t vertex) {
  const PointLocation location =
      Locate(mesh, mesh.points[vertex], mesh.last_triangle, mesh.walk_state);
  if (location.kind == PointLocation::Kind::kVertex) {
    return mesh.triangles[location.triangle].vertices[location.corner];
  }
  InsertLocatedVertex(mesh, vertex, location);
  return vertex;
}

absl::Status BuildDelaunay(TriangleMesh2d& mesh,
                           const CancellationToken* cancel) {
  MergeDuplicates(mesh);
  std::vector<int32_t> order = BiasedRandomizedOrder(mesh.points);
  std::erase_if(order,
                [&mesh](int32_t i) { return mesh.representative[i] != i; });
  if (!MoveSeedTriangleToFront(mesh, order)) {
    return InvalidFieldError("points",
                             "all points are collinear (or fewer than 3 are "
                             "distinct): no triangle exists");
  }
  mesh.vertex_triangle.assign(mesh.points.size(), kNoTriangle);
  mesh.triangles.reserve(2 * order.size() + 2);
  AddSeedTriangle(mesh, order[0], order[1], order[2]);
  for (size_t i = 3; i < order.size(); ++i) {
    if (i % kPointsPerPoll == 0) RETURN_IF_ERROR(CheckCancelled(cancel));
    InsertVertex(mesh, order[i]);
  }
  return absl::OkStatus();
}

}  // namespace freeform::internal
