// The closure, resolution and domain rules of a face's trims
// (trim_validation.h).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "faces/trim_validation.h"
#include "freeform/core/status.h"
#include "freeform/core/subdivision.h"

namespace freeform::internal {
namespace {

// The deepest halving of a piece whose hull pokes out of the domain.
constexpr int kMaxDomainDepth = 48;

// The domain widened by the tolerance.
struct Box {
  double lo[2];
  double hi[2];

  // Excess returns how far `p` lies outside the box (0 inside).
  double Excess(const double* p) const {
    double excess = 0.0;
    for (int j = 0; j < 2; ++j) {
      excess = std::max({excess, lo[j] - p[j], p[j] - hi[j]});
    }
    return excess;
  }
};

// HullInside reports whether every control point lies in the box and, for
// a rational piece, every weight is positive (the hull property).
bool HullInside(const BezierCurveData& bezier, const Box& box) {
  if (!HasHull(bezier.weights)) return false;
  for (size_t i = 0; i + 1 < bezier.coordinates.size(); i += 2) {
    if (box.Excess(&bezier.coordinates[i]) > 0.0) return false;
  }
  return true;
}

// CheckPieceInside halves `bezier` until each part's hull lies in the box,
// failing at an end point (on the curve) outside it, or at the depth limit.
absl::Status CheckPieceInside(const BezierCurveData& bezier, const Box& box,
                              int depth, const FaceBoundary& boundary,
                              const TrimPiece& piece) {
  if (HullInside(bezier, box)) return absl::OkStatus();
  const std::vector<double>& c = bezier.coordinates;
  const bool ends_positive =
      bezier.weights.empty() ||
      (bezier.weights.front() > 0.0 && bezier.weights.back() > 0.0);
  for (const double* end : {&c[0], &c[c.size() - 2]}) {
    const double excess = box.Excess(end);
    if ((ends_positive && excess > 0.0) || depth >= kMaxDomainDepth) {
      const SurfaceDomain& domain = boundary.domain;
      return InvalidFieldError(
          CurvePath(boundary, piece),
          absl::StrCat("leaves the surface's parameter rectangle [",
                       domain.u_start, ", ", domain.u_end, "] x [",
                       domain.v_start, ", ", domain.v_end, "] by ", excess,
                       " beyond the tolerance at (u, v) = (", end[0], ", ",
                       end[1], ")"));
    }
  }
  const double half[] = {0.5};
  absl::StatusOr<std::vector<BezierCurveData>> halves =
      SplitBezierCurve(bezier.view(), half);
  if (!halves.ok()) return halves.status();
  for (const BezierCurveData& part : *halves) {
    if (absl::Status status =
            CheckPieceInside(part, box, depth + 1, boundary, piece);
        !status.ok()) {
      return status;
    }
  }
  return absl::OkStatus();
}

}  // namespace

absl::Status CheckTrimResolution(const FaceBoundary& boundary) {
  double size = 0.0;
  for (const TrimPiece& piece : boundary.pieces) {
    for (const double c : piece.bezier.coordinates) {
      size = std::max(size, std::abs(c));
    }
  }
  if (boundary.tolerance >= 0x1p-46 * size) return absl::OkStatus();
  return InvalidFieldError(
      "tolerance",
      absl::StrCat(boundary.tolerance,
                   " is below what double precision resolves on trims of "
                   "size ",
                   size, " (2^-46 of it)"));
}

absl::Status CheckClosure(const FaceBoundary& boundary) {
  for (const BoundaryLoop& loop : boundary.loops) {
    for (int k = 0; k < loop.piece_count; ++k) {
      const TrimPiece& piece = boundary.pieces[loop.first_piece + k];
      const TrimPiece& before =
          boundary.pieces[loop.first_piece +
                          (k + loop.piece_count - 1) % loop.piece_count];
      const double gap = std::hypot(piece.first[0] - before.last[0],
                                    piece.first[1] - before.last[1]);
      if (gap <= boundary.tolerance) continue;
      return InvalidFieldError(
          CurvePath(boundary, piece),
          absl::StrCat("the loop is open: this curve starts ", gap,
                       " from the end of curves[", before.curve,
                       "], more than the tolerance ", boundary.tolerance));
    }
  }
  return absl::OkStatus();
}

absl::Status CheckInsideDomain(const FaceBoundary& boundary,
                               const CancellationToken* cancel) {
  const SurfaceDomain& d = boundary.domain;
  const double t = boundary.tolerance;
  const Box box{{d.u_start - t, d.v_start - t}, {d.u_end + t, d.v_end + t}};
  CancellationPoll poll(cancel);
  for (const TrimPiece& piece : boundary.pieces) {
    if (absl::Status status =
            CheckPieceInside(piece.bezier, box, 0, boundary, piece);
        !status.ok()) {
      return status;
    }
    if (absl::Status status = poll.Done(piece.bezier.coordinates.size());
        !status.ok()) {
      return status;
    }
  }
  return absl::OkStatus();
}

}  // namespace freeform::internal
