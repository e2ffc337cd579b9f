// The rule that loops neither cross themselves nor each other
// (trim_validation.h, CheckCrossings).
//
// Every non-degenerate piece is halved until it is monotone along its
// chord (each edge of its control polygon, which holds every tangent of the
// part, points forward along the chord: no part crosses itself). Pairs of
// parts whose control boxes come within the tolerance are found by a sweep
// in u and intersected: two segments exactly, anything else by
// IntersectCurves. Neighbouring parts of a loop meet at their shared end:
// an intersection there (within kJunctionRadius tolerances of it) is
// allowed, any other is a crossing.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "faces/trim_validation.h"
#include "freeform/core/intersection.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/subdivision.h"

namespace freeform::internal {
namespace {

// Parts are halved at most this often on their way to monotone; a part
// still not monotone then (a cusp) is kept whole.
constexpr int kMaxMonotoneDepth = 12;

// Intersections within this many tolerances of a shared end are the
// neighbours' meeting.
constexpr double kJunctionRadius = 8.0;

// Neighbours whose control points lie in cones of this cosine about the
// tangent at their shared end J (the part before behind J, the one after
// ahead of it) are within a tolerance of each other only within
// kJunctionRadius tolerances of J: for points a and b of the two,
// |a - b| >= kJunctionCone (|a - J| + |b - J|) - gap, the gap at J being at
// most a tolerance.
constexpr double kJunctionCone = 2.0 / kJunctionRadius;

// A monotone part of a piece, with its control box and its place among
// the parts of its loop.
struct Part {
  BezierCurveData bezier;
  int piece = 0;
  int loop = 0;
  // Its index among its loop's parts, and the loop's part count.
  int index = 0;
  int loop_parts = 0;
  Box2 box;
};

Point2 ControlPoint(const BezierCurveData& b, size_t i) {
  return {b.coordinates[2 * i], b.coordinates[2 * i + 1]};
}

size_t ControlCount(const BezierCurveData& b) {
  return b.coordinates.size() / 2;
}

// IsMonotone reports whether every control polygon edge has a positive dot
// product with the chord (a rational part needs positive weights).
bool IsMonotone(const BezierCurveData& b) {
  if (!HasHull(b.weights)) return false;
  const size_t n = ControlCount(b);
  const Point2 first = ControlPoint(b, 0);
  const Point2 last = ControlPoint(b, n - 1);
  const double chord[2] = {last[0] - first[0], last[1] - first[1]};
  for (size_t i = 0; i + 1 < n; ++i) {
    const Point2 p = ControlPoint(b, i);
    const Point2 q = ControlPoint(b, i + 1);
    if (!((q[0] - p[0]) * chord[0] + (q[1] - p[1]) * chord[1] > 0.0)) {
      return false;
    }
  }
  return true;
}

// AddMonotoneParts appends the monotone parts of `bezier` to `parts`, at
// most `limit` in all (RESOURCE_EXHAUSTED naming `loop_path` beyond).
absl::Status AddMonotoneParts(const BezierCurveData& bezier, int depth,
                              const Part& prototype, uint64_t limit,
                              const std::string& loop_path,
                              std::vector<Part>& parts) {
  if (parts.size() >= limit) {
    return ExhaustedFieldError(
        loop_path, absl::StrCat("the trims would be cut into more than ", limit,
                                " monotone parts (curves that turn often or "
                                "have cusps)"));
  }
  if (depth >= kMaxMonotoneDepth || IsMonotone(bezier)) {
    if (parts.size() >= kMaxFaceBoundarySegments) {
      return ExhaustedFieldError(
          "holes",
          absl::StrCat("the loops need more than ", kMaxFaceBoundarySegments,
                       " monotone parts for the crossing check"));
    }
    Part part = prototype;
    part.bezier = bezier;
    part.box = ControlBox(bezier.coordinates);
    parts.push_back(std::move(part));
    return absl::OkStatus();
  }
  const double half[] = {0.5};
  ASSIGN_OR_RETURN(std::vector<BezierCurveData> halves,
                   SplitBezierCurve(bezier.view(), half));
  for (const BezierCurveData& h : halves) {
    RETURN_IF_ERROR(
        AddMonotoneParts(h, depth + 1, prototype, limit, loop_path, parts));
  }
  return absl::OkStatus();
}

// MonotoneParts returns every loop's parts in loop order.
}  // namespace

uint64_t MonotonePartLimit(const FaceBoundary& boundary) {
  uint64_t limit = 64;
  for (const TrimPiece& piece : boundary.pieces) {
    // A segment is monotone along its chord; a degenerate piece is skipped.
    const uint64_t controls = piece.bezier.coordinates.size() / 2;
    limit += piece.degenerate ? 0 : controls <= 2 ? 1 : 16 * controls;
  }
  return limit;
}

uint64_t CrossingCheckBytes(const FaceBoundary& boundary) {
  size_t largest = 0;
  for (const TrimPiece& piece : boundary.pieces) {
    largest = std::max(
        largest, piece.bezier.coordinates.size() + piece.bezier.weights.size());
  }
  // Parts grow by push_back (up to twice their count), each with its
  // control points and weights in blocks of their own (the allocator's
  // header and rounding: 16 bytes each); the halving keeps a chain of
  // halves per depth.
  const uint64_t part_bytes = sizeof(Part) + largest * sizeof(double) + 32;
  return 2 * MonotonePartLimit(boundary) * part_bytes +
         2 * kMaxMonotoneDepth * part_bytes;
}

namespace {

absl::StatusOr<std::vector<Part>> MonotoneParts(
    const FaceBoundary& boundary, const CancellationToken* cancel) {
  std::vector<Part> parts;
  const uint64_t limit = MonotonePartLimit(boundary);
  for (size_t l = 0; l < boundary.loops.size(); ++l) {
    const BoundaryLoop& loop = boundary.loops[l];
    if (loop.is_domain) continue;
    const size_t first = parts.size();
    for (int k = 0; k < loop.piece_count; ++k) {
      const TrimPiece& piece = boundary.pieces[loop.first_piece + k];
      if (piece.degenerate) continue;
      const Part prototype{.piece = loop.first_piece + k,
                           .loop = static_cast<int>(l)};
      RETURN_IF_ERROR(AddMonotoneParts(piece.bezier, 0, prototype, limit,
                                       loop.path, parts));
    }
    for (size_t i = first; i < parts.size(); ++i) {
      parts[i].index = static_cast<int>(i - first);
      parts[i].loop_parts = static_cast<int>(parts.size() - first);
    }
    RETURN_IF_ERROR(CheckCancelled(cancel));
  }
  return parts;
}

// Junctions returns the shared ends of two parts that are neighbours in
// their loop (none, one, or two for a loop of two parts).
std::vector<Point2> Junctions(const Part& a, const Part& b) {
  std::vector<Point2> junctions;
  if (a.loop != b.loop) return junctions;
  const int n = a.loop_parts;
  const auto end_of = [](const Part& p) {
    return ControlPoint(p.bezier, ControlCount(p.bezier) - 1);
  };
  if ((a.index + 1) % n == b.index) junctions.push_back(end_of(a));
  if ((b.index + 1) % n == a.index) junctions.push_back(end_of(b));
  return junctions;
}

bool NearJunction(const Point2& p, const std::vector<Point2>& junctions,
                  double radius) {
  for (const Point2& j : junctions) {
    if (std::hypot(p[0] - j[0], p[1] - j[1]) <= radius) return true;
  }
  return false;
}

// SeparatedAcrossChords reports whether the control points of the two
// parts (their hulls hold them) project onto the normal of either's chord
// in intervals more than `tolerance` apart.
bool SeparatedAcrossChords(const Part& a, const Part& b, double tolerance) {
  if (!HasHull(a.bezier.weights) || !HasHull(b.bezier.weights)) return false;
  for (const Part* along : {&a, &b}) {
    const Point2 p0 = ControlPoint(along->bezier, 0);
    const Point2 p1 =
        ControlPoint(along->bezier, ControlCount(along->bezier) - 1);
    const Point2 normal{p0[1] - p1[1], p1[0] - p0[0]};
    const double length = std::hypot(normal[0], normal[1]);
    if (!(length > 0.0)) continue;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int side = 0; side < 2; ++side) {
      const BezierCurveData& bezier = (side == 0 ? a : b).bezier;
      for (size_t i = 0; i < ControlCount(bezier); ++i) {
        const Point2 q = ControlPoint(bezier, i);
        const double x = (q[0] * normal[0] + q[1] * normal[1]) / length;
        lo[side] = std::min(lo[side], x);
        hi[side] = std::max(hi[side], x);
      }
    }
    if (hi[0] + tolerance < lo[1] || hi[1] + tolerance < lo[0]) return true;
  }
  return false;
}

// MeetOnlyAtJunction reports whether `before`, which ends where `after`
// starts, and `after` lie in the cones of kJunctionCone about the tangent
// there (so every contact is within kJunctionRadius tolerances of it).
bool MeetOnlyAtJunction(const Part& before, const Part& after) {
  if (!HasHull(before.bezier.weights) || !HasHull(after.bezier.weights)) {
    return false;
  }
  const size_t n = ControlCount(before.bezier);
  const Point2 end = ControlPoint(before.bezier, n - 1);
  const Point2 start = ControlPoint(after.bezier, 0);
  const Point2 into = ControlPoint(before.bezier, n - 2);
  const Point2 out = ControlPoint(after.bezier, 1);
  const double in_length = std::hypot(end[0] - into[0], end[1] - into[1]);
  const double out_length = std::hypot(out[0] - start[0], out[1] - start[1]);
  if (!(in_length > 0.0 && out_length > 0.0)) return false;
  Point2 tangent{
      (end[0] - into[0]) / in_length + (out[0] - start[0]) / out_length,
      (end[1] - into[1]) / in_length + (out[1] - start[1]) / out_length};
  const double length = std::hypot(tangent[0], tangent[1]);
  if (!(length > 0.0)) return false;
  tangent = {tangent[0] / length, tangent[1] / length};
  const auto in_cone = [&tangent](const Point2& from, const Point2& to) {
    const Point2 d{to[0] - from[0], to[1] - from[1]};
    return d[0] * tangent[0] + d[1] * tangent[1] >=
           kJunctionCone * std::hypot(d[0], d[1]);
  };
  for (size_t i = 0; i + 1 < n; ++i) {
    if (!in_cone(ControlPoint(before.bezier, i), end)) return false;
  }
  for (size_t i = 1; i < ControlCount(after.bezier); ++i) {
    if (!in_cone(start, ControlPoint(after.bezier, i))) return false;
  }
  return true;
}

// ApartOrMeetingAtTheirEnd reports whether two parts are certainly apart,
// or neighbours that certainly meet only at their shared end.
bool ApartOrMeetingAtTheirEnd(const Part& a, const Part& b, size_t junctions,
                              double tolerance) {
  if (junctions == 0) return SeparatedAcrossChords(a, b, tolerance);
  if (junctions != 1) return false;
  return (a.index + 1) % a.loop_parts == b.index ? MeetOnlyAtJunction(a, b)
                                                 : MeetOnlyAtJunction(b, a);
}

// SegmentContact returns a point where two segments come within the
// tolerance, other than their shared ends: where they cross, or an end of
// one within the tolerance of the other (a segment that folds back onto
// its neighbour has its far end on it).
std::optional<Point2> SegmentContact(const Part& a, const Part& b,
                                     double tolerance,
                                     const std::vector<Point2>& junctions,
                                     double radius) {
  const Point2 a0 = ControlPoint(a.bezier, 0);
  const Point2 a1 = ControlPoint(a.bezier, 1);
  const Point2 b0 = ControlPoint(b.bezier, 0);
  const Point2 b1 = ControlPoint(b.bezier, 1);
  const double d1 = Cross(a0, a1, b0), d2 = Cross(a0, a1, b1);
  const double d3 = Cross(b0, b1, a0), d4 = Cross(b0, b1, a1);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) &&
      ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) {
    const double s = d3 / (d3 - d4);
    const Point2 x{a0[0] + s * (a1[0] - a0[0]), a0[1] + s * (a1[1] - a0[1])};
    if (!NearJunction(x, junctions, radius)) return x;
  }
  const auto end_near = [&](const Point2& q, const Point2& s0,
                            const Point2& s1) -> std::optional<Point2> {
    if (NearJunction(q, junctions, radius)) return std::nullopt;
    if (DistanceToSegment(q, s0, s1) <= tolerance) return q;
    return std::nullopt;
  };
  for (const auto& [p, s0, s1] :
       {std::array{a0, b0, b1}, std::array{a1, b0, b1}, std::array{b0, a0, a1},
        std::array{b1, a0, a1}}) {
    if (std::optional<Point2> q = end_near(p, s0, s1)) return q;
  }
  return std::nullopt;
}

