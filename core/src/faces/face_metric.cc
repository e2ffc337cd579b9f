// FaceMetric (face_metric.h): the planner's span-rectangle bounds in one
// frame, and the smallest enclosing circle of a scaled triangle.
#include "faces/face_metric.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "meshing/piece_bounds.h"

namespace freeform::internal {
namespace {

// A and B are raised to this fraction of the larger (face_mesh.h).
constexpr double kMetricFloor = 0.01;

// C0Lines returns the interior knots of multiplicity at least `degree`,
// where the homogeneous surface may be only C0.
std::vector<double> C0Lines(absl::Span<const double> knots, int degree,
                            const std::vector<int>& spans) {
  std::vector<double> lines;
  for (size_t k = 1; k < spans.size(); ++k) {
    const double knot = knots[static_cast<size_t>(spans[k])];
    if (std::count(knots.begin(), knots.end(), knot) >= degree) {
      lines.push_back(knot);
    }
  }
  return lines;
}

// FirstInside returns the first line strictly inside (lo, hi).
std::optional<double> FirstInside(const std::vector<double>& lines, double lo,
                                  double hi) {
  const auto it = std::upper_bound(lines.begin(), lines.end(), lo);
  if (it != lines.end() && *it < hi) return *it;
  return std::nullopt;
}

absl::Status CheckMeshableNet(const BSplineSurfaceView& view) {
  if (view.control_net.dimension != 3) {
    return InvalidFieldError("surface", "must be 3D to be meshed");
  }
  for (const double w : view.weights) {
    if (!(w > 0.0)) {
      return InvalidFieldError("surface",
                               "weights must be positive to be meshed");
    }
  }
  return absl::OkStatus();
}

// Breakpoints returns the starts of the spans and the end of the last.
std::vector<double> Breakpoints(absl::Span<const double> knots,
                                const std::vector<int>& spans) {
  std::vector<double> breaks;
  for (const int s : spans) breaks.push_back(knots[static_cast<size_t>(s)]);
  breaks.push_back(knots[static_cast<size_t>(spans.back() + 1)]);
  return breaks;
}

// SpanRange returns the first and last span of `breaks` meeting [lo, hi].
std::array<size_t, 2> SpanRange(const std::vector<double>& breaks, double lo,
                                double hi) {
  const size_t last_span = breaks.size() - 2;
  const auto first = std::upper_bound(breaks.begin(), breaks.end(), lo);
  const auto last = std::lower_bound(breaks.begin(), breaks.end(), hi);
  const size_t i0 = static_cast<size_t>(
      std::max<std::ptrdiff_t>(0, first - breaks.begin() - 1));
  const size_t i1 = static_cast<size_t>(
      std::max<std::ptrdiff_t>(0, last - breaks.begin() - 1));
  return {std::min(i0, last_span), std::min(std::max(i0, i1), last_span)};
}

double Squared(double x) { return x * x; }

// Floored raises A and B to kMetricFloor of the larger.
MetricWeights Floored(MetricWeights weights) {
  const double floor = kMetricFloor * std::max(weights.a, weights.b);
  return {std::max(weights.a, floor), std::max(weights.b, floor)};
}

}  // namespace

absl::StatusOr<FaceMetric> FaceMetric::Create(const Surface& surface) {
  absl::StatusOr<TensorForm> form = TensorFormOf(surface);
  if (!form.ok()) return form.status();
  const BSplineSurfaceView view = form->view();
  RETURN_IF_ERROR(CheckMeshableNet(view));
  const std::vector<int> spans_u =
      NonEmptySpans(view.knots_u, view.degree_u, view.control_net.count_u);
  const std::vector<int> spans_v =
      NonEmptySpans(view.knots_v, view.degree_v, view.control_net.count_v);
  FaceMetric metric;
  metric.c0_u_ = C0Lines(view.knots_u, view.degree_u, spans_u);
  metric.c0_v_ = C0Lines(view.knots_v, view.degree_v, spans_v);
  metric.rational_ = view.rational();
  metric.breaks_u_ = Breakpoints(view.knots_u, spans_u);
  metric.breaks_v_ = Breakpoints(view.knots_v, spans_v);
  const PieceFrame frame = NetFrame(view);
  for (size_t i = 0; i < spans_u.size(); ++i) {
    const double du = metric.breaks_u_[i + 1] - metric.breaks_u_[i];
    for (size_t j = 0; j < spans_v.size(); ++j) {
      const double dv = metric.breaks_v_[j + 1] - metric.breaks_v_[j];
      const PieceBounds bounds =
          BoundPieceIn(view, spans_u[i], spans_v[j], frame);
      if (!(std::isfinite(bounds.uu) && std::isfinite(bounds.uv) &&
            std::isfinite(bounds.vv))) {
        return InvalidFieldError(
            "surface",
            "its second partials have no finite bound from the "
            "control points");
      }
      metric.second_.push_back({bounds.uu / (du * du), bounds.uv / (du * dv),
                                bounds.vv / (dv * dv)});
      // One rectangle alone: the planner's frame of its active points.
      const PieceBounds own = BoundPiece(view, spans_u[i], spans_v[j]);
      metric.own_second_.push_back(
          {own.uu / (du * du), own.uv / (du * dv), own.vv / (dv * dv)});
    }
  }
  return metric;
}

MetricWeights FaceMetric::WeightsOver(double u0, double u1, double v0,
                                      double v1) const {
  const std::array<size_t, 2> range_u = SpanRange(breaks_u_, u0, u1);
  const std::array<size_t, 2> range_v = SpanRange(breaks_v_, v0, v1);
  MetricWeights weights;
  if (range_u[0] == range_u[1] && range_v[0] == range_v[1]) {
    const std::array<double, 3>& m =
        own_second_[range_u[0] * (breaks_v_.size() - 1) + range_v[0]];
    return Floored({m[0] + m[1], m[2] + m[1]});
  }
  for (size_t i = range_u[0]; i <= range_u[1]; ++i) {
    for (size_t j = range_v[0]; j <= range_v[1]; ++j) {
      const std::array<double, 3>& m = second(i, j);
      const double a = m[0] + m[1], b = m[2] + m[1];
      if (rational_) {
        weights.a += a;
        weights.b += b;
      } else {
        weights.a = std::max(weights.a, a);
        weights.b = std::max(weights.b, b);
      }
    }
  }
  return Floored(weights);
}

std::optional<KnotLine> FaceMetric::StraddledLine(double u0, double u1,
                                                  double v0, double v1) const {
  if (const std::optional<double> u = FirstInside(c0_u_, u0, u1)) {
    return KnotLine{.in_u = true, .value = *u};
  }
  if (const std::optional<double> v = FirstInside(c0_v_, v0, v1)) {
    return KnotLine{.in_u = false, .value = *v};
  }
  return std::nullopt;
}

double FaceMetric::TriangleBound(
    const std::array<freeform::Point2, 3>& corners) const {
  double u0 = corners[0].x, u1 = u0, v0 = corners[0].y, v1 = v0;
  for (const freeform::Point2& p : corners) {
    u0 = std::min(u0, p.x);
    u1 = std::max(u1, p.x);
    v0 = std::min(v0, p.y);
    v1 = std::max(v1, p.y);
  }
  // Across a C0 line the Taylor argument fails: no bound.
  if (StraddledLine(u0, u1, v0, v1).has_value()) return INFINITY;
  const MetricWeights w = WeightsOver(u0, u1, v0, v1);
  const double su = std::sqrt(w.a), sv = std::sqrt(w.b);
  std::array<std::array<double, 2>, 3> p;
  for (int k = 0; k < 3; ++k) p[k] = {su * corners[k].x, sv * corners[k].y};
  // Squared edge lengths, edge k opposite corner k.
  std::array<double, 3> edge2;
  for (int k = 0; k < 3; ++k) {
    const auto& a = p[(k + 1) % 3];
    const auto& b = p[(k + 2) % 3];
    edge2[k] = Squared(a[0] - b[0]) + Squared(a[1] - b[1]);
  }
  const double longest2 = std::max({edge2[0], edge2[1], edge2[2]});
  // Not acute (the longest edge's square at least the sum of the others'):
  // the circle on the longest edge encloses the triangle.
  if (2 * longest2 >= edge2[0] + edge2[1] + edge2[2]) return longest2 / 8;
  const double cross = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) -
                       (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
  // Circumradius^2 = a^2 b^2 c^2 / (4 area)^2 = a^2 b^2 c^2 / (2 cross)^2.
  const double radius2 = edge2[0] * edge2[1] * edge2[2] / (4 * cross * cross);
  return radius2 / 2;
}

double FaceMetric::SegmentBound(freeform::Point2 a, freeform::Point2 b) const {
  const MetricWeights w = WeightsOver(std::min(a.x, b.x), std::max(a.x, b.x),
                                      std::min(a.y, b.y), std::max(a.y, b.y));
  return (w.a * Squared(a.x - b.x) + w.b * Squared(a.y - b.y)) / 8;
}

}  // namespace freeform::internal
