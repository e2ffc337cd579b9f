// Constrained Delaunay triangulation of points and segments in the plane,
// for meshing trimmed faces in their (u, v) domain: trim loops become
// segments, interior points come from the mesh planner, and refinement
// inserts Steiner points one at a time (ConstrainedTriangulation).
//
// The geometric decisions are exact: orientation and in-circle signs come
// from adaptive predicates (Shewchuk 1997, docs/references.md) that are
// exact for every coordinate that is 0 or has a magnitude in
// [kMinTriangulationMagnitude, kMaxTriangulationMagnitude]; the API refuses
// other coordinates. The output is deterministic: the insertion order is a
// fixed-seed biased randomized order (BRIO) along a Hilbert curve.
//
//   ASSIGN_OR_RETURN(PlanarTriangulation mesh,
//                    TriangulateConstrained(points, segments, {}, cancel));
//
// A ConstrainedTriangulation is not safe to modify from two threads; const
// methods may run concurrently with each other.
#ifndef FREEFORM_CORE_CONSTRAINED_DELAUNAY_H_
#define FREEFORM_CORE_CONSTRAINED_DELAUNAY_H_

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/cancellation.h"

namespace freeform {

// Point2 is a point of the plane (a (u, v) parameter pair of a face).
struct Point2 {
  double x = 0.0;
  double y = 0.0;

  friend bool operator==(const Point2&, const Point2&) = default;
};

// The range of coordinate magnitudes (besides 0) in which the predicates'
// signs are exact: the degree-4 terms of the in-circle test neither
// overflow nor fall below the normal range (predicates.h).
inline constexpr double kMinTriangulationMagnitude = 0x1p-180;
inline constexpr double kMaxTriangulationMagnitude = 0x1p200;

// The most points (input and Steiner) a triangulation holds: its indices
// are int32_t, and a triangulation of n points has about 2n triangles and
// 3n edges.
inline constexpr size_t kMaxTriangulationPoints = (size_t{1} << 29) - 1;

struct ConstrainedTriangulationOptions {
  enum class Region {
    // Every triangle of the convex hull of the points.
    kConvexHull,
    // The triangles enclosed by the segments by the even-odd rule: a flood
    // from the hull across unconstrained edges reaches the outside (depth
    // 0); each constrained edge crossed adds one to the depth; the
    // triangles of odd depth are kept.
    kInsideSegments,
  };
  Region region = Region::kConvexHull;
};

// PlanarTriangulation is a triangulation as plain arrays.
struct PlanarTriangulation {
  // Counter-clockwise triangles, indices into `points`.
  std::vector<std::array<int32_t, 3>> triangles;
  // The input points followed by any Steiner points.
  std::vector<Point2> points;
  // Per input point: the vertex it merged into, itself unless it is an
  // exact duplicate of an earlier point (in insertion order). Only
  // representatives appear in `triangles`.
  std::vector<int32_t> representative;
  // The mesh edges that carry a segment, after segments were split at the
  // vertices they pass through; each edge once, {smaller, larger} index.
  // Edges outside the region are listed too.
  std::vector<std::array<int32_t, 2>> constrained_edges;
};

namespace internal {
struct TriangleMesh2d;
}  // namespace internal

// ConstrainedTriangulation is the constrained Delaunay triangulation of a
// point set and non-crossing segments, kept constrained Delaunay while
// points are inserted.
class ConstrainedTriangulation {
 public:
  // Build triangulates `points` with `segments` (pairs of point indices).
  // A segment that passes through a point is split there. Fails with
  // INVALID_ARGUMENT naming "points[i]" for a coordinate that is not
  // finite or outside the exact range, "points" for more than
  // kMaxTriangulationPoints points or for points that are all collinear
  // (fewer than 3 non-collinear points: no triangle exists), "segments[i]"
  // for an index out of range or a segment whose ends merged into one
  // vertex, and "segments[i]: crosses or overlaps segments[j]" for two
  // segments that cross or overlap (share a piece of positive length; a
  // segment listed twice overlaps itself), i the later one. Segments may
  // meet at input points. Every error carries its field path (status.h).
  // Returns the token's status when it is cancelled.
  static absl::StatusOr<ConstrainedTriangulation> Build(
      absl::Span<const Point2> points,
      absl::Span<const std::array<int32_t, 2>> segments,
      const CancellationToken* cancel);

  ConstrainedTriangulation(ConstrainedTriangulation&&) noexcept;
  ConstrainedTriangulation& operator=(ConstrainedTriangulation&&) noexcept;
  ~ConstrainedTriangulation();

  // InsertPoint adds `point` and restores the constrained Delaunay property
  // (flips that never flip a constrained edge). Returns the new vertex's
  // index, or the existing vertex's for a point already in the mesh. A
  // point on a constrained edge splits it; a point outside the hull extends
  // the hull. Fails with INVALID_ARGUMENT for a coordinate that is not
  // finite or outside the exact range, or when the mesh is full.
  absl::StatusOr<int32_t> InsertPoint(Point2 point);

  // LocateTriangle returns the counter-clockwise vertices of a triangle
  // that contains `point` (on its boundary or inside), or nullopt when
  // `point` is outside the convex hull or not a valid coordinate.
  std::optional<std::array<int32_t, 3>> LocateTriangle(Point2 point) const;

  // Result returns the triangles of `region` and the edges carrying
  // segments.
  PlanarTriangulation Result(
      ConstrainedTriangulationOptions::Region region) const;

  // point_count returns the number of points, input and Steiner.
  size_t point_count() const;

 private:
  explicit ConstrainedTriangulation(
      std::unique_ptr<internal::TriangleMesh2d> mesh);
  std::unique_ptr<internal::TriangleMesh2d> mesh_;
};

// TriangulateConstrained returns the constrained Delaunay triangulation of
// `points` and `segments` restricted to `options.region`; the errors are
// those of ConstrainedTriangulation::Build. No Steiner points are added.
absl::StatusOr<PlanarTriangulation> TriangulateConstrained(
    absl::Span<const Point2> points,
    absl::Span<const std::array<int32_t, 2>> segments,
    const ConstrainedTriangulationOptions& options,
    const CancellationToken* cancel);

// ConstrainedTriangulationMemoryBound returns an upper bound, in bytes, of
// the memory TriangulateConstrained allocates at its peak for these sizes
// (its result included), saturating at SIZE_MAX.
size_t ConstrainedTriangulationMemoryBound(size_t point_count,
                                           size_t segment_count);

}  // namespace freeform

#endif  // FREEFORM_CORE_CONSTRAINED_DELAUNAY_H_
