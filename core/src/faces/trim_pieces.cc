// Cutting a face's loops into 2D Bezier pieces (face_boundary.h).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "faces/face_boundary.h"
#include "freeform/core/saturating.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"

namespace freeform::internal {
namespace {

// The domain rectangle's four edges, counter-clockwise from (u0, v0).
std::vector<BezierCurveData> DomainEdges(const SurfaceDomain& d) {
  const Point2 corners[5] = {{d.u_start, d.v_start},
                             {d.u_end, d.v_start},
                             {d.u_end, d.v_end},
                             {d.u_start, d.v_end},
                             {d.u_start, d.v_start}};
  std::vector<BezierCurveData> edges;
  for (int k = 0; k < 4; ++k) {
    edges.push_back({.dimension = 2,
                     .coordinates = {corners[k][0], corners[k][1],
                                     corners[k + 1][0], corners[k + 1][1]},
                     .weights = {}});
  }
  return edges;
}

// MakePiece completes a piece's end points and degeneracy; fails when an
// end weight is 0 (a point at infinity cannot lie in the domain).
absl::StatusOr<TrimPiece> MakePiece(BezierCurveData bezier, int loop, int curve,
                                    double start, double end, double tolerance,
                                    absl::string_view path) {
  if (!bezier.weights.empty() &&
      !(bezier.weights.front() > 0.0 && bezier.weights.back() > 0.0)) {
    return InvalidFieldError(
        path, "reaches a point at infinity (a weight of 0 at a piece end)");
  }
  TrimPiece piece{.bezier = std::move(bezier),
                  .loop = loop,
                  .curve = curve,
                  .start = start,
                  .end = end};
  const std::vector<double>& c = piece.bezier.coordinates;
  piece.first = {c[0], c[1]};
  piece.last = {c[c.size() - 2], c[c.size() - 1]};
  piece.degenerate =
      ControlBox(piece.bezier.coordinates).Diagonal() <= tolerance;
  return piece;
}

// AddLoopPieces decomposes the curves of one loop into boundary->pieces.
absl::Status AddLoopPieces(const TrimLoop& loop, int loop_index,
                           FaceBoundary* boundary,
                           const CancellationToken* cancel) {
  const std::string& path = boundary->loops[loop_index].path;
  if (loop.curves.empty()) {
    return InvalidFieldError(absl::StrCat(path, ".curves"),
                             "a loop needs at least one curve");
  }
  for (size_t j = 0; j < loop.curves.size(); ++j) {
    const std::string curve_path =
        IndexedField(absl::StrCat(path, ".curves"), j);
    const Curve& curve = loop.curves[j];
    if (DimensionOf(curve) != 2) {
      return InvalidFieldError(
          curve_path, absl::StrCat("a trim curve must be 2D (u, v), not of "
                                   "dimension ",
                                   DimensionOf(curve)));
    }
    ASSIGN_OR_RETURN(BezierDecomposition decomposition,
                     DecomposeCurve(curve, cancel));
    for (size_t k = 0; k < decomposition.segments.size(); ++k) {
      ASSIGN_OR_RETURN(
          TrimPiece piece,
          MakePiece(std::move(decomposition.segments[k]), loop_index,
                    static_cast<int>(j), decomposition.breakpoints[k],
                    decomposition.breakpoints[k + 1], boundary->tolerance,
                    curve_path));
      boundary->pieces.push_back(std::move(piece));
    }
  }
  return absl::OkStatus();
}

// CheckPieceCount refuses loops with more Bezier pieces than
// kMaxFaceTrimPieces, before any is cut.
absl::Status CheckPieceCount(const TrimmedSurfaceParts& parts) {
  uint64_t pieces = 0;
  const auto count = [&pieces](const TrimLoop& loop) {
    for (const Curve& curve : loop.curves) {
      pieces = SaturatingSum(pieces, DecomposedCurvePieces(curve));
    }
  };
  if (parts.outer.has_value()) count(*parts.outer);
  for (const TrimLoop& hole : parts.holes) count(hole);
  if (pieces <= kMaxFaceTrimPieces) return absl::OkStatus();
  return ExhaustedFieldError(
      parts.holes.empty() ? "outer" : "holes",
      absl::StrCat("the loops have ", pieces, " Bezier pieces, more than ",
                   kMaxFaceTrimPieces));
}

}  // namespace

absl::Status BuildTrimPieces(const TrimmedSurfaceParts& parts,
                             FaceBoundary* boundary,
                             const CancellationToken* cancel) {
  RETURN_IF_ERROR(CheckPieceCount(parts));
  const auto start_loop = [boundary](std::string path, bool hole) {
    boundary->loops.push_back(
        {.path = std::move(path),
         .hole = hole,
         .first_piece = static_cast<int>(boundary->pieces.size())});
    return static_cast<int>(boundary->loops.size()) - 1;
  };
  const auto end_loop = [boundary](int index) {
    BoundaryLoop& loop = boundary->loops[index];
    loop.piece_count =
        static_cast<int>(boundary->pieces.size()) - loop.first_piece;
  };
  if (parts.outer.has_value()) {
    const int index = start_loop("outer", false);
    RETURN_IF_ERROR(AddLoopPieces(*parts.outer, index, boundary, cancel));
    end_loop(index);
  } else {
    const int index = start_loop("domain", false);
    boundary->loops[index].is_domain = true;
    int edge = 0;
    for (BezierCurveData& bezier : DomainEdges(boundary->domain)) {
      ASSIGN_OR_RETURN(
          TrimPiece piece,
          MakePiece(std::move(bezier), index, edge, 0.0, 1.0, 0.0, "domain"));
      boundary->pieces.push_back(std::move(piece));
      ++edge;
    }
    end_loop(index);
  }
  for (size_t i = 0; i < parts.holes.size(); ++i) {
    const int index = start_loop(IndexedField("holes", i), true);
    RETURN_IF_ERROR(AddLoopPieces(parts.holes[i], index, boundary, cancel));
    end_loop(index);
    RETURN_IF_ERROR(CheckCancelled(cancel));
  }
  return absl::OkStatus();
}

std::string CurvePath(const FaceBoundary& boundary, const TrimPiece& piece) {
  return IndexedField(absl::StrCat(boundary.loops[piece.loop].path, ".curves"),
                      piece.curve);
}

Curve PieceCurve(const BezierCurveData& bezier) {
  // The piece came out of a valid curve's decomposition: it is valid.
  return *BezierCurve::Create(bezier.view());
}

}  // namespace freeform::internal
