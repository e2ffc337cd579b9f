// CurveService queries of position: ClosestPoint, Intersect and
// BoundingBox.
#include <algorithm>
#include <memory>
#include <utility>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "curve_service.h"
#include "freeform/core/bounding_box.h"
#include "freeform/core/closest_point.h"
#include "freeform/core/intersection.h"
#include "freeform/core/status.h"
#include "plan.h"
#include "prepare.h"
#include "prepare_options.h"
#include "queries.h"

namespace freeform::server {
namespace {

absl::StatusOr<UnaryWork> PlanClosestPoint(
    const v1::CurveClosestPointRequest& request, const ServiceLimits& limits,
    v1::ClosestPointResponse& response) {
  absl::StatusOr<Curve> curve = PrepareCurve(request.curve(), limits);
  if (!curve.ok()) return curve.status();
  absl::StatusOr<uint64_t> work = PieceWorkBytes(
      DecomposedCurveValues(*curve), DecomposedCurvePieces(*curve),
      kPieceRecordBytes, limits, "curve");
  if (!work.ok()) return work.status();
  return PlanClosestPoints(
      GeometryFieldOf(request), DimensionOf(*curve), 1, *work,
      request.queries(), request.options(),
      [curve = *std::move(curve)](const PointsView& queries,
                                  const ClosestPointOptions& options,
                                  const ExecutionContext& execution) {
        return CurveClosestPoints(curve, queries, options, execution);
      },
      limits, response);
}

void WriteIntersections(const CurveIntersections& found,
                        v1::IntersectCurvesResponse& response) {
  response.set_dimension(static_cast<uint32_t>(found.dimension));
  response.mutable_first_parameters()->Add(found.first_parameters.begin(),
                                           found.first_parameters.end());
  response.mutable_second_parameters()->Add(found.second_parameters.begin(),
                                            found.second_parameters.end());
  response.mutable_points()->set_dimension(
      static_cast<uint32_t>(found.dimension));
  response.mutable_points()->mutable_coordinates()->Add(found.points.begin(),
                                                        found.points.end());
  response.mutable_first_intervals()->Add(found.first_intervals.begin(),
                                          found.first_intervals.end());
  response.mutable_second_intervals()->Add(found.second_intervals.begin(),
                                           found.second_intervals.end());
}

absl::StatusOr<UnaryWork> PlanIntersect(
    const v1::IntersectCurvesRequest& request, const ServiceLimits& limits,
    v1::IntersectCurvesResponse& response) {
  absl::StatusOr<Curve> first = PrepareCurve(request.first(), limits, "first");
  if (!first.ok()) return first.status();
  absl::StatusOr<Curve> second =
      PrepareCurve(request.second(), limits, "second");
  if (!second.ok()) return second.status();
  absl::StatusOr<uint64_t> work = PieceWorkBytes(
      DecomposedCurveValues(*first), DecomposedCurvePieces(*first),
      kPartRecordBytes, limits, "first");
  if (!work.ok()) return work.status();
  absl::StatusOr<uint64_t> second_work = PieceWorkBytes(
      DecomposedCurveValues(*second), DecomposedCurvePieces(*second),
      kPartRecordBytes, limits, "second");
  if (!second_work.ok()) return second_work.status();
  const int dimension = DimensionOf(*first);
  if (DimensionOf(*second) != dimension) {
    return InvalidFieldError(
        "second", absl::StrCat("must have the first curve's dimension ",
                               dimension, ", not ", DimensionOf(*second)));
  }
  // A point holds two parameters and a point, an overlap four parameters.
  const uint64_t per_result =
      std::max<uint64_t>(2 + static_cast<uint64_t>(dimension), 4);
  absl::StatusOr<IntersectionOptions> options =
      ToCore(request.options(), per_result, limits);
  if (!options.ok()) return options.status();
  const uint64_t values = options->max_results * per_result;
  // The search keeps its candidates besides the answer.
  const uint64_t candidates =
      IntersectionCandidateBytes(options->max_results, dimension);
  return UnaryWork{
      .plan = {.memory_bytes =
                   AnswerPlan(values,
                              8 * values + *work + *second_work + candidates,
                              limits)
                       .memory_bytes,
               .heavy = true},
      .run = [first = *std::move(first), second = *std::move(second),
              options = *options,
              &response](const ExecutionContext& execution) -> absl::Status {
        absl::StatusOr<CurveIntersections> found =
            IntersectCurves(first, second, options, execution.cancellation);
        if (!found.ok()) return IntersectionError(found.status());
        WriteIntersections(*found, response);
        return absl::OkStatus();
      }};
}

absl::StatusOr<UnaryWork> PlanBoundingBox(
    const v1::CurveBoundingBoxRequest& request, const ServiceLimits& limits,
    v1::BoundingBoxResponse& response) {
  return PlanBoundingBoxOf(
      PrepareCurve(request.curve(), limits), request, "curve",
      [](const Curve& curve) { return CurveBoundingBoxBytes(curve); },
      [](const Curve& curve, double tolerance,
         const CancellationToken* cancel) {
        return CurveBoundingBox(curve, tolerance, cancel);
      },
      limits, response);
}

}  // namespace

grpc::ServerUnaryReactor* CurveServiceImpl::ClosestPoint(
    grpc::CallbackServerContext* context,
    const v1::CurveClosestPointRequest* request,
    v1::ClosestPointResponse* response) {
  return frame_->Unary("CurveService.ClosestPoint", context, request, response,
                       [this, request, response] {
                         return PlanClosestPoint(*request, frame_->limits(),
                                                 *response);
                       });
}

grpc::ServerUnaryReactor* CurveServiceImpl::Intersect(
    grpc::CallbackServerContext* context,
    const v1::IntersectCurvesRequest* request,
    v1::IntersectCurvesResponse* response) {
  return frame_->Unary("CurveService.Intersect", context, request, response,
                       [this, request, response] {
                         return PlanIntersect(*request, frame_->limits(),
                                              *response);
                       });
}

grpc::ServerUnaryReactor* CurveServiceImpl::BoundingBox(
    grpc::CallbackServerContext* context,
    const v1::CurveBoundingBoxRequest* request,
    v1::BoundingBoxResponse* response) {
  return frame_->Unary("CurveService.BoundingBox", context, request, response,
                       [this, request, response] {
                         return PlanBoundingBox(*request, frame_->limits(),
                                                *response);
                       });
}

}  // namespace freeform::server
