// The boundary samples and interior grid of TessellateFace
// (face_mesh_parts.h).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "absl/functional/function_ref.h"
#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "faces/face_mesh_parts.h"
#include "freeform/core/curve.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "meshing/piece_bounds.h"

namespace freeform::internal {
namespace {

// A chord is halved at most this often.
constexpr int kMaxChordDepth = 40;
// Interior nodes this close to the boundary, in grid spacings, are dropped.
constexpr double kBoundaryGap = 0.3;

using PointAt = absl::FunctionRef<absl::StatusOr<freeform::Point2>(double)>;

// Bisection steps for a chord's crossing of a C0 line.
constexpr int kCrossingSteps = 64;

struct Crossing {
  double t = 0.0;
  freeform::Point2 point;
};

double Across(const freeform::Point2& p, const KnotLine& line) {
  return (line.in_u ? p.x : p.y) - line.value;
}

// CrossingOf returns a point of the curve between t0 and t1 (whose ends
// lie strictly on either side of the line) on the line, by bisection, its
// coordinate set to the line's.
absl::StatusOr<Crossing> CrossingOf(PointAt point_at, double t0,
                                    freeform::Point2 p0, double t1,
                                    const KnotLine& line) {
  const bool below = Across(p0, line) < 0.0;
  double lo = t0, hi = t1;
  for (int step = 0; step < kCrossingSteps; ++step) {
    const double mid = 0.5 * (lo + hi);
    ASSIGN_OR_RETURN(const freeform::Point2 p, point_at(mid));
    ((Across(p, line) < 0.0) == below ? lo : hi) = mid;
  }
  Crossing crossing{.t = 0.5 * (lo + hi)};
  ASSIGN_OR_RETURN(crossing.point, point_at(crossing.t));
  (line.in_u ? crossing.point.x : crossing.point.y) = line.value;
  return crossing;
}

// LoopBuilder collects one closed chain of points.
class LoopBuilder {
 public:
  LoopBuilder(const FaceMetric& metric, double chord_bound,
              const SurfaceDomain& domain, size_t max_points)
      : metric_(metric),
        chord_bound_(chord_bound),
        domain_(domain),
        max_points_(max_points) {}

  // AddChord appends the start of the chord from (t0, p0) to (t1, p1) and
  // the points that halve it until every part meets the bound.
  absl::Status AddChord(PointAt point_at, double t0, freeform::Point2 p0,
                        double t1, freeform::Point2 p1, int depth = 0) {
    if (depth == 0) Append(p0);
    if (const std::optional<KnotLine> line =
            metric_.StraddledLine(std::min(p0.x, p1.x), std::max(p0.x, p1.x),
                                  std::min(p0.y, p1.y), std::max(p0.y, p1.y))) {
      // Split at a crossing of the C0 line, so no chord (and no triangle
      // on it) lies across the line.
      ASSIGN_OR_RETURN(const Crossing crossing,
                       CrossingOf(point_at, t0, p0, t1, *line));
      RETURN_IF_ERROR(
          AddChord(point_at, t0, p0, crossing.t, crossing.point, depth + 1));
      Append(crossing.point);
      return AddChord(point_at, crossing.t, crossing.point, t1, p1, depth + 1);
    }
    if (depth >= kMaxChordDepth ||
        metric_.SegmentBound(p0, p1) <= chord_bound_) {
      return absl::OkStatus();
    }
    if (points_.size() >= max_points_) return TooManyVertices(max_points_);
    const double tm = 0.5 * (t0 + t1);
    ASSIGN_OR_RETURN(const freeform::Point2 pm, point_at(tm));
    RETURN_IF_ERROR(AddChord(point_at, t0, p0, tm, pm, depth + 1));
    Append(pm);
    return AddChord(point_at, tm, pm, t1, p1, depth + 1);
  }

  // Finish returns the chain, without a last point equal to the first.
  std::vector<freeform::Point2> Finish() {
    while (points_.size() > 1 && points_.back() == points_.front()) {
      points_.pop_back();
    }
    return std::move(points_);
  }

 private:
  void Append(freeform::Point2 p) {
    p.x = std::clamp(p.x, domain_.u_start, domain_.u_end);
    p.y = std::clamp(p.y, domain_.v_start, domain_.v_end);
    if (points_.empty() || !(points_.back() == p)) points_.push_back(p);
  }

