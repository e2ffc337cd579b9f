// CurveService RPCs that refine or cut curves: Split, InsertKnots,
// Decompose, Subdivide (polygons) and Tessellate. Each visits the prepared
// curve, so every curve kind is handled (or refused by name) explicitly.
#include <algorithm>

#include "absl/strings/str_cat.h"
#include "convert.h"
#include "curve_service.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/subdivision.h"
#include "freeform/core/tessellation.h"
#include "geometry_out.h"
#include "plan.h"
#include "prepare.h"
#include "prepare_options.h"
#include "visit.h"

namespace freeform::server {
namespace {

// Values of `count` control points of a (rational) curve of `dimension`.
uint64_t CurveValues(uint64_t count, int dimension, bool rational) {
  return SaturatingProduct(
      count, static_cast<uint64_t>(dimension) + (rational ? 1 : 0));
}

absl::StatusOr<UnaryWork> PlanBezierSplit(const BezierCurve& bezier,
                                          const v1::SplitCurveRequest& request,
                                          const ServiceLimits& limits,
                                          v1::SplitCurveResponse& response) {
  const uint64_t cuts = static_cast<uint64_t>(request.parameters_size());
  if (cuts == 0) {
    return InvalidFieldError("parameters", "needs at least one parameter");
  }
  RETURN_IF_ERROR(CheckPointLimit(cuts, limits, "parameters"));
  const BezierCurveView view = bezier.view();
  const uint64_t values = SaturatingProduct(
      cuts + 1, CurveValues(view.control_points.size(), bezier.dimension(),
                            view.rational()));
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "parameters"));
  return UnaryWork{
      .plan = AnswerPlan(values, 8 * values, limits),
      .run = [bezier, &request,
              &response](const ExecutionContext& execution) -> absl::Status {
        absl::StatusOr<std::vector<BezierCurveData>> pieces =
            SplitBezierCurve(bezier.view(), SpanOf(request.parameters()),
                             execution.cancellation);
        if (!pieces.ok()) return pieces.status();
        for (const BezierCurveData& piece : *pieces) {
          if (execution.cancellation != nullptr &&
              execution.cancellation->IsCancelled()) {
            return execution.cancellation->status();
          }
          ToProto(piece, *response.add_pieces());
        }
        return absl::OkStatus();
      }};
}

absl::StatusOr<UnaryWork> PlanSplit(const v1::SplitCurveRequest& request,
                                    const ServiceLimits& limits,
                                    v1::SplitCurveResponse& response) {
  absl::StatusOr<Curve> curve = PrepareCurve(request.curve(), limits);
  if (!curve.ok()) return curve.status();
  return std::visit<absl::StatusOr<UnaryWork>>(
      Overloaded{[&](const BezierCurve& bezier) {
                   return PlanBezierSplit(bezier, request, limits, response);
                 },
                 Refuse<BSplineCurve, LagrangeCurve, HermiteCurve>{
                     "curve",
                     "Split takes a Bezier or power-form curve; use "
                     "InsertKnots or Decompose for B-splines"}},
      *curve);
}

absl::StatusOr<UnaryWork> PlanBSplineInsert(
    const BSplineCurve& bspline, const v1::InsertKnotsRequest& request,
    const ServiceLimits& limits, v1::InsertKnotsResponse& response) {
  const BSplineCurveView view = bspline.view();
  const uint64_t count =
      view.control_points.size() + static_cast<uint64_t>(request.knots_size());
  RETURN_IF_ERROR(CheckPointLimit(count, limits, "knots"));
  const uint64_t values =
      CurveValues(count, bspline.dimension(), view.rational()) + count +
      static_cast<uint64_t>(view.degree) + 1;
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "knots"));
  return UnaryWork{
      .plan = AnswerPlan(values, 8 * values, limits),
      .run = [view, &request,
              &response](const ExecutionContext& execution) -> absl::Status {
        absl::StatusOr<BSplineCurveData> refined =
            InsertKnots(view, SpanOf(request.knots()), execution.cancellation);
        if (!refined.ok()) return refined.status();
        ToProto(*refined, *response.mutable_curve());
        return absl::OkStatus();
      }};
}

