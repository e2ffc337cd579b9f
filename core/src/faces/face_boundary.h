// The precomputed boundary of a trimmed face (trimmed_surface.h): every
// loop cut into 2D Bezier pieces, a certified polyline per loop, and a
// uniform grid of the polylines' segments over the parameter rectangle.
// Built once by TrimmedSurface::Create, read-only afterwards (thread-safe).
// Internal to the core.
#ifndef FREEFORM_CORE_SRC_FACES_FACE_BOUNDARY_H_
#define FREEFORM_CORE_SRC_FACES_FACE_BOUNDARY_H_

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "faces/plane_geometry.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/geometry_data.h"
#include "freeform/core/tensor_surface.h"
#include "freeform/core/trimmed_surface.h"

namespace freeform::internal {

// One Bezier piece of a trim curve: curve `curve` of loop `loop` on
// [start, end] of the curve's own parameter, reparameterized to [0, 1].
struct TrimPiece {
  BezierCurveData bezier;
  int loop = 0;
  int curve = 0;
  double start = 0.0;
  double end = 1.0;
  // All control points equal: a zero-length piece, skipped.
  bool degenerate = false;
  Point2 first{};  // the piece's point at 0
  Point2 last{};   // the piece's point at 1
};

// A loop: its pieces are pieces[first_piece .. first_piece + piece_count).
struct BoundaryLoop {
  // "outer", "holes[i]", or "domain" for the parameter rectangle of a face
  // without an outer loop.
  std::string path;
  bool hole = false;
  // The parameter rectangle: trims may touch it (they are inside it by
  // CheckInsideDomain), so it takes no part in CheckCrossings.
  bool is_domain = false;
  int first_piece = 0;
  int piece_count = 0;
  // Its segments are segments[first_segment .. first_segment +
  // segment_count).
  uint32_t first_segment = 0;
  uint32_t segment_count = 0;
  // The polyline's Hausdorff distance bound to the loop.
  double epsilon = 0.0;
  // The box of the polyline widened by epsilon: it holds the loop, whose
  // winding number about a point outside it is 0.
  Box2 box;
};

// A chord of a loop's polyline. A chord of piece `piece` joins its points
// at the piece parameters s0 < s1 and lies within `epsilon` of the arc
// between them; a chord with piece -1 closes the gap between two pieces
// (exact, epsilon 0).
struct BoundarySegment {
  Point2 a{};
  Point2 b{};
  double s0 = 0.0;
  double s1 = 0.0;
  double epsilon = 0.0;
  int32_t piece = -1;
  int32_t loop = 0;
};

// A uniform grid over a rectangle: cells for segments near a point, rows
// for the segments a ray along +u from it may cross.
struct SegmentGrid {
  double u_start = 0.0;
  double v_start = 0.0;
  double cell_u = 1.0;
  double cell_v = 1.0;
  int columns = 1;
  int rows = 1;
  // The segments of cell (i, j) (column i, row j) are
  // cell_segments[cell_start[j * columns + i] .. cell_start[... + 1]):
  // those whose box, widened by their epsilon, meets the cell.
  std::vector<uint32_t> cell_start;
  std::vector<uint32_t> cell_segments;
  // The segments whose v-range meets row j, grouped by loop, in two
  // orders: rightward[row_start[j] .. row_start[j + 1]) by their largest u,
  // descending within a loop (a ray along +u from u needs those reaching
  // past u, a prefix), leftward by their smallest u, ascending (for a ray
  // along -u).
  std::vector<uint32_t> row_start;
  std::vector<uint32_t> rightward;
  std::vector<uint32_t> leftward;
  // The loops of row j: runs[run_start[j] .. run_start[j + 1]), each the
  // positions [begin, end) of one loop's segments in both orders.
  struct Run {
    int32_t loop;
    uint32_t begin;
    uint32_t end;
  };
  std::vector<uint32_t> run_start;
  std::vector<Run> runs;

  int Column(double u) const;
  int Row(double v) const;
};

struct FaceBoundary {
  SurfaceDomain domain;
  double tolerance = 0.0;
  // The outer loop (or the domain rectangle) first, then the holes.
  std::vector<BoundaryLoop> loops;
  std::vector<TrimPiece> pieces;
  std::vector<BoundarySegment> segments;
  SegmentGrid grid;
};

// BuildTrimPieces fills boundary->loops and ->pieces from the face's loops
// (the domain rectangle's four edges first when there is no outer loop),
// checking that every curve is 2D and the piece count. Fails with
// INVALID_ARGUMENT naming "<loop>.curves" or "<loop>.curves[j]",
// RESOURCE_EXHAUSTED, and the token's status.
absl::Status BuildTrimPieces(const TrimmedSurfaceParts& parts,
                             FaceBoundary* boundary,
                             const CancellationToken* cancel);

// BuildBoundaryPolylines tessellates every loop (epsilon: the larger of the
// face's tolerance and 2^-10 of the loop's extent) into boundary->segments
// and builds the grid. Fails with RESOURCE_EXHAUSTED and the token's
// status.
absl::Status BuildBoundaryPolylines(FaceBoundary* boundary,
                                    const CancellationToken* cancel);

// BoundaryPolylineBytes returns an upper bound of the memory
// BuildBoundaryPolylines adds to a boundary whose pieces are built (the
// polylines and the grid), or its RESOURCE_EXHAUSTED.
absl::StatusOr<uint64_t> BoundaryPolylineBytes(const FaceBoundary& boundary);

// CurvePath returns "<loop path>.curves[j]" of a piece's curve.
std::string CurvePath(const FaceBoundary& boundary, const TrimPiece& piece);

// PieceBezierCurve returns a piece as a Curve (a view of its data).
Curve PieceCurve(const BezierCurveData& bezier);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_FACES_FACE_BOUNDARY_H_
