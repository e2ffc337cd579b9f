#include "freeform/core/tessellation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "base/homogeneous.h"
#include "base/tessellation_checks.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/subdivision.h"
#include "geometry/variant_dispatch.h"

namespace freeform {
namespace {

using internal::CheckResolvable;
using internal::TessellationTooLarge;
using internal::ValidateTolerance;

// The cancellation token is polled after this many subdivision steps.
constexpr size_t kStepsPerCancelCheck = 256;

// The layout of a Bezier piece's control points: degree + 1 points of
// `stride` values, the weight last when rational.
struct PieceShape {
  int degree = 0;
  int dimension = 0;
  bool rational = false;
  int stride() const { return dimension + (rational ? 1 : 0); }
  size_t size() const {
    return static_cast<size_t>(degree + 1) * static_cast<size_t>(stride());
  }
};

// DistanceToSegment returns the distance from p to the segment [a, b].
double DistanceToSegment(const double* p, const double* a, const double* b,
                         int dimension) {
  double ab2 = 0.0;
  double ap_ab = 0.0;
  for (int j = 0; j < dimension; ++j) {
    const double ab = b[j] - a[j];
    ab2 += ab * ab;
    ap_ab += (p[j] - a[j]) * ab;
  }
  const double s = ab2 > 0.0 ? std::clamp(ap_ab / ab2, 0.0, 1.0) : 0.0;
  double d2 = 0.0;
  for (int j = 0; j < dimension; ++j) {
    const double e = p[j] - (a[j] + s * (b[j] - a[j]));
    d2 += e * e;
  }
  return std::sqrt(d2);
}

// IsFlat reports whether every control point lies within `tolerance` of
// the chord (docs/references.md, 'Flatness test for curve tessellation').
// Rational pieces are projected first and are never flat while a weight is
// not positive (the convex hull property needs positive weights).
// `projected` is scratch.
bool IsFlat(const double* control, const PieceShape& shape, double tolerance,
            std::vector<double>& projected) {
  const int d = shape.dimension;
  if (shape.degree < 2) return true;
  const double* points = control;
  if (shape.rational) {
    projected.resize(static_cast<size_t>(shape.degree + 1) * d);
    for (int i = 0; i <= shape.degree; ++i) {
      if (!internal::ProjectPositive(
              control + static_cast<size_t>(i) * shape.stride(), d,
              projected.data() + static_cast<size_t>(i) * d)) {
        return false;
      }
    }
    points = projected.data();
  }
  const double* last = points + static_cast<size_t>(shape.degree) * d;
  for (int i = 1; i < shape.degree; ++i) {
    if (DistanceToSegment(points + static_cast<size_t>(i) * d, points, last,
                          d) > tolerance) {
      return false;
    }
  }
  return true;
}

// SplitInHalf writes the control points of the halves [0, 1/2] and
// [1/2, 1] of a (homogeneous) Bezier piece by de Casteljau.
void SplitInHalf(const double* control, const PieceShape& shape, double* left,
                 double* right, std::vector<double>& work) {
  const int n = shape.degree;
  const int s = shape.stride();
  work.assign(control, control + shape.size());
  for (int j = 0; j < s; ++j) {
    left[j] = work[j];
    right[static_cast<size_t>(n) * s + j] =
        work[static_cast<size_t>(n) * s + j];
  }
  for (int level = 1; level <= n; ++level) {
    for (int i = 0; i + level <= n; ++i) {
      for (int j = 0; j < s; ++j) {
        work[i * s + j] = 0.5 * (work[i * s + j] + work[(i + 1) * s + j]);
      }
    }
    for (int j = 0; j < s; ++j) {
      left[level * s + j] = work[j];
      right[(n - level) * s + j] = work[(n - level) * s + j];
    }
  }
}

// SubdivideBezierPiece appends to `parameters` the ends of the flat pieces
// of the Bezier piece `control` on the global interval [a, b], in order
// (a itself is not appended). Depth first, with a LIFO stack of control
// polygons in one buffer so nothing is allocated per piece.
absl::Status SubdivideBezierPiece(const double* control,
                                  const PieceShape& shape, double a, double b,
                                  double tolerance, size_t max_points,
                                  const CancellationToken* cancel,
                                  std::vector<double>& parameters) {
  struct Interval {
    double a;
    double b;
    int depth;
  };
  const size_t size = shape.size();
  std::vector<double> stack(control, control + size);
  std::vector<Interval> intervals = {{a, b, 0}};
  std::vector<double> projected, work, halves(2 * size);
  size_t steps = 0;
  while (!intervals.empty()) {
    if (++steps % kStepsPerCancelCheck == 0) {
      RETURN_IF_ERROR(CheckCancelled(cancel));
    }
    const Interval top = intervals.back();
    const double* piece = stack.data() + stack.size() - size;
    if (top.depth >= internal::kMaxSubdivisionDepth ||
        IsFlat(piece, shape, tolerance, projected)) {
      if (parameters.size() >= max_points)
        return TessellationTooLarge("tolerance", "points", max_points);
      parameters.push_back(top.b);
      intervals.pop_back();
      stack.resize(stack.size() - size);
      continue;
    }
    SplitInHalf(piece, shape, halves.data(), halves.data() + size, work);
    const double mid = 0.5 * (top.a + top.b);
    // Right half below the left one, so the left half is refined first.
    std::copy(halves.begin() + size, halves.end(), stack.end() - size);
    stack.insert(stack.end(), halves.begin(), halves.begin() + size);
    intervals.back() = {mid, top.b, top.depth + 1};
    intervals.push_back({top.a, mid, top.depth + 1});
  }
  return absl::OkStatus();
}

// ValidateCurveRequest checks the curve (`validation`, the status of its
// Validate* function), the tolerance and that a polyline (two points at
// least) fits in max_points.
absl::Status ValidateCurveRequest(const absl::Status& validation,
                                  double tolerance, size_t max_points) {
  if (!validation.ok()) return validation;
  RETURN_IF_ERROR(ValidateTolerance(tolerance));
  if (max_points < 2) {
    return TessellationTooLarge("tolerance", "points", max_points);
  }
  return absl::OkStatus();
}

// The control points of a Bezier piece or a B-spline ready to subdivide:
// their layout and their values, homogeneous (w P, w) when rational.
struct PieceControl {
  PieceShape shape;
  std::vector<double> values;
};

// ResolvableControl returns the control points of degree `degree` to
// subdivide, once the tolerance is known to be resolvable at their scale
// (CheckResolvable).
absl::StatusOr<PieceControl> ResolvableControl(const PointsView& points,
                                               absl::Span<const double> weights,
                                               int degree, double tolerance) {
  RETURN_IF_ERROR(CheckResolvable(tolerance, points.coordinates, degree));
  return PieceControl{.shape = {.degree = degree,
                                .dimension = points.dimension,
                                .rational = !weights.empty()},
                      .values = internal::LiftedValues(points, weights)};
}

// PolylineAt evaluates the points at `parameters` with `evaluate`.
template <typename Evaluate>
absl::StatusOr<Polyline> PolylineAt(int dimension,
                                    std::vector<double> parameters,
                                    Evaluate evaluate,
                                    const CancellationToken* cancel) {
  Polyline polyline;
  polyline.dimension = dimension;
  polyline.points.resize(parameters.size() * static_cast<size_t>(dimension));
  const std::vector<absl::Span<double>> output = {
      absl::MakeSpan(polyline.points)};
  ExecutionContext context;
  context.cancellation = cancel;
  RETURN_IF_ERROR(evaluate(parameters, output, context));
  polyline.parameters = std::move(parameters);
  return polyline;
}

// BlossomBezierPoints writes the Bezier control points of the non-empty
// span [u_s, u_{s+1}] of a B-spline with (homogeneous) control points
// `control` of `stride` values: point i is the blossom
// f(u_s^(p-i), u_{s+1}^i), by de Boor's algorithm with argument t_r at
// level r (The NURBS Book, section 5.1; de Boor, "A Practical Guide to
// Splines"). Works for clamped and unclamped knots.
void BlossomBezierPoints(const std::vector<double>& control, int stride, int p,
                         int s, absl::Span<const double> knots,
                         std::vector<double>& work, double* bezier) {
  for (int i = 0; i <= p; ++i) {
    work.assign(control.begin() + static_cast<size_t>(s - p) * stride,
                control.begin() + static_cast<size_t>(s + 1) * stride);
    for (int r = 1; r <= p; ++r) {
      const double t = r <= p - i ? knots[s] : knots[s + 1];
      for (int j = p; j >= r; --j) {
        const double lo = knots[s - p + j];
        const double alpha = (t - lo) / (knots[s + j - r + 1] - lo);
        for (int k = 0; k < stride; ++k) {
          work[j * stride + k] = (1.0 - alpha) * work[(j - 1) * stride + k] +
                                 alpha * work[j * stride + k];
        }
      }
    }
    std::copy(work.begin() + static_cast<size_t>(p) * stride, work.end(),
              bezier + static_cast<size_t>(i) * stride);
  }
}

}  // namespace

absl::StatusOr<Polyline> TessellateBezierCurve(
    const BezierCurveView& curve, double tolerance, size_t max_points,
    const CancellationToken* cancel) {
  RETURN_IF_ERROR(
      ValidateCurveRequest(ValidateBezierCurve(curve), tolerance, max_points));
  absl::StatusOr<PieceControl> control = ResolvableControl(
      curve.control_points, curve.weights, curve.degree(), tolerance);
  if (!control.ok()) return control.status();
  std::vector<double> parameters = {0.0};
  RETURN_IF_ERROR(SubdivideBezierPiece(control->values.data(), control->shape,
                                       0.0, 1.0, tolerance, max_points, cancel,
                                       parameters));
  return PolylineAt(
      control->shape.dimension, std::move(parameters),
      [&](absl::Span<const double> t, CurveOutput output,
          const ExecutionContext& context) {
        return EvaluateBezierCurve(curve, t, output, context);
      },
      cancel);
}

absl::StatusOr<Polyline> TessellateBSplineCurve(
    const BSplineCurveView& curve, double tolerance, size_t max_points,
    const CancellationToken* cancel) {
  RETURN_IF_ERROR(
      ValidateCurveRequest(ValidateBSplineCurve(curve), tolerance, max_points));
  const int p = curve.degree;
  absl::StatusOr<PieceControl> control =
      ResolvableControl(curve.control_points, curve.weights, p, tolerance);
  if (!control.ok()) return control.status();
  const PieceShape& shape = control->shape;
  const int n = static_cast<int>(curve.control_points.size()) - 1;
  std::vector<double> parameters = {curve.knots[p]};
  std::vector<double> bezier(shape.size()), work;
  for (int s = p; s <= n; ++s) {
    if (!(curve.knots[s] < curve.knots[s + 1])) continue;
    RETURN_IF_ERROR(CheckCancelled(cancel));
    BlossomBezierPoints(control->values, shape.stride(), p, s, curve.knots,
                        work, bezier.data());
    RETURN_IF_ERROR(SubdivideBezierPiece(bezier.data(), shape, curve.knots[s],
                                         curve.knots[s + 1], tolerance,
                                         max_points, cancel, parameters));
  }
  return PolylineAt(
      shape.dimension, std::move(parameters),
      [&](absl::Span<const double> t, CurveOutput output,
          const ExecutionContext& context) {
        return EvaluateBSplineCurve(curve, t, output, context);
      },
      cancel);
}

namespace {

// TessellatePieces refines the Bezier pieces of `curve` (DecomposeCurve) on
// their breakpoint intervals and evaluates the points on the curve.
absl::StatusOr<Polyline> TessellatePieces(const Curve& curve, double tolerance,
                                          size_t max_points,
                                          const CancellationToken* cancel) {
  RETURN_IF_ERROR(
      ValidateCurveRequest(absl::OkStatus(), tolerance, max_points));
  absl::StatusOr<BezierDecomposition> pieces = DecomposeCurve(curve, cancel);
  if (!pieces.ok()) return pieces.status();
  std::vector<double> parameters = {pieces->breakpoints.front()};
  for (size_t k = 0; k < pieces->segments.size(); ++k) {
    const BezierCurveView piece = pieces->segments[k].view();
    absl::StatusOr<PieceControl> control = ResolvableControl(
        piece.control_points, piece.weights, piece.degree(), tolerance);
    if (!control.ok()) return control.status();
    RETURN_IF_ERROR(SubdivideBezierPiece(
        control->values.data(), control->shape, pieces->breakpoints[k],
        pieces->breakpoints[k + 1], tolerance, max_points, cancel, parameters));
  }
  return PolylineAt(
      DimensionOf(curve), std::move(parameters),
      [&](absl::Span<const double> t, CurveOutput output,
          const ExecutionContext& context) {
        return EvaluateCurve(curve, t, output, context);
      },
      cancel);
}

}  // namespace

absl::StatusOr<Polyline> TessellateCurve(const Curve& curve, double tolerance,
                                         size_t max_points,
                                         const CancellationToken* cancel) {
  return std::visit(
      internal::Overloaded{[&](const BezierCurve& bezier) {
                             return TessellateBezierCurve(
                                 bezier.view(), tolerance, max_points, cancel);
                           },
                           [&](const BSplineCurve& bspline) {
                             return TessellateBSplineCurve(
                                 bspline.view(), tolerance, max_points, cancel);
                           },
                           [&](const auto&) {
                             return TessellatePieces(curve, tolerance,
                                                     max_points, cancel);
                           }},
      curve);
}

}  // namespace freeform
