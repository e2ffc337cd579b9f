// The orientation and nesting rules of a face's loops (trim_validation.h):
// signed areas by Green's theorem, and the winding number of every hole's
// point about the other loops.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "faces/quadrature.h"
#include "faces/trim_validation.h"
#include "faces/winding.h"
#include "freeform/core/arc_length.h"
#include "freeform/core/bezier.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"

namespace freeform::internal {
namespace {

// The most intervals of the adaptive rule on one rational piece.
constexpr size_t kMaxAreaIntervals = 1024;

// PieceSignedArea returns the integral of u v' dt over a piece: exact by
// Gauss-Legendre with degree + 1 points for a polynomial piece (u v' has
// degree 2 n - 1), adaptive Gauss-Kronrod to 1e-15 of the piece's extent
// squared for a rational one.
double PieceSignedArea(const BezierCurveData& bezier) {
  const BezierPointEvaluator evaluator(bezier.view(), 1);
  std::vector<double> scratch(evaluator.scratch_size());
  double derivatives[4];
  const auto u_dv = [&](double t) {
    evaluator.Evaluate(t, scratch.data(), derivatives);
    return derivatives[0] * derivatives[3];
  };
  const int degree = static_cast<int>(bezier.coordinates.size() / 2) - 1;
  if (degree < 1) return 0.0;
  if (bezier.weights.empty()) {
    std::vector<double> nodes(degree + 1), weights(degree + 1);
    GaussLegendreRule(degree + 1, absl::MakeSpan(nodes),
                      absl::MakeSpan(weights));
    double sum = 0.0;
    for (int k = 0; k <= degree; ++k) {
      sum += weights[k] * u_dv(0.5 * (1.0 + nodes[k]));
    }
    return 0.5 * sum;
  }
  double extent = 0.0;
  for (const double c : bezier.coordinates)
    extent = std::max(extent, std::abs(c));
  const auto integrand = [&](size_t, double a, double b, Estimate* values) {
    for (int k = 0; k < kKronrodPoints; ++k) {
      values[k] = {.value = u_dv(KronrodNode(a, b, k)), .error = 0.0};
    }
    return absl::OkStatus();
  };
  absl::StatusOr<Estimate> area = IntegrateAdaptive(
      integrand, 0.0, 1.0, 1e-15 * std::max(extent * extent, 1e-300),
      kMaxAreaIntervals, nullptr);
  return area.ok() ? area->value : 0.0;
}

// HoleWithin checks one hole: the winding number of the other loops about
// one of its points is 1 (inside the outer loop, in no other hole).
absl::Status CheckHoleContainment(const FaceBoundary& boundary, int index) {
  const BoundaryLoop& hole = boundary.loops[index];
  for (int k = 0; k < hole.piece_count; ++k) {
    const Point2& p = boundary.pieces[hole.first_piece + k].first;
    const WindingAt around = FaceWinding(boundary, p, 0.0, index);
    if (around.on_boundary) continue;  // Try another point of the hole.
    if (around.winding == 1) return absl::OkStatus();
    if (LoopWinding(boundary, 0, p, 0.0).winding == 0) {
      return InvalidFieldError(
          hole.path,
          absl::StrCat("lies outside the ",
                       !boundary.loops[0].is_domain ? "outer loop"
                                                    : "parameter rectangle",
                       ": holes must lie inside it"));
    }
    for (size_t other = 1; other < boundary.loops.size(); ++other) {
      if (static_cast<int>(other) == index) continue;
      if (LoopWinding(boundary, static_cast<int>(other), p, 0.0).winding != 0) {
        return InvalidFieldError(
            hole.path, absl::StrCat("lies inside ", boundary.loops[other].path,
                                    ": holes must not be nested"));
      }
    }
    return InvalidFieldError(hole.path, "is not inside the face's outer loop");
  }
  return InvalidFieldError(hole.path,
                           "touches another loop at every piece's start");
}

}  // namespace

double LoopSignedArea(const FaceBoundary& boundary, int loop) {
  const BoundaryLoop& l = boundary.loops[loop];
  double area = 0.0;
  for (int k = 0; k < l.piece_count; ++k) {
    area += PieceSignedArea(boundary.pieces[l.first_piece + k].bezier);
  }
  return area;
}

absl::Status CheckOrientation(const FaceBoundary& boundary) {
  for (size_t l = 0; l < boundary.loops.size(); ++l) {
    const BoundaryLoop& loop = boundary.loops[l];
    const double area = LoopSignedArea(boundary, static_cast<int>(l));
    if (!loop.hole && !(area > 0.0)) {
      return InvalidFieldError(
          loop.path, absl::StrCat("runs clockwise (signed area ", area,
                                  " in (u, v)): the outer loop must run "
                                  "counter-clockwise"));
    }
    if (loop.hole && !(area < 0.0)) {
      return InvalidFieldError(
          loop.path, absl::StrCat("runs counter-clockwise (signed area ", area,
                                  " in (u, v)): holes must run clockwise"));
    }
  }
  return absl::OkStatus();
}

absl::Status CheckContainment(const FaceBoundary& boundary,
                              const CancellationToken* cancel) {
  CancellationPoll poll(cancel);
  for (size_t l = 1; l < boundary.loops.size(); ++l) {
    RETURN_IF_ERROR(CheckHoleContainment(boundary, static_cast<int>(l)));
    RETURN_IF_ERROR(poll.Done(64));
  }
  return absl::OkStatus();
}

}  // namespace freeform::internal
