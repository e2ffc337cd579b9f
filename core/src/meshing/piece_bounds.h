// Bounds on the first and second partials of a surface's span rectangles,
// from the control points of its derivative nets (mesh.h's a-priori bound):
// shared by the mesh planner (mesh_plan.cc) and the face mesher
// (faces/face_mesh.cc). Internal to the core; thread-safe (pure functions).
#ifndef FREEFORM_CORE_SRC_MESHING_PIECE_BOUNDS_H_
#define FREEFORM_CORE_SRC_MESHING_PIECE_BOUNDS_H_

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/surface.h"

namespace freeform::internal {

// A surface as the planner reads it: a B-spline net with knots. A Bezier
// surface has clamped knots on [0, 1]; a triangular patch is its degenerate
// tensor net (DecomposeSurface).
struct TensorForm {
  std::optional<BSplineSurfaceView> external;
  SurfaceData owned;
  // The proto field of the surface kind, for errors: "bezier", ...
  const char* kind = "";

  BSplineSurfaceView view() const {
    return external.has_value() ? *external : owned.bspline_view();
  }
};

// TensorFormOf returns the tensor net of any surface.
absl::StatusOr<TensorForm> TensorFormOf(const Surface& surface);

// WeightIndex returns the position of the weight of P[i][j].
size_t WeightIndex(const ControlNetView& net, int i, int j);

// Bounds on the partials of one span rectangle reparameterized to [0, 1]^2.
struct PieceBounds {
  double uu = 0.0, uv = 0.0, vv = 0.0;  // second partials
  double u = 0.0, v = 0.0;              // first partials
};

// The frame of the homogeneous form (w (P - c), w): the centre c, the
// radius R of the control points about it, and their least weight w_min.
struct PieceFrame {
  std::array<double, 3> centre = {};
  double radius = 0.0;
  double min_weight = 1.0;
};

// NetFrame returns the frame of every control point of `surface`: bounds
// of different span rectangles in this one frame may be added.
PieceFrame NetFrame(const BSplineSurfaceView& surface);

// BoundPiece bounds the partials of span rectangle [u_su, u_su+1] x
// [v_sv, v_sv+1] of `surface` as a piece on [0, 1]^2: S_s = du S_u, S_ss =
// du^2 S_uu, ... The derivatives of the homogeneous surface lie in the
// convex hull of the active control points of its derivative nets; the
// rational bound is (|H_s| + R |H_w|) / w_min about the centre c of the
// active points (mesh.h). BoundPieceIn uses the given frame instead (its
// centre, radius and least weight must cover the active points).
PieceBounds BoundPiece(const BSplineSurfaceView& surface, int su, int sv);
PieceBounds BoundPieceIn(const BSplineSurfaceView& surface, int su, int sv,
                         const PieceFrame& frame);

// NeededCells returns ceil(sqrt(m / (4 tolerance))), at least 1, as a
// double (it may be huge): with h = 1 / cells, h^2 m / 8 <= tolerance / 2.
double NeededCells(double m, double tolerance);

// NonEmptySpans returns the non-empty spans s (knots[s] < knots[s + 1]) of
// a domain [t_p, t_{count}].
std::vector<int> NonEmptySpans(absl::Span<const double> knots, int degree,
                               int count);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_MESHING_PIECE_BOUNDS_H_
