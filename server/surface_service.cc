// SurfaceService evaluation RPCs: Evaluate, EvaluateStream and
// EvaluateBasis.
#include "surface_service.h"

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "convert.h"
#include "freeform/core/basis.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/surface.h"
#include "freeform/core/triangular.h"
#include "plan.h"
#include "prepare_samples.h"
#include "surface_evaluation.h"

namespace freeform::server {

CallPlan EvaluationMemory(const SurfacePlan& plan, uint64_t points,
                          const ServiceLimits& limits) {
  const uint64_t scratch = plan.normals ? 8 * points * 3 * PartialCount(2) : 0;
  return AnswerPlan(points * plan.ValuesPerPoint(), scratch, limits);
}

absl::Status EvaluateChunk(const SurfacePlan& plan, size_t first, size_t last,
                           const ExecutionContext& execution,
                           v1::EvaluateSurfaceResponse& response) {
  const size_t count = last - first;
  const int dimension = plan.dimension;
  const size_t size = count * static_cast<size_t>(dimension);
  response.set_dimension(static_cast<uint32_t>(dimension));
  response.set_first_index(first);
  response.set_count(static_cast<uint32_t>(count));
  std::vector<absl::Span<double>> output;
  for (int total = 0; total <= plan.order; ++total) {
    for (int order_v = 0; order_v <= total; ++order_v) {
      v1::PartialDerivative* partial = response.add_partials();
      partial->set_order_u(static_cast<uint32_t>(total - order_v));
      partial->set_order_v(static_cast<uint32_t>(order_v));
      partial->mutable_values()->set_dimension(
          static_cast<uint32_t>(dimension));
      output.push_back(UninitializedArray(
          *partial->mutable_values()->mutable_coordinates(), size));
    }
  }
  absl::Span<double> normals;
  if (plan.normals) {
    response.mutable_normals()->set_dimension(3);
    normals = UninitializedArray(
        *response.mutable_normals()->mutable_coordinates(), 3 * count);
  }
  const size_t dimensions = static_cast<size_t>(dimension);
  for (const SurfacePlan::Piece& piece : plan.Pieces(first, last)) {
    const size_t points = piece.samples.size();
    std::vector<absl::Span<double>> piece_output;
    piece_output.reserve(output.size());
    for (absl::Span<double> partial : output) {
      piece_output.push_back(
          partial.subspan(piece.offset * dimensions, points * dimensions));
    }
    const absl::Span<double> piece_normals =
        normals.empty() ? normals
                        : normals.subspan(3 * piece.offset, 3 * points);
    RETURN_IF_ERROR(EvaluateSurface(*plan.surface, piece.samples, piece_output,
                                    piece_normals, execution));
  }
  return absl::OkStatus();
}

namespace {

absl::StatusOr<UnaryWork> PlanTensorBasis(
    const v1::EvaluateSurfaceBasisRequest& request, const ServiceLimits& limits,
    v1::EvaluateSurfaceBasisResponse& response) {
  ASSIGN_OR_RETURN(TensorBasisEvaluation evaluation,
                   PrepareTensorBasisEvaluation(request, limits));
  const uint64_t functions = evaluation.FunctionCount();
  const uint64_t count = evaluation.samples.size();
  const uint64_t values = SaturatingProduct(count, functions);
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "parameters"));
  const uint64_t work =
      8 * count *
      (FunctionCountOf(evaluation.u) + FunctionCountOf(evaluation.v));
  return UnaryWork{
      .plan = AnswerPlan(values, work, limits),
      .run = [evaluation = std::move(evaluation), functions, values,
              &response](const ExecutionContext& execution) {
        response.set_function_count(static_cast<uint32_t>(functions));
        response.set_count(static_cast<uint32_t>(evaluation.samples.size()));
        return EvaluateTensorBasis(
            evaluation.u, evaluation.v, evaluation.samples.All(),
            UninitializedArray(*response.mutable_values(), values), execution);
      }};
}

