// What the mesh planner and the mesh builder share about one planned piece:
// the layout of its ring (the samples of its four sides, the border of its
// interior grid, and the zipper that triangulates the ring between them) and
// the unit normals of a Bezier piece. TessellatePlanned makes its triangles
// from this layout, and the normal-angle refinement of PlanMesh
// (mesh_angle.cc) checks the same edges before any vertex is made.
#ifndef FREEFORM_CORE_SRC_MESHING_MESH_RING_H_
#define FREEFORM_CORE_SRC_MESHING_MESH_RING_H_

#include <array>
#include <cstddef>
#include <vector>

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "freeform/core/surface.h"
#include "meshing/mesh_plan.h"

namespace freeform::internal {

// SideSegments returns the segments of side `side` of a piece: those of its
// edge, or for a collapsed side (one vertex) the piece's grid cells along
// it, which keeps the fan triangles at its apex small in parameter space.
int SideSegments(const PiecePlan& piece, const EdgePlan& edge, int side);

// SidePoint returns the (u, v) of sample m of n of a side, at t = m / n in
// the direction of increasing parameter.
std::array<double, 2> SidePoint(int side, int m, int n);

// A sample of a piece's outer loop: sample m of side `side`, its (u, v),
// and its perimeter coordinate theta in [0, 4] (side k covers [k, k + 1],
// counter-clockwise from (0, 0)).
struct OuterPlace {
  int side = 0;
  int m = 0;
  double u = 0.0;
  double v = 0.0;
  double theta = 0.0;
};

// A node (i, j) of a piece's interior grid on its inner loop, its (u, v) =
// (i / grid_u, j / grid_v), and the perimeter coordinate of the outer
// loop's side it faces.
struct InnerPlace {
  int i = 0;
  int j = 0;
  double u = 0.0;
  double v = 0.0;
  double theta = 0.0;
};

// OuterLoop returns the side samples counter-clockwise from (0, 0); a
// corner appears at the end of one side and at the start of the next.
std::vector<OuterPlace> OuterLoop(const PiecePlan& piece,
                                  absl::Span<const EdgePlan> edges);

// InnerLoop returns the boundary of the interior grid (nodes 1..grid - 1
// each way) counter-clockwise, each node with the perimeter coordinate of
// the side it faces (its u or v along that side), so the zipper pairs
// samples that are at most one spacing apart in u and in v, also at the
// corners (where the inner corner appears once for each side). A single
// node row or column is both ends of its side.
std::vector<InnerPlace> InnerLoop(int grid_u, int grid_v);

// ZipLoops triangulates the ring between the loops by merging them in
// order of theta (a "zipper"): each step advances the loop whose next
// sample comes first, so every triangle spans at most about one sample
// spacing of each loop. It calls triangle(i, j, true) for the triangle
// (outer[i], outer[i + 1], inner[j]) and triangle(i, j, false) for
// (outer[i], inner[j + 1], inner[j]), both counter-clockwise in (u, v).
template <typename Outer, typename Inner, typename Triangle>
void ZipLoops(const Outer& outer, const Inner& inner, Triangle triangle) {
  size_t i = 0;
  size_t j = 0;
  while (i + 1 < outer.size() || j + 1 < inner.size()) {
    const bool advance_outer =
        j + 1 == inner.size() ||
        (i + 1 < outer.size() && outer[i + 1].theta <= inner[j + 1].theta);
    triangle(i, j, advance_outer);
    if (advance_outer) {
      ++i;
    } else {
      ++j;
    }
  }
}

// PieceEvaluator evaluates a Bezier piece at (u, v) pairs: the positions
// and the unit normals, by first partials where the normal is regular and
// by the limit from inside the piece (second partials, ComputeUnitNormals)
// where S_u x S_v vanishes. A zero normal means the surface has none there.
// Reuses its memory from call to call.
class PieceEvaluator {
 public:
  absl::Status Evaluate(const BezierSurfaceView& piece,
                        absl::Span<const double> uv);
  // Point k at positions()[3 k .. 3 k + 2], its normal at normals()[3 k..].
  absl::Span<const double> positions() const { return buffers_[0]; }
  absl::Span<const double> normals() const { return normals_; }

 private:
  std::vector<std::vector<double>> buffers_, second_buffers_;
  std::vector<double> normals_, second_normals_;
  std::vector<double> degenerate_uv_;
  std::vector<size_t> degenerate_;
};

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_MESHING_MESH_RING_H_
