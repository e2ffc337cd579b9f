#include "faces/winding.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "absl/container/inlined_vector.h"
#include "freeform/core/subdivision.h"
#include "freeform/core/tessellation.h"

namespace freeform::internal {
namespace {

// Each refinement of an arc divides its chords' bound by this.
constexpr double kRefinement = 1.0 / 8.0;

// The refinement stops at this fraction of the tolerance...
constexpr double kFloorOfTolerance = 1.0 / 256.0;
// ... or at this fraction of the piece's largest coordinate (the
// tessellation's resolution is 2^-48 of it).
constexpr double kFloorOfScale = 0x1p-44;

// The most points of one refined arc.
constexpr size_t kMaxArcPoints = size_t{1} << 12;

// ChordCrossing returns the signed crossing of the chord a -> b with the
// ray from p along +u, or along -u when not `rightward` (Sunday's winding
// number: along +u, +1 for an upward chord with p on its left and -1 for a
// downward one with p on its right; along -u the other sides, negated;
// half-open in v, so the two rays agree on a closed loop).
int ChordCrossing(const Point2& a, const Point2& b, const Point2& p,
                  bool rightward) {
  const double left = Cross(a, b, p);
  const double side = rightward ? left : -left;
  const int sign = rightward ? 1 : -1;
  if (a[1] <= p[1]) {
    if (b[1] > p[1] && side > 0.0) return sign;
  } else if (b[1] <= p[1] && side < 0.0) {
    return -sign;
  }
  return 0;
}

// SubArc returns the piece on [s0, s1], reparameterized to [0, 1].
BezierCurveData SubArc(const BezierCurveData& bezier, double s0, double s1) {
  std::vector<double> cuts;
  if (s0 > 0.0) cuts.push_back(s0);
  if (s1 < 1.0) cuts.push_back(s1);
  if (cuts.empty()) return bezier;
  absl::StatusOr<std::vector<BezierCurveData>> parts =
      SplitBezierCurve(bezier.view(), cuts);
  if (!parts.ok()) return bezier;
  return std::move((*parts)[s0 > 0.0 ? 1 : 0]);
}

double LargestCoordinate(const BezierCurveData& bezier) {
  double size = 0.0;
  for (const double c : bezier.coordinates) size = std::max(size, std::abs(c));
  return size;
}

// The winding of the chords and arcs about one point, and whether the
// point was found within the tolerance of a loop.
class WindingCounter {
 public:
  WindingCounter(const FaceBoundary& boundary, const Point2& p,
                 double tolerance, bool rightward)
      : boundary_(boundary),
        p_(p),
        tolerance_(tolerance),
        rightward_(rightward) {}

  const WindingAt& result() const { return result_; }
  bool on_boundary() const { return result_.on_boundary; }

  // IsNear reports whether the segment is within its bound plus the
  // tolerance of the point (its chord alone may not count); an exact one
  // that near puts the point on the boundary.
  bool IsNear(const BoundarySegment& s) {
    const double d = DistanceToSegment(p_, s.a, s.b);
    if (d > s.epsilon + tolerance_) return false;
    if (s.epsilon == 0.0 || d + s.epsilon <= tolerance_) {
      result_.on_boundary = true;
    }
    return true;
  }

  void AddChord(const BoundarySegment& s) {
    result_.winding += ChordCrossing(s.a, s.b, p_, rightward_);
  }

  // AddArc adds the winding of a near segment's arc.
  void AddArc(const BoundarySegment& s) {
    if (result_.on_boundary) return;
    const BezierCurveData& bezier = boundary_.pieces[s.piece].bezier;
    const double floor = std::max(tolerance_ * kFloorOfTolerance,
                                  kFloorOfScale * LargestCoordinate(bezier));
    Refine(bezier, s.s0, s.s1, s.a, s.b, s.epsilon, floor);
  }

 private:
  // Refine re-tessellates the arc on [s0, s1] (from a to b) with a finer
  // bound and counts each sub-chord, recursing into the near ones.
  void Refine(const BezierCurveData& bezier, double s0, double s1,
              const Point2& a, const Point2& b, double epsilon, double floor) {
    const double finer = std::max(epsilon * kRefinement, floor);
    const BezierCurveData arc = SubArc(bezier, s0, s1);
    absl::StatusOr<Polyline> polyline =
        TessellateBezierCurve(arc.view(), finer, kMaxArcPoints);
    if (!polyline.ok() || !(epsilon > floor)) {
      CountChord(a, b, /*bound=*/0.0);
      return;
    }
    const size_t n = polyline->parameters.size();
    const std::vector<double>& x = polyline->points;
    for (size_t k = 0; k + 1 < n && !result_.on_boundary; ++k) {
      const Point2 c = k == 0 ? a : Point2{x[2 * k], x[2 * k + 1]};
      const Point2 d = k + 2 == n ? b : Point2{x[2 * k + 2], x[2 * k + 3]};
      const double dist = DistanceToSegment(p_, c, d);
      if (dist + finer <= tolerance_) {
        result_.on_boundary = true;
      } else if (dist > finer + tolerance_ || finer <= floor) {
        CountChord(c, d, dist);
      } else {
        const double t0 = polyline->parameters[k];
        const double t1 = polyline->parameters[k + 1];
        Refine(bezier, s0 + (s1 - s0) * t0, s0 + (s1 - s0) * t1, c, d, finer,
               floor);
      }
    }
  }

