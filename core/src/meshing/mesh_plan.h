// MeshPlan (mesh.h): what PlanMesh decides before any vertex is made and
// TessellatePlanned follows: the pieces of every surface with their grids,
// and the sides they share with their sample counts.
#ifndef FREEFORM_CORE_SRC_MESHING_MESH_PLAN_H_
#define FREEFORM_CORE_SRC_MESHING_MESH_PLAN_H_

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/mesh.h"
#include "freeform/core/surface.h"

namespace freeform {
namespace internal {

// Grid cells or side segments beyond this are refused (they would not fit
// the 32-bit vertex indices anyway).
inline constexpr double kMaxMeshCells = 1 << 30;

// A piece side: bottom (v = 0), right (u = 1), top (v = 1), left (u = 0);
// its curve runs in the direction of increasing parameter.
enum MeshSide { kBottom = 0, kRight = 1, kTop = 2, kLeft = 3 };

// One span rectangle of one surface, meshed as a (rational) Bezier piece on
// [0, 1]^2.
struct PiecePlan {
  uint32_t surface = 0;
  // The index of the piece in DecomposeSurface(surface).pieces.patches.
  uint32_t piece = 0;
  int grid_u = 2;  // interior grid cells
  int grid_v = 2;
  std::array<int, 4> edge = {};       // index into MeshPlan::edges
  std::array<bool, 4> reversed = {};  // canonical direction is reversed
};

// A side shared by the pieces whose PiecePlan::edge names it.
struct EdgePlan {
  int segments = 1;
  bool collapsed = false;
};

}  // namespace internal

class MeshPlan {
 public:
  absl::Span<const Surface> surfaces;
  std::vector<internal::PiecePlan> pieces;
  std::vector<internal::EdgePlan> edges;
  // The Bezier pieces of every surface (DecomposeSurface) when planning
  // evaluated them (a normal-angle limit), else empty: TessellatePlanned
  // cuts the surfaces itself then.
  std::vector<SurfaceDecomposition> decompositions;
  MeshSize size;
  uint64_t piece_values = 0;
  // The largest absolute control-point coordinate (the welding scale).
  double scale = 0.0;
};

namespace internal {

// RefineNormalAngles raises the grids of plan.pieces and the segments of
// plan.edges until the unit normals at the two ends of every edge the
// builder will make differ by at most options.max_normal_angle
// (mesh_angle.cc), evaluating plan.decompositions, which must hold every
// surface's pieces. `vertex_count` is the planned vertex count, kept up to
// date. Fails with RESOURCE_EXHAUSTED naming "max_normal_angle" when more
// than options.max_vertices vertices would be needed, and with the token's
// CANCELLED / DEADLINE_EXCEEDED.
absl::Status RefineNormalAngles(MeshPlan& plan, const MeshOptions& options,
                                double& vertex_count,
                                const CancellationToken* cancel);

}  // namespace internal
}  // namespace freeform

#endif  // FREEFORM_CORE_SRC_MESHING_MESH_PLAN_H_
