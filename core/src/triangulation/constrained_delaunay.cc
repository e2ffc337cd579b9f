#include "freeform/core/constrained_delaunay.h"

#include <cstdint>
#include <limits>
#include <utility>

#include "absl/strings/str_cat.h"
#include "freeform/core/saturating.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "triangulation/constraint_insertion.h"
#include "triangulation/delaunay_insertion.h"
#include "triangulation/predicates.h"
#include "triangulation/triangle_mesh_2d.h"
#include "triangulation/triangulation_region.h"

namespace freeform {
namespace {

using internal::TriangleMesh2d;

// The memory bound's terms (ConstrainedTriangulationMemoryBound): per point
// the mesh (points 16, representatives 4, vertex triangles 4, about two
// triangles of 36 bytes), the insertion order and its keys (16), the
// region's depths and flood (16), the result (triangles 24, points 20,
// segment edges) and the worst segment insertion's scratch (a cavity of
// every triangle: its chains, new triangles, crossed edges and the two hash
// maps of its edges). tests/core/triangulation_memory_test.cc measures
// peaks of 116 bytes per point for random points, 136 for a loop of
// segments and 344 for one segment that crosses every triangle of 10^4
// points.
constexpr uint64_t kBytesPerPoint = 512;
constexpr uint64_t kBytesPerSegment = 16;
constexpr uint64_t kFixedBytes = uint64_t{64} << 10;

// Segment insertion polls the token once per this many replaced triangles.
constexpr size_t kSegmentWorkPerPoll = 4096;

bool InRange(Point2 point) {
  return internal::InTriangulationRange(point.x) &&
         internal::InTriangulationRange(point.y);
}

absl::Status ValidatePoint(Point2 point, absl::string_view field) {
  if (InRange(point)) return absl::OkStatus();
  return InvalidFieldError(
      field, absl::StrCat("(", point.x, ", ", point.y,
                          ") is not finite or outside the exact range: each "
                          "coordinate must be 0 or of a magnitude in "
                          "[2^-180, 2^200]"));
}

absl::Status SegmentError(absl::Span<const std::array<int32_t, 2>> segments,
                          size_t i, absl::string_view rule) {
  return InvalidFieldError(
      IndexedField("segments", i),
      absl::StrCat("(", segments[i][0], ", ", segments[i][1], ") ", rule));
}

absl::Status ValidateInput(absl::Span<const Point2> points,
                           absl::Span<const std::array<int32_t, 2>> segments) {
  if (points.size() > kMaxTriangulationPoints) {
    return InvalidFieldError(
        "points", absl::StrCat(points.size(), " points exceed the limit of ",
                               kMaxTriangulationPoints));
  }
  if (segments.size() >
      static_cast<size_t>(std::numeric_limits<int32_t>::max())) {
    return InvalidFieldError(
        "segments", absl::StrCat(segments.size(),
                                 " segments exceed the limit of 2^31 - 1"));
  }
  for (size_t i = 0; i < points.size(); ++i) {
    RETURN_IF_ERROR(ValidatePoint(points[i], IndexedField("points", i)));
  }
  const auto count = static_cast<int64_t>(points.size());
  for (size_t i = 0; i < segments.size(); ++i) {
    for (const int32_t end : segments[i]) {
      if (end < 0 || end >= count) {
        return SegmentError(segments, i,
                            absl::StrCat("has the point index ", end,
                                         " outside [0, ", count, ")"));
      }
    }
  }
  return absl::OkStatus();
}

absl::Status InsertSegments(TriangleMesh2d& mesh,
                            absl::Span<const std::array<int32_t, 2>> segments,
                            const CancellationToken* cancel) {
  internal::SegmentScratch scratch;
  CancellationPoll poll(cancel, kSegmentWorkPerPoll);
  for (size_t i = 0; i < segments.size(); ++i) {
    const int32_t a = mesh.representative[segments[i][0]];
    const int32_t b = mesh.representative[segments[i][1]];
    if (a == b) {
      return SegmentError(segments, i, "joins a point to itself");
    }
    ASSIGN_OR_RETURN(
        const size_t work,
        internal::InsertSegment(mesh, a, b, static_cast<int32_t>(i), scratch));
    RETURN_IF_ERROR(poll.Done(work));
  }
  return absl::OkStatus();
}

}  // namespace

ConstrainedTriangulation::ConstrainedTriangulation(
    std::unique_ptr<internal::TriangleMesh2d> mesh)
    : mesh_(std::move(mesh)) {}
ConstrainedTriangulation::ConstrainedTriangulation(
    ConstrainedTriangulation&&) noexcept = default;
ConstrainedTriangulation& ConstrainedTriangulation::operator=(
    ConstrainedTriangulation&&) noexcept = default;
ConstrainedTriangulation::~ConstrainedTriangulation() = default;

absl::StatusOr<ConstrainedTriangulation> ConstrainedTriangulation::Build(
    absl::Span<const Point2> points,
    absl::Span<const std::array<int32_t, 2>> segments,
    const CancellationToken* cancel) {
  RETURN_IF_ERROR(ValidateInput(points, segments));
  auto mesh = std::make_unique<TriangleMesh2d>();
  mesh->points.assign(points.begin(), points.end());
  RETURN_IF_ERROR(internal::BuildDelaunay(*mesh, cancel));
  RETURN_IF_ERROR(InsertSegments(*mesh, segments, cancel));
  return ConstrainedTriangulation(std::move(mesh));
}

absl::StatusOr<int32_t> ConstrainedTriangulation::InsertPoint(Point2 point) {
  RETURN_IF_ERROR(ValidatePoint(point, "point"));
  const internal::PointLocation location =
      internal::Locate(*mesh_, point, mesh_->last_triangle, mesh_->walk_state);
  if (location.kind == internal::PointLocation::Kind::kVertex) {
    return mesh_->triangles[location.triangle].vertices[location.corner];
  }
  if (mesh_->points.size() >= kMaxTriangulationPoints) {
    return InvalidFieldError(
        "point", absl::StrCat("the triangulation already holds the most "
                              "points, ",
                              kMaxTriangulationPoints));
  }
  const auto vertex = static_cast<int32_t>(mesh_->points.size());
  mesh_->points.push_back(point);
  mesh_->vertex_triangle.push_back(internal::kNoTriangle);
  internal::InsertLocatedVertex(*mesh_, vertex, location);
  return vertex;
}

std::optional<std::array<int32_t, 3>> ConstrainedTriangulation::LocateTriangle(
    Point2 point) const {
  if (!InRange(point)) return std::nullopt;
  uint64_t random_state = mesh_->walk_state;
  const internal::PointLocation location =
      internal::Locate(*mesh_, point, mesh_->last_triangle, random_state);
  if (location.kind == internal::PointLocation::Kind::kOutside) {
    return std::nullopt;
  }
  return mesh_->triangles[location.triangle].vertices;
}

PlanarTriangulation ConstrainedTriangulation::Result(
    ConstrainedTriangulationOptions::Region region) const {
  return internal::ExtractTriangulation(*mesh_, region);
}

size_t ConstrainedTriangulation::point_count() const {
  return mesh_->points.size();
}

absl::StatusOr<PlanarTriangulation> TriangulateConstrained(
    absl::Span<const Point2> points,
    absl::Span<const std::array<int32_t, 2>> segments,
    const ConstrainedTriangulationOptions& options,
    const CancellationToken* cancel) {
  ASSIGN_OR_RETURN(const ConstrainedTriangulation triangulation,
                   ConstrainedTriangulation::Build(points, segments, cancel));
  return triangulation.Result(options.region);
}

size_t ConstrainedTriangulationMemoryBound(size_t point_count,
                                           size_t segment_count) {
  const uint64_t bytes = SaturatingSum(
      SaturatingSum(SaturatingProduct(point_count, kBytesPerPoint),
                    SaturatingProduct(segment_count, kBytesPerSegment)),
      kFixedBytes);
  return bytes > std::numeric_limits<size_t>::max()
             ? std::numeric_limits<size_t>::max()
             : static_cast<size_t>(bytes);
}

}  // namespace freeform
