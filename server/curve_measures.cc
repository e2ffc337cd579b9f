// CurveService queries of shape along a curve: ArcLength,
// ParametersAtArcLength, SampleByArcLength, Curvature and
// RotationMinimizingFrames.
#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "convert.h"
#include "curve_service.h"
#include "freeform/core/arc_length.h"
#include "freeform/core/differential_geometry.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "plan.h"
#include "prepare.h"
#include "prepare_options.h"
#include "prepare_samples.h"
#include "queries.h"

namespace freeform::server {
namespace {

// CheckCount returns RESOURCE_EXHAUSTED naming `field` when `count` items
// are over the parameter limit.
absl::Status CheckCount(uint64_t count, const ServiceLimits& limits,
                        absl::string_view field) {
  if (count <= limits.max_parameters) return absl::OkStatus();
  return ExhaustedFieldError(
      field, absl::StrCat(count, " values exceed the server's limit of ",
                          limits.max_parameters, " (--max_parameters)"));
}

// ArcLengthWork returns the working memory of an arc-length call on
// `curve` that builds `tables` length tables at once (ArcLengthWorkValues),
// or RESOURCE_EXHAUSTED naming "curve" when it is over the memory budget.
absl::StatusOr<uint64_t> ArcLengthWork(const Curve& curve, size_t tables,
                                       const ServiceLimits& limits) {
  const uint64_t bytes =
      SaturatingProduct(ArcLengthWorkValues(curve, tables), 8);
  if (bytes <= limits.memory_budget_bytes) return bytes;
  return ExhaustedFieldError(
      "curve", absl::StrCat("its arc-length tables would take ", bytes >> 20,
                            " MiB, over the server's memory budget of ",
                            limits.memory_budget_bytes >> 20, " MiB"));
}

// LengthError names the request's fields for the core's errors of an
// arc-length call: "weights" is the curve's (a length no double parameter
// reaches within the tolerance). The intervals' ends are checked before,
// where they are prepared (PrepareInterval, PrepareArcLengthStart).
absl::Status LengthError(const absl::Status& status,
                         const google::protobuf::Message& request) {
  return QueryError(status, GeometryFieldOf(request), "tolerance");
}

// ParameterError renames the core's "parameters[i]" (a parameter where the
// curve stands still) to the request's path of that parameter.
absl::Status ParameterError(const absl::Status& status,
                            const v1::Parameters& parameters) {
  const std::optional<std::string> field = FieldPathOf(status);
  if (!field.has_value() || !absl::StartsWith(*field, "parameters[")) {
    return status;
  }
  const std::string index = field->substr(std::string("parameters").size());
  return InvalidFieldError(
      parameters.has_list() ? absl::StrCat("parameters.list.values", index)
                            : "parameters.range",
      absl::StrCat("value ", index, ": ", FieldRuleOf(status)));
}

// PointsAt writes the curve's points at `parameters` into `points`.
absl::Status PointsAt(const Curve& curve, absl::Span<const double> parameters,
                      v1::Points& points, const ExecutionContext& execution) {
  const int dimension = DimensionOf(curve);
  points.set_dimension(static_cast<uint32_t>(dimension));
  const absl::Span<double> output[] = {
      UninitializedArray(*points.mutable_coordinates(),
                         parameters.size() * static_cast<size_t>(dimension))};
  return EvaluateCurve(curve, parameters, output, execution);
}

// Answers of parameters and points: their size per parameter.
uint64_t ParameterAndPointValues(const Curve& curve) {
  return 1 + static_cast<uint64_t>(DimensionOf(curve));
}

// ArcLengthPlan returns the plan of an arc-length query of `curve` whose
// answer holds `values` doubles and whose work takes `work_bytes` (its
// length tables, ArcLengthWork) besides the records of its pieces: heavy
// whatever its size.
CallPlan ArcLengthPlan(const Curve& curve, uint64_t values, uint64_t work_bytes,
                       const ServiceLimits& limits) {
  return {.memory_bytes = AnswerPlan(values,
                                     work_bytes + DecomposedCurvePieces(curve) *
                                                      kArcLengthPieceBytes,
                                     limits)
                              .memory_bytes,
          .heavy = true};
}

absl::StatusOr<UnaryWork> PlanArcLength(const v1::ArcLengthRequest& request,
                                        const ServiceLimits& limits,
                                        v1::ArcLengthResponse& response) {
  absl::StatusOr<Curve> curve = PrepareCurve(request.curve(), limits);
  if (!curve.ok()) return curve.status();
  absl::StatusOr<double> tolerance = RequestTolerance(request);
  if (!tolerance.ok()) return tolerance.status();
  const uint64_t count =
      std::max<uint64_t>(1, static_cast<uint64_t>(request.intervals_size()));
  RETURN_IF_ERROR(CheckCount(count, limits, "intervals"));
  std::vector<double> intervals;
  intervals.reserve(2 * count);
  for (int i = 0; i < request.intervals_size(); ++i) {
    ASSIGN_OR_RETURN(
        const ParameterDomain interval,
        PrepareInterval(request.intervals(i), *curve,
                        IndexedField("intervals", static_cast<size_t>(i))));
    intervals.push_back(interval.start);
    intervals.push_back(interval.end);
  }
  if (intervals.empty()) {
    const ParameterDomain domain = DomainOf(*curve);
    intervals = {domain.start, domain.end};
  }
  // One table per thread of the pool.
  absl::StatusOr<uint64_t> work =
      ArcLengthWork(*curve, 1 + DefaultMaxHelpers(), limits);
  if (!work.ok()) return work.status();
  return UnaryWork{
      .plan = ArcLengthPlan(*curve, count, 16 * count + *work, limits),
      .run = [curve = *std::move(curve), intervals = std::move(intervals),
              tolerance = *tolerance, &request,
              &response](const ExecutionContext& execution) -> absl::Status {
        return LengthError(
            ArcLengths(curve, intervals, tolerance,
                       UninitializedArray(*response.mutable_lengths(),
                                          intervals.size() / 2),
                       execution),
            request);
      }};
}

absl::StatusOr<UnaryWork> PlanParametersAtArcLength(
    const v1::ParametersAtArcLengthRequest& request,
    const ServiceLimits& limits, v1::ParametersAtArcLengthResponse& response) {
  absl::StatusOr<Curve> curve = PrepareCurve(request.curve(), limits);
  if (!curve.ok()) return curve.status();
  absl::StatusOr<double> tolerance = RequestTolerance(request);
  if (!tolerance.ok()) return tolerance.status();
  const uint64_t count = static_cast<uint64_t>(request.lengths_size());
  if (count == 0) {
    return InvalidFieldError("lengths", "needs at least one length");
  }
  RETURN_IF_ERROR(CheckCount(count, limits, "lengths"));
  const uint64_t values = count * ParameterAndPointValues(*curve);
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "lengths"));
  ASSIGN_OR_RETURN(const double start, PrepareArcLengthStart(request, *curve));
  absl::StatusOr<uint64_t> work = ArcLengthWork(*curve, 1, limits);
  if (!work.ok()) return work.status();
  return UnaryWork{
      .plan = ArcLengthPlan(*curve, values, *work, limits),
      .run = [curve = *std::move(curve), start,
              lengths = SpanOf(request.lengths()), tolerance = *tolerance,
              &request,
              &response](const ExecutionContext& execution) -> absl::Status {
        const absl::Span<double> parameters =
            UninitializedArray(*response.mutable_parameters(), lengths.size());
        if (absl::Status status = ParametersAtArcLengths(
                curve, start, lengths, tolerance, parameters, execution);
            !status.ok()) {
          return LengthError(status, request);
        }
        return PointsAt(curve, parameters, *response.mutable_points(),
                        execution);
      }};
}

