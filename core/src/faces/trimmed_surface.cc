#include "freeform/core/trimmed_surface.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "faces/face_boundary.h"
#include "faces/trim_validation.h"
#include "faces/winding.h"
#include "freeform/core/points.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"

namespace freeform {
namespace {

using internal::FaceBoundary;
using internal::Point2;

// The most points of a chunk (the token is checked before each).
constexpr size_t kPointsPerChunk = 1024;

absl::StatusOr<std::shared_ptr<const FaceBoundary>> BuildBoundary(
    const TrimmedSurfaceParts& parts, double tolerance,
    const CancellationToken* cancel) {
  auto boundary = std::make_shared<FaceBoundary>();
  boundary->domain = DomainOf(parts.surface);
  boundary->tolerance = tolerance;
  RETURN_IF_ERROR(internal::BuildTrimPieces(parts, boundary.get(), cancel));
  RETURN_IF_ERROR(internal::CheckTrimResolution(*boundary));
  RETURN_IF_ERROR(internal::CheckClosure(*boundary));
  RETURN_IF_ERROR(internal::CheckInsideDomain(*boundary, cancel));
  RETURN_IF_ERROR(internal::CheckCrossings(*boundary, cancel));
  RETURN_IF_ERROR(internal::CheckOrientation(*boundary));
  RETURN_IF_ERROR(internal::BuildBoundaryPolylines(boundary.get(), cancel));
  RETURN_IF_ERROR(internal::CheckContainment(*boundary, cancel));
  return boundary;
}

PointLocation Classify(const FaceBoundary& boundary, const Point2& p,
                       double tolerance) {
  const SurfaceDomain& d = boundary.domain;
  if (p[0] < d.u_start - tolerance || p[0] > d.u_end + tolerance ||
      p[1] < d.v_start - tolerance || p[1] > d.v_end + tolerance) {
    return PointLocation::kOutside;
  }
  const internal::WindingAt at = internal::FaceWinding(boundary, p, tolerance);
  if (at.on_boundary) return PointLocation::kOnBoundary;
  return at.winding > 0 ? PointLocation::kInside : PointLocation::kOutside;
}

}  // namespace

absl::StatusOr<TrimmedSurface> TrimmedSurface::Create(
    TrimmedSurfaceParts parts, double tolerance,
    const CancellationToken* cancel) {
  RETURN_IF_ERROR(ValidatePositive(tolerance, "tolerance"));
  if (IsTriangular(parts.surface)) {
    return InvalidFieldError(
        "surface",
        "a triangular patch cannot be trimmed yet: use a tensor-product "
        "surface");
  }
  ASSIGN_OR_RETURN(std::shared_ptr<const FaceBoundary> boundary,
                   BuildBoundary(parts, tolerance, cancel));
  return TrimmedSurface(std::move(parts), tolerance, std::move(boundary));
}

absl::StatusOr<TrimmedSurfaceWork> TrimmedSurfaceWorkBytes(
    const TrimmedSurfaceParts& parts, double tolerance,
    const CancellationToken* cancel) {
  RETURN_IF_ERROR(ValidatePositive(tolerance, "tolerance"));
  if (IsTriangular(parts.surface)) {
    return TrimmedSurfaceWork{};  // Create refuses it
  }
  FaceBoundary boundary;
  boundary.domain = DomainOf(parts.surface);
  boundary.tolerance = tolerance;
  RETURN_IF_ERROR(internal::BuildTrimPieces(parts, &boundary, cancel));
  // The pieces, as Create keeps them (grown by push_back: up to twice).
  uint64_t piece_bytes = 0;
  for (const internal::TrimPiece& piece : boundary.pieces) {
    piece_bytes +=
        sizeof(internal::TrimPiece) + (piece.bezier.coordinates.capacity() +
                                       piece.bezier.weights.capacity()) *
                                          sizeof(double);
  }
  ASSIGN_OR_RETURN(const uint64_t polyline_bytes,
                   internal::BoundaryPolylineBytes(boundary));
  return TrimmedSurfaceWork{
      .bytes = 2 * piece_bytes +
               2 * boundary.loops.size() * sizeof(internal::BoundaryLoop) +
               internal::CrossingCheckBytes(boundary) + polyline_bytes,
      .pieces = boundary.pieces.size()};
}

absl::StatusOr<std::vector<PointLocation>> ClassifyPoints(
    const TrimmedSurface& face, absl::Span<const double> uv, double tolerance,
    const ExecutionContext& context) {
  if (uv.size() % 2 != 0) {
    return InvalidFieldError("uv", "must hold (u, v) pairs");
  }
  std::vector<PointLocation> locations(uv.size() / 2);
  RETURN_IF_ERROR(ClassifySamples(face, SurfaceSamples::Pairs(uv), tolerance,
                                  absl::MakeSpan(locations), context));
  return locations;
}

absl::Status ClassifySamples(const TrimmedSurface& face,
                             const SurfaceSamples& samples, double tolerance,
                             absl::Span<PointLocation> locations,
                             const ExecutionContext& context) {
  if (locations.size() != samples.size()) {
    return InvalidFieldError("locations", "must hold one per sample");
  }
  if (!(std::isfinite(tolerance) && tolerance >= 0.0)) {
    return InvalidFieldError("tolerance", "must be finite and not negative");
  }
  if (samples.grid) {
    RETURN_IF_ERROR(ValidateFinite(samples.u, "u"));
    RETURN_IF_ERROR(ValidateFinite(samples.v, "v"));
  } else {
    RETURN_IF_ERROR(ValidateFinite(samples.uv, "uv"));
  }
  const FaceBoundary& boundary = face.boundary();
  const size_t v_count = samples.v.size();
  ExecutionContext chunks = context;
  chunks.grain = std::min(chunks.grain, kPointsPerChunk);
  return ParallelFor(locations.size(), chunks, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const Point2 p =
          samples.grid ? Point2{samples.u[i / v_count], samples.v[i % v_count]}
                       : Point2{samples.uv[2 * i], samples.uv[2 * i + 1]};
      locations[i] = Classify(boundary, p, tolerance);
    }
  });
}

void OrientFaceNormals(const TrimmedSurface& face, absl::Span<double> normals) {
  if (!face.reversed()) return;
  for (double& x : normals) x = -x;
}

}  // namespace freeform