Point2 PointAt(const BezierCurveData& bezier, double t) {
  BezierPointEvaluator evaluator(bezier.view(), 0);
  std::vector<double> scratch(evaluator.scratch_size());
  Point2 point{};
  evaluator.Evaluate(t, scratch.data(), point.data());
  return point;
}

// CurveContact is SegmentContact for any parts, by IntersectCurves.
absl::StatusOr<std::optional<Point2>> CurveContact(
    const Part& a, const Part& b, double tolerance,
    const std::vector<Point2>& junctions, double radius,
    const CancellationToken* cancel) {
  IntersectionOptions options;
  options.tolerance = tolerance;
  options.separation = tolerance;
  ASSIGN_OR_RETURN(CurveIntersections found,
                   IntersectCurves(PieceCurve(a.bezier), PieceCurve(b.bezier),
                                   options, cancel));
  for (size_t k = 0; k < found.first_parameters.size(); ++k) {
    const Point2 p{found.points[2 * k], found.points[2 * k + 1]};
    if (!NearJunction(p, junctions, radius)) return p;
  }
  for (const double t : found.first_intervals) {
    const Point2 p = PointAt(a.bezier, t);
    if (!NearJunction(p, junctions, radius)) return p;
  }
  return std::nullopt;
}

absl::Status CrossingError(const FaceBoundary& boundary, const Part& a,
                           const Part& b, const Point2& at) {
  // The later curve in the face's order is named; the message names the
  // other.
  const std::string later =
      CurvePath(boundary, boundary.pieces[std::max(a.piece, b.piece)]);
  const std::string earlier =
      CurvePath(boundary, boundary.pieces[std::min(a.piece, b.piece)]);
  const std::string what = later == earlier
                               ? std::string("crosses itself")
                               : absl::StrCat("crosses or touches ", earlier);
  return InvalidFieldError(
      later, absl::StrCat(what, " near (u, v) = (", at[0], ", ", at[1],
                          "): loops must not cross themselves or each other"));
}

