// What the query RPCs of both services share (query.proto): the working
// memory of their Bezier pieces, the plans of closest points and bounding
// boxes for a curve or a surface, the writers of their answers, and the
// mapping of the core's errors to the request's fields. The options and
// their defaults are prepare_options.h's. Thread-compatible.
#ifndef FREEFORM_SERVER_QUERIES_H_
#define FREEFORM_SERVER_QUERIES_H_

#include <cstdint>
#include <string>

#include "absl/functional/any_invocable.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "freeform/core/bounding_box.h"
#include "freeform/core/closest_point.h"
#include "freeform/core/intersection.h"
#include "freeform/core/status_macros.h"
#include "freeform/v1/query.pb.h"
#include "prepare_options.h"
#include "rpc.h"
#include "service_limits.h"

namespace freeform::server {

// PieceWorkBytes returns the working memory of a query that cuts geometry
// into Bezier pieces of `piece_values` doubles (DecomposedCurveValues,
// SurfacePieceValues), three times their values (cutting holds the
// knot-refined control points beside the pieces; the queries then keep them
// in homogeneous form and a copy, projected or subdivided), or
// RESOURCE_EXHAUSTED naming `field` when that is over the server's memory
// budget.
absl::StatusOr<uint64_t> PieceWorkBytes(uint64_t piece_values,
                                        const ServiceLimits& limits,
                                        absl::string_view field);

// Bytes of records per piece besides its values: its data and lifted net
// with their blocks, and the query's box, ball and flags of it
// (closest points, sections).
inline constexpr uint64_t kPieceRecordBytes = 256;
// The same for the intersections, which also hold every piece of their
// second input as a part (a shared block with its projected points and
// box) while the first input's pieces are searched against them.
inline constexpr uint64_t kPartRecordBytes = 512;

// Bytes per curve piece of the arc-length queries: the breakpoints and the
// cuts between them, and the length table's ends and sums, grown by
// doubling, for four kept intervals per piece. A smooth piece's quadrature
// halves agree to rounding within a few halvings (a piece whose speed
// vanishes somewhere measures the same); the core's own cap is
// kMaxArcLengthIntervals per piece.
inline constexpr uint64_t kArcLengthPieceBytes = 256;

// PieceWorkBytes with `pieces` pieces (DecomposedCurvePieces,
// SurfacePieceCount) of `records` bytes of records each besides.
absl::StatusOr<uint64_t> PieceWorkBytes(uint64_t piece_values, uint64_t pieces,
                                        uint64_t records,
                                        const ServiceLimits& limits,
                                        absl::string_view field);

// CheckWorkBytes returns `bytes`, a query's working memory, or
// RESOURCE_EXHAUSTED naming `field` when that is over the server's memory
// budget.
absl::StatusOr<uint64_t> CheckWorkBytes(uint64_t bytes,
                                        const ServiceLimits& limits,
                                        absl::string_view field);

// IntersectionError maps the core's errors of an intersection to the
// request's fields: "max_results", "tolerance" (below what double precision
// resolves on the inputs) and "separation" are under options., and
// "max_work" (more work than the server does for one search: stretches of
// contact the tolerance cannot resolve, or too many crossings) is
// options.tolerance. Other errors pass unchanged.
absl::Status IntersectionError(const absl::Status& status);

// QueryError maps the core's fields of a query no double parameter answers
// (core/arc_length.h, core/closest_point.h) to the request's: "weights" to
// the geometry's weights (`geometry` is its path, "curve.bspline", so
// "curve.bspline.weights") and "tolerance" to `tolerance` ("tolerance" or
// "options.tolerance"). Other errors pass unchanged.
absl::Status QueryError(const absl::Status& status, absl::string_view geometry,
                        absl::string_view tolerance);

// A closest-point search of a prepared geometry: (queries, options,
// context) -> minima.
using ClosestPointSearch = absl::AnyInvocable<absl::StatusOr<ClosestPoints>(
    const PointsView&, const ClosestPointOptions&, const ExecutionContext&)
                                                  const>;

// PlanClosestPoints plans a batch of closest-point queries of a geometry
// at the request path `geometry` ("curve.bspline") of `dimension` with
// `parameter_count` parameters per point, whose pieces take `work_bytes`
// (PieceWorkBytes; the search adds a rescaled copy of the geometry and of
// the queries): the queries ("queries", within the parameter limit) and
// options are checked and the answer's size bounded before any work. The
// search's errors name the request's fields (QueryError).
absl::StatusOr<UnaryWork> PlanClosestPoints(
    std::string geometry, int dimension, int parameter_count,
    uint64_t work_bytes, const v1::Points& queries,
    const v1::ClosestPointOptions& options, ClosestPointSearch search,
    const ServiceLimits& limits, v1::ClosestPointResponse& response);

// A bounding-box computation of a prepared geometry at a tolerance.
using BoxComputation = absl::AnyInvocable<absl::StatusOr<BoundingBox>(
    double, const CancellationToken*) const>;

// PlanBoundingBox plans the box of a geometry of `dimension` whose pieces
// take `work_bytes`, to `tolerance`.
UnaryWork PlanBoundingBox(int dimension, uint64_t work_bytes, double tolerance,
                          BoxComputation compute, const ServiceLimits& limits,
                          v1::BoundingBoxResponse& response);

// PlanBoundingBoxOf plans the box of a curve's or a surface's BoundingBox
// request: `geometry` is its prepared geometry (or the error preparing it),
// at the request path `field`, whose work `work_bytes(geometry)` takes and
// `compute(geometry, tolerance, cancel)` finds, to the request's tolerance.
template <typename Geometry, typename Request, typename WorkBytes,
          typename Compute>
absl::StatusOr<UnaryWork> PlanBoundingBoxOf(
    absl::StatusOr<Geometry> geometry, const Request& request,
    absl::string_view field, WorkBytes work_bytes, Compute compute,
    const ServiceLimits& limits, v1::BoundingBoxResponse& response) {
  ASSIGN_OR_RETURN(Geometry prepared, std::move(geometry));
  ASSIGN_OR_RETURN(const double tolerance, RequestTolerance(request));
  ASSIGN_OR_RETURN(const uint64_t work,
                   CheckWorkBytes(work_bytes(prepared), limits, field));
  const int dimension = DimensionOf(prepared);
  return PlanBoundingBox(
      dimension, work, tolerance,
      [prepared = std::move(prepared), compute](
          double box_tolerance, const CancellationToken* cancel) {
        return compute(prepared, box_tolerance, cancel);
      },
      limits, response);
}

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_QUERIES_H_
