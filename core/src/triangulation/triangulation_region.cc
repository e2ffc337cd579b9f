#include "triangulation/triangulation_region.h"

#include <algorithm>
#include <utility>

namespace freeform::internal {
namespace {

// The triangles of region `region` (all real ones, or those of odd depth).
std::vector<bool> RegionTriangles(
    const TriangleMesh2d& mesh,
    ConstrainedTriangulationOptions::Region region) {
  std::vector<bool> kept(mesh.triangles.size());
  if (region == ConstrainedTriangulationOptions::Region::kConvexHull) {
    for (size_t t = 0; t < kept.size(); ++t) {
      kept[t] = !mesh.IsGhost(static_cast<int32_t>(t));
    }
    return kept;
  }
  const std::vector<int32_t> depths = SegmentDepths(mesh);
  for (size_t t = 0; t < kept.size(); ++t) kept[t] = depths[t] % 2 == 1;
  return kept;
}

// Whether the edge opposite `corner` of the real `triangle` is listed from
// this side: once per edge.
bool ListsEdge(const TriangleMesh2d& mesh, int32_t triangle, int corner) {
  const int32_t other = mesh.triangles[triangle].neighbors[corner];
  return mesh.IsGhost(other) || triangle < other;
}

// ForEachSegmentEdge calls `visit` once per edge that carries a segment.
template <typename Visit>
void ForEachSegmentEdge(const TriangleMesh2d& mesh, Visit visit) {
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto triangle = static_cast<int32_t>(t);
    if (mesh.IsGhost(triangle)) continue;
    for (int corner = 0; corner < 3; ++corner) {
      if (mesh.triangles[t].segments[corner] != kNoSegment &&
          ListsEdge(mesh, triangle, corner)) {
        visit(mesh.Edge(triangle, corner));
      }
    }
  }
}

}  // namespace

std::vector<int32_t> SegmentDepths(const TriangleMesh2d& mesh) {
  std::vector<int32_t> depths(mesh.triangles.size(), -1);
  std::vector<int32_t> layer, next_layer;
  for (size_t g = 0; g < mesh.triangles.size(); ++g) {
    const auto ghost = static_cast<int32_t>(g);
    if (!mesh.IsGhost(ghost)) continue;
    const int corner = mesh.CornerOf(ghost, kGhostVertex);
    const MeshTriangle& t = mesh.triangles[ghost];
    (t.segments[corner] == kNoSegment ? layer : next_layer)
        .push_back(t.neighbors[corner]);
  }
  for (int32_t depth = 0; !layer.empty() || !next_layer.empty(); ++depth) {
    while (!layer.empty()) {
      const int32_t triangle = layer.back();
      layer.pop_back();
      if (depths[triangle] >= 0) continue;
      depths[triangle] = depth;
      const MeshTriangle& t = mesh.triangles[triangle];
      for (int corner = 0; corner < 3; ++corner) {
        const int32_t other = t.neighbors[corner];
        if (depths[other] >= 0 || mesh.IsGhost(other)) continue;
        (t.segments[corner] == kNoSegment ? layer : next_layer)
            .push_back(other);
      }
    }
    std::swap(layer, next_layer);
  }
  return depths;
}

PlanarTriangulation ExtractTriangulation(
    const TriangleMesh2d& mesh,
    ConstrainedTriangulationOptions::Region region) {
  const std::vector<bool> kept = RegionTriangles(mesh, region);
  PlanarTriangulation result;
  result.triangles.reserve(std::count(kept.begin(), kept.end(), true));
  for (size_t t = 0; t < kept.size(); ++t) {
    if (kept[t]) result.triangles.push_back(mesh.triangles[t].vertices);
  }
  size_t segment_edges = 0;
  ForEachSegmentEdge(mesh, [&](std::array<int32_t, 2>) { ++segment_edges; });
  result.constrained_edges.reserve(segment_edges);
  ForEachSegmentEdge(mesh, [&](std::array<int32_t, 2> edge) {
    result.constrained_edges.push_back(
        {std::min(edge[0], edge[1]), std::max(edge[0], edge[1])});
  });
  result.points = mesh.points;
  result.representative = mesh.representative;
  return result;
}

}  // namespace freeform::internal