  // CountChord decides a chord at the end of the refinement by its own
  // distance (or counts a far one).
  void CountChord(const Point2& a, const Point2& b, double distance) {
    if (distance == 0.0) distance = DistanceToSegment(p_, a, b);
    if (distance <= tolerance_) {
      result_.on_boundary = true;
      return;
    }
    result_.winding += ChordCrossing(a, b, p_, rightward_);
  }

  const FaceBoundary& boundary_;
  const Point2 p_;
  const double tolerance_;
  const bool rightward_;
  WindingAt result_;
};

// VisitCellSegments calls visit(index, segment) for every segment listed
// in the grid's cells that meet the box p +- reach (a segment listed in
// several cells comes several times) until visit returns false.
template <typename Visit>
void VisitCellSegments(const FaceBoundary& boundary, const Point2& p,
                       double reach, Visit&& visit) {
  const SegmentGrid& grid = boundary.grid;
  const int c0 = grid.Column(p[0] - reach);
  const int c1 = grid.Column(p[0] + reach);
  const int r0 = grid.Row(p[1] - reach);
  const int r1 = grid.Row(p[1] + reach);
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      const size_t cell = static_cast<size_t>(r) * grid.columns + c;
      for (uint32_t k = grid.cell_start[cell]; k < grid.cell_start[cell + 1];
           ++k) {
        const uint32_t index = grid.cell_segments[k];
        if (!visit(index, boundary.segments[index])) return;
      }
    }
  }
}

}  // namespace

bool TrimMayBeWithin(const FaceBoundary& boundary, const Point2& p,
                     double reach) {
  bool found = false;
  VisitCellSegments(
      boundary, p, reach, [&](uint32_t, const BoundarySegment& s) {
        found = DistanceToSegment(p, s.a, s.b) <= s.epsilon + reach;
        return !found;
      });
  return found;
}

WindingAt FaceWinding(const FaceBoundary& boundary, const Point2& p,
                      double tolerance, int exclude_loop) {
  const SegmentGrid& grid = boundary.grid;
  // The ray runs to the nearer side of the parameter rectangle.
  const bool rightward =
      p[0] >= 0.5 * (boundary.domain.u_start + boundary.domain.u_end);
  WindingCounter counter(boundary, p, tolerance, rightward);
  absl::InlinedVector<uint32_t, 16> near;
  VisitCellSegments(
      boundary, p, tolerance, [&](uint32_t index, const BoundarySegment& s) {
        if (s.loop == exclude_loop ||
            std::find(near.begin(), near.end(), index) != near.end() ||
            !counter.IsNear(s)) {
          return true;
        }
        near.push_back(index);
        return !counter.on_boundary();
      });
  if (counter.on_boundary()) return counter.result();
  const int row = grid.Row(p[1]);
  const std::vector<uint32_t>& order =
      rightward ? grid.rightward : grid.leftward;
  for (uint32_t r = grid.run_start[row]; r < grid.run_start[row + 1]; ++r) {
    const SegmentGrid::Run& run = grid.runs[r];
    // A loop whose box does not hold p winds 0 times about it.
    const BoundaryLoop& loop = boundary.loops[run.loop];
    if (run.loop == exclude_loop || p[0] < loop.box.lo[0] - tolerance ||
        p[0] > loop.box.hi[0] + tolerance ||
        p[1] < loop.box.lo[1] - tolerance ||
        p[1] > loop.box.hi[1] + tolerance) {
      continue;
    }
    for (uint32_t k = run.begin; k < run.end; ++k) {
      const uint32_t index = order[k];
      const BoundarySegment& s = boundary.segments[index];
      // The rest of the run lies wholly behind the ray's start.
      if (rightward ? std::max(s.a[0], s.b[0]) < p[0]
                    : std::min(s.a[0], s.b[0]) > p[0]) {
        break;
      }
      if (!near.empty() &&
          std::find(near.begin(), near.end(), index) != near.end()) {
        continue;
      }
      counter.AddChord(s);
    }
  }
  for (const uint32_t index : near) {
    counter.AddArc(boundary.segments[index]);
    if (counter.on_boundary()) break;
  }
  return counter.result();
}

WindingAt LoopWinding(const FaceBoundary& boundary, int loop, const Point2& p,
                      double tolerance) {
  const BoundaryLoop& l = boundary.loops[loop];
  WindingCounter counter(boundary, p, tolerance, /*rightward=*/true);
  for (uint32_t k = 0; k < l.segment_count && !counter.on_boundary(); ++k) {
    const BoundarySegment& s = boundary.segments[l.first_segment + k];
    if (!counter.IsNear(s)) {
      counter.AddChord(s);
    } else {
      counter.AddArc(s);
    }
  }
  return counter.result();
}

}  // namespace freeform::internal