absl::StatusOr<UnaryWork> PlanSampleByArcLength(
    const v1::SampleByArcLengthRequest& request, const ServiceLimits& limits,
    v1::SampleByArcLengthResponse& response) {
  absl::StatusOr<Curve> curve = PrepareCurve(request.curve(), limits);
  if (!curve.ok()) return curve.status();
  absl::StatusOr<double> tolerance = RequestTolerance(request);
  if (!tolerance.ok()) return tolerance.status();
  const uint64_t count = request.count();
  if (count < 2) {
    return InvalidFieldError("count",
                             absl::StrCat("must be at least 2, got ", count));
  }
  RETURN_IF_ERROR(CheckCount(count, limits, "count"));
  const uint64_t values = count * ParameterAndPointValues(*curve);
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "count"));
  ASSIGN_OR_RETURN(const ParameterDomain interval,
                   PrepareInterval(request.interval(), *curve, "interval"));
  const double start = interval.start, end = interval.end;
  absl::StatusOr<uint64_t> work = ArcLengthWork(*curve, 1, limits);
  if (!work.ok()) return work.status();
  return UnaryWork{
      .plan = ArcLengthPlan(*curve, values, *work, limits),
      .run = [curve = *std::move(curve), start, end, count,
              tolerance = *tolerance, &request,
              &response](const ExecutionContext& execution) -> absl::Status {
        const absl::Span<double> parameters = UninitializedArray(
            *response.mutable_parameters(), static_cast<size_t>(count));
        RETURN_IF_ERROR(LengthError(
            EqualArcLengthParameters(curve, start, end,
                                     static_cast<size_t>(count), tolerance,
                                     parameters, execution),
            request));
        return PointsAt(curve, parameters, *response.mutable_points(),
                        execution);
      }};
}