absl::Status CheckPair(const FaceBoundary& boundary, const Part& a,
                       const Part& b, const CancellationToken* cancel) {
  const double tolerance = boundary.tolerance;
  const std::vector<Point2> junctions = Junctions(a, b);
  const double radius = kJunctionRadius * tolerance;
  if (ApartOrMeetingAtTheirEnd(a, b, junctions.size(), tolerance)) {
    return absl::OkStatus();
  }
  std::optional<Point2> contact;
  if (ControlCount(a.bezier) == 2 && ControlCount(b.bezier) == 2) {
    contact = SegmentContact(a, b, tolerance, junctions, radius);
  } else {
    ASSIGN_OR_RETURN(contact,
                     CurveContact(a, b, tolerance, junctions, radius, cancel));
  }
  if (!contact.has_value()) return absl::OkStatus();
  return CrossingError(boundary, a, b, *contact);
}

}  // namespace

absl::Status CheckCrossings(const FaceBoundary& boundary,
                            const CancellationToken* cancel) {
  ASSIGN_OR_RETURN(std::vector<Part> parts, MonotoneParts(boundary, cancel));
  std::vector<size_t> order(parts.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&parts](size_t x, size_t y) {
    return parts[x].box.lo[0] < parts[y].box.lo[0];
  });
  const double tolerance = boundary.tolerance;
  CancellationPoll poll(cancel);
  for (size_t i = 0; i < order.size(); ++i) {
    const Part& a = parts[order[i]];
    for (size_t k = i + 1; k < order.size(); ++k) {
      const Part& b = parts[order[k]];
      if (b.box.lo[0] > a.box.hi[0] + tolerance) break;
      if (b.box.lo[1] > a.box.hi[1] + tolerance ||
          a.box.lo[1] > b.box.hi[1] + tolerance) {
        continue;
      }
      RETURN_IF_ERROR(CheckPair(boundary, a, b, cancel));
      RETURN_IF_ERROR(poll.Done(
          16 * (a.bezier.coordinates.size() + b.bezier.coordinates.size())));
    }
  }
  return absl::OkStatus();
}

}  // namespace freeform::internal