  const FaceMetric& metric_;
  double chord_bound_;
  SurfaceDomain domain_;
  size_t max_points_;
  std::vector<freeform::Point2> points_;
};

absl::StatusOr<freeform::Point2> CurvePoint(const Curve& curve, double t) {
  double point[2];
  const absl::Span<double> buffer(point, 2);
  RETURN_IF_ERROR(
      EvaluateCurve(curve, absl::Span<const double>(&t, 1),
                    absl::Span<const absl::Span<double>>(&buffer, 1)));
  return freeform::Point2{point[0], point[1]};
}

// SampleLoop samples loop `hole` (-1: the outer loop) curve by curve.
absl::Status SampleLoop(const TrimmedSurface& face, int hole, double tolerance,
                        size_t max_vertices, const CancellationToken* cancel,
                        LoopBuilder& loop) {
  const TrimLoop& trims = hole < 0 ? *face.outer() : face.holes()[hole];
  for (size_t j = 0; j < trims.curves.size(); ++j) {
    absl::StatusOr<TrimSamples> sampled = SampleTrimCurve(
        face, hole, static_cast<int>(j), tolerance / 2, max_vertices, cancel);
    if (absl::IsResourceExhausted(sampled.status())) {
      return TooManyVertices(max_vertices);
    }
    if (!sampled.ok()) return sampled.status();
    const TrimSamples& samples = *sampled;
    const Curve& curve = trims.curves[j];
    const auto point_at = [&](double t) { return CurvePoint(curve, t); };
    const std::vector<double>& uv = samples.uv;
    for (size_t k = 0; k + 1 < samples.parameters.size(); ++k) {
      RETURN_IF_ERROR(loop.AddChord(
          point_at, samples.parameters[k], {uv[2 * k], uv[2 * k + 1]},
          samples.parameters[k + 1], {uv[2 * k + 2], uv[2 * k + 3]}));
    }
  }
  return absl::OkStatus();
}

// SampleDomain samples the parameter rectangle's sides, counter-clockwise.
absl::Status SampleDomain(const SurfaceDomain& d, LoopBuilder& loop) {
  const std::array<freeform::Point2, 5> corners = {
      freeform::Point2{d.u_start, d.v_start},
      freeform::Point2{d.u_end, d.v_start}, freeform::Point2{d.u_end, d.v_end},
      freeform::Point2{d.u_start, d.v_end},
      freeform::Point2{d.u_start, d.v_start}};
  for (size_t k = 0; k < 4; ++k) {
    const freeform::Point2 a = corners[k], b = corners[k + 1];
    const auto point_at = [&](double t) -> absl::StatusOr<freeform::Point2> {
      return freeform::Point2{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
    };
    RETURN_IF_ERROR(loop.AddChord(point_at, 0.0, a, 1.0, b));
  }
  return absl::OkStatus();
}

}  // namespace

absl::Status TooManyVertices(size_t max_vertices) {
  return ExhaustedFieldError(
      "max_vertices",
      absl::StrCat("the face's mesh needs more than ", max_vertices,
                   " vertices at this tolerance"));
}

absl::StatusOr<SampledBoundary> SampleFaceBoundary(
    const TrimmedSurface& face, const FaceMetric& metric, double tolerance,
    size_t max_vertices, const CancellationToken* cancel) {
  const SurfaceDomain domain = DomainOf(face.surface());
  SampledBoundary boundary;
  const int holes = static_cast<int>(face.holes().size());
  for (int hole = -1; hole < holes; ++hole) {
    RETURN_IF_ERROR(CheckCancelled(cancel));
    LoopBuilder loop(metric, tolerance / 2, domain, max_vertices);
    if (hole < 0 && !face.outer().has_value()) {
      RETURN_IF_ERROR(SampleDomain(domain, loop));
    } else {
      RETURN_IF_ERROR(
          SampleLoop(face, hole, tolerance, max_vertices, cancel, loop));
    }
    const std::vector<freeform::Point2> points = loop.Finish();
    if (points.size() < 3) continue;  // a loop of zero area
    if (boundary.points.size() + points.size() > max_vertices) {
      return TooManyVertices(max_vertices);
    }
    const int32_t first = static_cast<int32_t>(boundary.points.size());
    const int32_t count = static_cast<int32_t>(points.size());
    for (int32_t k = 0; k < count; ++k) {
      boundary.segments.push_back({first + k, first + (k + 1) % count});
    }
    boundary.points.insert(boundary.points.end(), points.begin(), points.end());
  }
  return boundary;
}

absl::StatusOr<std::vector<freeform::Point2>> InteriorGrid(
    const TrimmedSurface& face, const FaceMetric& metric, double tolerance,
    size_t boundary_points, size_t max_vertices,
    const CancellationToken* cancel) {
  const std::vector<double>& bu = metric.breaks_u();
  const std::vector<double>& bv = metric.breaks_v();
  // The cells of every span rectangle, counted before any node is made.
  std::vector<std::array<double, 2>> cells;
  double total = static_cast<double>(boundary_points);
  for (size_t i = 0; i + 1 < bu.size(); ++i) {
    for (size_t j = 0; j + 1 < bv.size(); ++j) {
      const double du = bu[i + 1] - bu[i], dv = bv[j + 1] - bv[j];
      const MetricWeights w =
          metric.WeightsOver(bu[i], bu[i + 1], bv[j], bv[j + 1]);
      cells.push_back({NeededCells(w.a * du * du, tolerance),
                       NeededCells(w.b * dv * dv, tolerance)});
      total += cells.back()[0] * cells.back()[1];
    }
  }
  if (!(total <= static_cast<double>(max_vertices))) {
    return TooManyVertices(max_vertices);
  }
  std::vector<freeform::Point2> interior;
  std::vector<double> uv;
  for (size_t i = 0; i + 1 < bu.size(); ++i) {
    for (size_t j = 0; j + 1 < bv.size(); ++j) {
      RETURN_IF_ERROR(CheckCancelled(cancel));
      const auto [cells_u, cells_v] = cells[i * (bv.size() - 1) + j];
      const double hu = (bu[i + 1] - bu[i]) / cells_u;
      const double hv = (bv[j + 1] - bv[j]) / cells_v;
      // The counts fit: their product is at most max_vertices.
      const size_t count_u = static_cast<size_t>(cells_u);
      const size_t count_v = static_cast<size_t>(cells_v);
      uv.clear();
      for (size_t a = 0; a < count_u; ++a) {
        for (size_t b = 0; b < count_v; ++b) {
          uv.push_back(bu[i] + static_cast<double>(a) * hu);
          uv.push_back(bv[j] + static_cast<double>(b) * hv);
        }
      }
      ASSIGN_OR_RETURN(
          const std::vector<PointLocation> where,
          ClassifyPoints(face, uv, kBoundaryGap * std::max(hu, hv),
                         ExecutionContext{.cancellation = cancel}));
      for (size_t k = 0; k < where.size(); ++k) {
        if (where[k] == PointLocation::kInside) {
          interior.push_back({uv[2 * k], uv[2 * k + 1]});
        }
      }
    }
  }
  return interior;
}

}  // namespace freeform::internal