// ScaledCopyBytes returns the memory of the copies of the curve and of the
// parameters rescaled by powers of two that curvature and frames evaluate
// (core/differential_geometry.h): at most the curve's Bezier pieces'
// values, and one value per parameter.
uint64_t ScaledCopyBytes(const Curve& curve,
                         const std::vector<double>& parameters) {
  return SaturatingProduct(DecomposedCurveValues(curve) + parameters.size(), 8);
}

// Points of `dimension` coordinates in a response, `count` of them, or none
// when `size` is 0 (a buffer the dimension does not have).
absl::Span<double> PointArray(v1::Points& points, int dimension, size_t size) {
  if (size == 0) return {};
  points.set_dimension(static_cast<uint32_t>(dimension));
  return UninitializedArray(*points.mutable_coordinates(), size);
}

absl::StatusOr<UnaryWork> PlanCurvature(
    const v1::CurveCurvatureRequest& request, const ServiceLimits& limits,
    v1::CurveCurvatureResponse& response) {
  absl::StatusOr<Curve> curve = PrepareCurve(request.curve(), limits);
  if (!curve.ok()) return curve.status();
  absl::StatusOr<std::vector<double>> parameters =
      ResolveParameters(request.parameters(), *curve, limits);
  if (!parameters.ok()) return parameters.status();
  const int dimension = DimensionOf(*curve);
  const FrenetFrameSizes sizes = FrenetSizes(dimension, parameters->size());
  const uint64_t values = uint64_t{sizes.tangents} + sizes.normals +
                          sizes.binormals + sizes.curvatures + sizes.torsions +
                          sizes.statuses;
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "parameters"));
  return UnaryWork{
      .plan = AnswerPlan(
          values, 8 * values + ScaledCopyBytes(*curve, *parameters), limits),
      .run = [curve = *std::move(curve), parameters = *std::move(parameters),
              dimension, sizes,
              &response](const ExecutionContext& execution) -> absl::Status {
        response.set_dimension(static_cast<uint32_t>(dimension));
        std::vector<CurvePointStatus> statuses(sizes.statuses);
        const FrenetFrameOutput output = {
            .tangents = PointArray(*response.mutable_tangents(), dimension,
                                   sizes.tangents),
            .normals = PointArray(*response.mutable_normals(), dimension,
                                  sizes.normals),
            .binormals =
                PointArray(*response.mutable_binormals(), 3, sizes.binormals),
            .curvatures = UninitializedArray(*response.mutable_curvatures(),
                                             sizes.curvatures),
            .torsions = sizes.torsions == 0
                            ? absl::Span<double>()
                            : UninitializedArray(*response.mutable_torsions(),
                                                 sizes.torsions),
            .statuses = absl::MakeSpan(statuses)};
        RETURN_IF_ERROR(
            EvaluateFrenetFrames(curve, parameters, output, execution));
        response.mutable_statuses()->Reserve(static_cast<int>(statuses.size()));
        for (const CurvePointStatus status : statuses) {
          response.add_statuses(static_cast<v1::CurvePointStatus>(status));
        }
        return absl::OkStatus();
      }};
}