absl::StatusOr<UnaryWork> PlanInsert(const v1::InsertKnotsRequest& request,
                                     const ServiceLimits& limits,
                                     v1::InsertKnotsResponse& response) {
  absl::StatusOr<Curve> curve = PrepareCurve(request.curve(), limits);
  if (!curve.ok()) return curve.status();
  return std::visit<absl::StatusOr<UnaryWork>>(
      Overloaded{[&](const BSplineCurve& bspline) {
                   return PlanBSplineInsert(bspline, request, limits, response);
                 },
                 Refuse<BezierCurve, LagrangeCurve, HermiteCurve>{
                     "curve", "InsertKnots takes a B-spline or NURBS curve"}},
      *curve);
}

// Bytes of one Bezier segment beside its doubles: the core's record of it
// and its array's block, and in the answer its Curve, BezierCurve and
// Points messages with their blocks and its pointer in the repeated field
// (grown by doubling).
constexpr uint64_t kSegmentRecordBytes =
    sizeof(BezierCurveData) + sizeof(v1::Curve) + sizeof(v1::BezierCurve) +
    sizeof(v1::Points) + 5 * 32 + 2 * sizeof(void*);

absl::StatusOr<UnaryWork> PlanDecompose(
    const v1::DecomposeCurveRequest& request, const ServiceLimits& limits,
    v1::DecomposeCurveResponse& response) {
  absl::StatusOr<Curve> curve = PrepareCurve(request.curve(), limits);
  if (!curve.ok()) return curve.status();
  const uint64_t values = DecomposedCurveValues(*curve);
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "curve"));
  // Cutting holds the knot-refined control points beside the pieces, which
  // then live beside the answer; every segment has its records.
  return UnaryWork{
      .plan = AnswerPlan(
          values,
          8 * values + DecomposedCurvePieces(*curve) * kSegmentRecordBytes,
          limits),
      .run = [curve = *std::move(curve),
              &response](const ExecutionContext& execution) -> absl::Status {
        absl::StatusOr<BezierDecomposition> decomposition =
            DecomposeCurve(curve, execution.cancellation);
        if (!decomposition.ok()) return decomposition.status();
        for (const BezierCurveData& segment : decomposition->segments) {
          ToProto(segment, *response.add_segments());
        }
        response.mutable_breakpoints()->Add(decomposition->breakpoints.begin(),
                                            decomposition->breakpoints.end());
        return absl::OkStatus();
      }};
}

// Points after `levels` doublings of `count` points (an upper bound: open
// polygons lose a few per level), saturating.
uint64_t SubdividedCount(uint64_t count, uint32_t levels) {
  if (levels >= 63) return UINT64_MAX;
  return SaturatingProduct(count, uint64_t{1} << levels);
}

absl::StatusOr<UnaryWork> PlanSubdivide(const v1::SubdivideRequest& request,
                                        const ServiceLimits& limits,
                                        v1::SubdivideResponse& response) {
  absl::StatusOr<PointsView> polygon =
      PreparePoints(request.polygon(), limits, "polygon");
  if (!polygon.ok()) return polygon.status();
  absl::StatusOr<SubdivisionScheme> scheme = ToCore(request.scheme());
  if (!scheme.ok()) return scheme.status();
  if (request.levels() < 1) {
    return InvalidFieldError("levels", "must be at least 1");
  }
  if (request.degree() > static_cast<uint32_t>(kMaxSubdivisionDegree)) {
    return InvalidFieldError(
        "degree", absl::StrCat("must be at most ", kMaxSubdivisionDegree,
                               ", got ", request.degree()));
  }
  const uint64_t last =
      SaturatingProduct(SubdividedCount(polygon->size(), request.levels()),
                        static_cast<uint64_t>(polygon->dimension));
  // Every level is computed; with keep_levels every level is answered too,
  // and the levels before the last add up to less than the last.
  const uint64_t values = request.keep_levels() ? 3 * last : last;
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "levels"));
  return UnaryWork{
      .plan = AnswerPlan(values, 16 * last, limits),
      .run = [polygon = *polygon, scheme = *scheme, &request,
              &response](const ExecutionContext& execution) -> absl::Status {
        absl::StatusOr<std::vector<std::vector<double>>> levels =
            SubdividePolygon(polygon, request.closed(), scheme,
                             static_cast<int>(request.degree()),
                             static_cast<int>(request.levels()),
                             execution.cancellation);
        if (!levels.ok()) return levels.status();
        const uint32_t dimension = request.polygon().dimension();
        for (size_t level = 0; level < levels->size(); ++level) {
          const bool is_last = level + 1 == levels->size();
          if (!is_last && !request.keep_levels()) continue;
          v1::Points* out =
              is_last ? response.mutable_polygon() : response.add_levels();
          out->set_dimension(dimension);
          out->mutable_coordinates()->Add((*levels)[level].begin(),
                                          (*levels)[level].end());
          if (is_last && request.keep_levels()) *response.add_levels() = *out;
        }
        return absl::OkStatus();
      }};
}