absl::StatusOr<UnaryWork> PlanTriangularBasis(
    const v1::EvaluateSurfaceBasisRequest& request, const ServiceLimits& limits,
    v1::EvaluateSurfaceBasisResponse& response) {
  ASSIGN_OR_RETURN(const TriangularBasisEvaluation evaluation,
                   PrepareTriangularBasisEvaluation(request, limits));
  const uint64_t functions = evaluation.FunctionCount();
  const uint64_t values = SaturatingProduct(evaluation.size(), functions);
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "parameters"));
  return UnaryWork{
      .plan = AnswerPlan(values, 0, limits),
      .run = [evaluation, functions, values,
              &response](const ExecutionContext& execution) {
        response.set_function_count(static_cast<uint32_t>(functions));
        response.set_count(static_cast<uint32_t>(evaluation.size()));
        return PrefixFieldPath(
            EvaluateTriangularBasis(
                evaluation.degree, evaluation.uv,
                UninitializedArray(*response.mutable_values(), values),
                execution),
            "parameters.points");
      }};
}

}  // namespace

grpc::ServerUnaryReactor* SurfaceServiceImpl::Evaluate(
    grpc::CallbackServerContext* context,
    const v1::EvaluateSurfaceRequest* request,
    v1::EvaluateSurfaceResponse* response) {
  return frame_->Unary(
      "SurfaceService.Evaluate", context, request, response,
      [this, request, response]() -> absl::StatusOr<UnaryWork> {
        const ServiceLimits& limits = frame_->limits();
        absl::StatusOr<SurfacePlan> plan =
            PrepareSurfaceEvaluation(*request, limits);
        if (!plan.ok()) return plan.status();
        if (absl::Status status =
                CheckMessageLimit(plan->size() * plan->ValuesPerPoint(), limits,
                                  "; use EvaluateStream");
            !status.ok()) {
          return status;
        }
        const CallPlan memory = EvaluationMemory(*plan, plan->size(), limits);
        return UnaryWork{.plan = memory,
                         .run = [plan = *std::move(plan),
                                 response](const ExecutionContext& execution) {
                           return EvaluateChunk(plan, 0, plan.size(), execution,
                                                *response);
                         }};
      });
}

grpc::ServerWriteReactor<v1::EvaluateSurfaceResponse>*
SurfaceServiceImpl::EvaluateStream(grpc::CallbackServerContext* context,
                                   const v1::EvaluateSurfaceRequest* request) {
  using Work = StreamWork<v1::EvaluateSurfaceResponse>;
  return frame_->Stream<v1::EvaluateSurfaceResponse>(
      "SurfaceService.EvaluateStream", context, request,
      [this, request]() -> absl::StatusOr<Work> {
        const ServiceLimits& limits = frame_->limits();
        absl::StatusOr<SurfacePlan> plan =
            PrepareSurfaceEvaluation(*request, limits);
        if (!plan.ok()) return plan.status();
        const size_t max_points =
            std::max<size_t>(1, static_cast<size_t>(limits.max_message_bytes) /
                                    2 / (plan->ValuesPerPoint() * 8));
        size_t chunk = std::min(max_points, request->chunk_size() > 0
                                                ? request->chunk_size()
                                                : limits.default_stream_chunk);
        const size_t count = plan->size();
        CallPlan memory = EvaluationMemory(*plan, chunk, limits);
        memory.memory_bytes *= frame_->chunks_in_flight();
        memory.heavy = true;
        auto shared = std::make_shared<const SurfacePlan>(*std::move(plan));
        return EvenChunks<v1::EvaluateSurfaceResponse>(
            memory, count, chunk,
            [shared](size_t first, size_t last,
                     v1::EvaluateSurfaceResponse& response,
                     const ExecutionContext& execution) {
              return EvaluateChunk(*shared, first, last, execution, response);
            });
      });
}

grpc::ServerUnaryReactor* SurfaceServiceImpl::EvaluateBasis(
    grpc::CallbackServerContext* context,
    const v1::EvaluateSurfaceBasisRequest* request,
    v1::EvaluateSurfaceBasisResponse* response) {
  return frame_->Unary(
      "SurfaceService.EvaluateBasis", context, request, response,
      [this, request, response]() -> absl::StatusOr<UnaryWork> {
        switch (request->kind_case()) {
          case v1::EvaluateSurfaceBasisRequest::kTensor:
            return PlanTensorBasis(*request, frame_->limits(), *response);
          case v1::EvaluateSurfaceBasisRequest::kTriangularDegree:
            return PlanTriangularBasis(*request, frame_->limits(), *response);
          case v1::EvaluateSurfaceBasisRequest::KIND_NOT_SET:
            break;
        }
        return InvalidFieldError("tensor",
                                 "set a tensor basis or a triangular_degree");
      });
}

}  // namespace freeform::server