absl::StatusOr<UnaryWork> PlanRotationMinimizingFrames(
    const v1::RotationMinimizingFramesRequest& request,
    const ServiceLimits& limits,
    v1::RotationMinimizingFramesResponse& response) {
  absl::StatusOr<Curve> curve = PrepareCurve(request.curve(), limits);
  if (!curve.ok()) return curve.status();
  absl::StatusOr<std::vector<double>> parameters =
      ResolveParameters(request.parameters(), *curve, limits);
  if (!parameters.ok()) return parameters.status();
  const int dimension = DimensionOf(*curve);
  if (dimension < 2) {
    return InvalidFieldError("curve",
                             "rotation-minimizing frames need a curve of "
                             "dimension 2 or more");
  }
  const RotationMinimizingFrameSizes sizes =
      RotationMinimizingSizes(dimension, parameters->size());
  const uint64_t values =
      uint64_t{sizes.tangents} + sizes.references + sizes.third;
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "parameters"));
  return UnaryWork{
      .plan = AnswerPlan(
          values, 8 * values + ScaledCopyBytes(*curve, *parameters), limits),
      .run = [curve = *std::move(curve), parameters = *std::move(parameters),
              reference = SpanOf(request.initial_reference()), dimension, sizes,
              request = &request.parameters(),
              &response](const ExecutionContext& execution) {
        response.set_dimension(static_cast<uint32_t>(dimension));
        const RotationMinimizingFrameOutput output = {
            .tangents = PointArray(*response.mutable_tangents(), dimension,
                                   sizes.tangents),
            .references = PointArray(*response.mutable_references(), dimension,
                                     sizes.references),
            .third = PointArray(*response.mutable_third(), 3, sizes.third)};
        return ParameterError(
            EvaluateRotationMinimizingFrames(curve, parameters, reference,
                                             output, execution),
            *request);
      }};
}

}  // namespace

grpc::ServerUnaryReactor* CurveServiceImpl::ArcLength(
    grpc::CallbackServerContext* context, const v1::ArcLengthRequest* request,
    v1::ArcLengthResponse* response) {
  return frame_->Unary("CurveService.ArcLength", context, request, response,
                       [this, request, response] {
                         return PlanArcLength(*request, frame_->limits(),
                                              *response);
                       });
}

grpc::ServerUnaryReactor* CurveServiceImpl::ParametersAtArcLength(
    grpc::CallbackServerContext* context,
    const v1::ParametersAtArcLengthRequest* request,
    v1::ParametersAtArcLengthResponse* response) {
  return frame_->Unary("CurveService.ParametersAtArcLength", context, request,
                       response, [this, request, response] {
                         return PlanParametersAtArcLength(
                             *request, frame_->limits(), *response);
                       });
}

grpc::ServerUnaryReactor* CurveServiceImpl::SampleByArcLength(
    grpc::CallbackServerContext* context,
    const v1::SampleByArcLengthRequest* request,
    v1::SampleByArcLengthResponse* response) {
  return frame_->Unary("CurveService.SampleByArcLength", context, request,
                       response, [this, request, response] {
                         return PlanSampleByArcLength(
                             *request, frame_->limits(), *response);
                       });
}

grpc::ServerUnaryReactor* CurveServiceImpl::Curvature(
    grpc::CallbackServerContext* context,
    const v1::CurveCurvatureRequest* request,
    v1::CurveCurvatureResponse* response) {
  return frame_->Unary("CurveService.Curvature", context, request, response,
                       [this, request, response] {
                         return PlanCurvature(*request, frame_->limits(),
                                              *response);
                       });
}

grpc::ServerUnaryReactor* CurveServiceImpl::RotationMinimizingFrames(
    grpc::CallbackServerContext* context,
    const v1::RotationMinimizingFramesRequest* request,
    v1::RotationMinimizingFramesResponse* response) {
  return frame_->Unary("CurveService.RotationMinimizingFrames", context,
                       request, response, [this, request, response] {
                         return PlanRotationMinimizingFrames(
                             *request, frame_->limits(), *response);
                       });
}

}  // namespace freeform::server