absl::StatusOr<UnaryWork> PlanTessellate(
    const v1::TessellateCurveRequest& request, const ServiceLimits& limits,
    v1::TessellateCurveResponse& response) {
  absl::StatusOr<Curve> curve = PrepareCurve(request.curve(), limits);
  if (!curve.ok()) return curve.status();
  ASSIGN_OR_RETURN(const double tolerance,
                   GivenTolerance(request.tolerance(), "tolerance"));
  const int dimension = DimensionOf(*curve);
  // A point costs its coordinates and its parameter.
  const uint64_t per_point = static_cast<uint64_t>(dimension) + 1;
  const uint64_t fit =
      static_cast<uint64_t>(limits.max_message_bytes) / 8 / per_point;
  const uint64_t requested =
      request.max_points() > 0 ? request.max_points() : limits.max_parameters;
  const uint64_t cap = std::min({requested, uint64_t{limits.max_parameters},
                                 fit, limits.max_output_values / per_point});
  // The polyline's points are known to be at most `bound` before the work
  // (SIZE_MAX when unknown: a rational curve with a weight of 0).
  const size_t bound = CurvePointBound(*curve, tolerance);
  const uint64_t values = std::min<uint64_t>(cap, bound) * per_point;
  return UnaryWork{
      .plan = AnswerPlan(values, 8 * values, limits),
      .run = [curve = *std::move(curve), tolerance, cap,
              &response](const ExecutionContext& execution) -> absl::Status {
        absl::StatusOr<Polyline> polyline = TessellateCurve(
            curve, tolerance, static_cast<size_t>(cap), execution.cancellation);
        if (!polyline.ok()) return polyline.status();
        response.mutable_points()->set_dimension(
            static_cast<uint32_t>(polyline->dimension));
        response.mutable_points()->mutable_coordinates()->Add(
            polyline->points.begin(), polyline->points.end());
        response.mutable_parameters()->Add(polyline->parameters.begin(),
                                           polyline->parameters.end());
        return absl::OkStatus();
      }};
}

}  // namespace

grpc::ServerUnaryReactor* CurveServiceImpl::Split(
    grpc::CallbackServerContext* context, const v1::SplitCurveRequest* request,
    v1::SplitCurveResponse* response) {
  return frame_->Unary("CurveService.Split", context, request, response,
                       [this, request, response] {
                         return PlanSplit(*request, frame_->limits(),
                                          *response);
                       });
}

grpc::ServerUnaryReactor* CurveServiceImpl::InsertKnots(
    grpc::CallbackServerContext* context, const v1::InsertKnotsRequest* request,
    v1::InsertKnotsResponse* response) {
  return frame_->Unary("CurveService.InsertKnots", context, request, response,
                       [this, request, response] {
                         return PlanInsert(*request, frame_->limits(),
                                           *response);
                       });
}

grpc::ServerUnaryReactor* CurveServiceImpl::Decompose(
    grpc::CallbackServerContext* context,
    const v1::DecomposeCurveRequest* request,
    v1::DecomposeCurveResponse* response) {
  return frame_->Unary("CurveService.Decompose", context, request, response,
                       [this, request, response] {
                         return PlanDecompose(*request, frame_->limits(),
                                              *response);
                       });
}

grpc::ServerUnaryReactor* CurveServiceImpl::Subdivide(
    grpc::CallbackServerContext* context, const v1::SubdivideRequest* request,
    v1::SubdivideResponse* response) {
  return frame_->Unary("CurveService.Subdivide", context, request, response,
                       [this, request, response] {
                         return PlanSubdivide(*request, frame_->limits(),
                                              *response);
                       });
}

grpc::ServerUnaryReactor* CurveServiceImpl::Tessellate(
    grpc::CallbackServerContext* context,
    const v1::TessellateCurveRequest* request,
    v1::TessellateCurveResponse* response) {
  return frame_->Unary("CurveService.Tessellate", context, request, response,
                       [this, request, response] {
                         return PlanTessellate(*request, frame_->limits(),
                                               *response);
                       });
}

}  // namespace freeform::server
