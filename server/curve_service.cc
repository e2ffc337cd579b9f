// CurveService evaluation RPCs: Evaluate, EvaluateStream and EvaluateBasis.
// Each prepares its request into one Evaluation (prepare_samples.h), plans
// the answer, and runs the core into the response.
#include "curve_service.h"

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "convert.h"
#include "freeform/core/basis.h"
#include "freeform/core/curve.h"
#include "freeform/core/status_macros.h"
#include "plan.h"
#include "prepare_samples.h"

namespace freeform::server {
namespace {

// Adds `orders` arrays of `size` values to a response and returns spans
// over their (uninitialized) storage; `add` makes one array.
template <typename AddArray>
std::vector<absl::Span<double>> OutputArrays(size_t orders, size_t size,
                                             AddArray add) {
  std::vector<absl::Span<double>> spans;
  spans.reserve(orders);
  for (size_t k = 0; k < orders; ++k) {
    spans.push_back(UninitializedArray(*add(), size));
  }
  return spans;
}

// Parameters per thread whose storage is kept between calls (1 MiB).
constexpr size_t kReusedParameters = 1 << 17;

// Evaluates parameters [first, last) into `response`.
absl::Status EvaluateChunk(const Evaluation<Curve>& evaluation, size_t first,
                           size_t last, const ExecutionContext& execution,
                           v1::EvaluateCurveResponse& response) {
  const uint32_t dimension = static_cast<uint32_t>(evaluation.dimension);
  response.set_dimension(dimension);
  response.set_first_index(first);
  response.set_count(static_cast<uint32_t>(last - first));
  const std::vector<absl::Span<double>> output =
      OutputArrays(evaluation.orders, (last - first) * dimension, [&] {
        v1::Points* points = response.add_derivatives();
        points->set_dimension(dimension);
        return points->mutable_coordinates();
      });
  // Stream chunks reuse their thread's storage: fresh pages for every
  // chunk's parameters cost more than generating them.
  thread_local ParameterStorage chunk_storage;
  ParameterStorage call_storage;
  ParameterStorage& storage =
      last - first <= kReusedParameters ? chunk_storage : call_storage;
  return EvaluateCurve(evaluation.geometry,
                       evaluation.parameters.Values(first, last, storage),
                       output, execution);
}

// Parameters per streamed chunk: the request's, or the default, within half
// a message.
size_t StreamChunk(uint32_t requested, uint64_t values_per_parameter,
                   const ServiceLimits& limits) {
  const uint64_t fit =
      std::max<uint64_t>(1, static_cast<uint64_t>(limits.max_message_bytes) /
                                2 / (8 * values_per_parameter));
  return static_cast<size_t>(std::min<uint64_t>(
      fit, requested > 0 ? requested : limits.default_stream_chunk));
}

}  // namespace

grpc::ServerUnaryReactor* CurveServiceImpl::Evaluate(
    grpc::CallbackServerContext* context,
    const v1::EvaluateCurveRequest* request,
    v1::EvaluateCurveResponse* response) {
  return frame_->Unary(
      "CurveService.Evaluate", context, request, response,
      [this, request, response]() -> absl::StatusOr<UnaryWork> {
        const ServiceLimits& limits = frame_->limits();
        absl::StatusOr<Evaluation<Curve>> evaluation =
            PrepareCurveEvaluation(*request, limits);
        if (!evaluation.ok()) return evaluation.status();
        if (absl::Status status = CheckMessageLimit(
                evaluation->Values(), limits, "; use EvaluateStream");
            !status.ok()) {
          return status;
        }
        const CallPlan plan = AnswerPlan(evaluation->Values(), 0, limits);
        return UnaryWork{.plan = plan,
                         .run = [evaluation = *std::move(evaluation),
                                 response](const ExecutionContext& execution) {
                           return EvaluateChunk(evaluation, 0,
                                                evaluation.parameters.size(),
                                                execution, *response);
                         }};
      });
}

grpc::ServerWriteReactor<v1::EvaluateCurveResponse>*
CurveServiceImpl::EvaluateStream(grpc::CallbackServerContext* context,
                                 const v1::EvaluateCurveRequest* request) {
  using Work = StreamWork<v1::EvaluateCurveResponse>;
  return frame_->Stream<v1::EvaluateCurveResponse>(
      "CurveService.EvaluateStream", context, request,
      [this, request]() -> absl::StatusOr<Work> {
        const ServiceLimits& limits = frame_->limits();
        absl::StatusOr<Evaluation<Curve>> evaluation =
            PrepareCurveEvaluation(*request, limits);
        if (!evaluation.ok()) return evaluation.status();
        const size_t count = evaluation->parameters.size();
        const size_t chunk = StreamChunk(
            request->chunk_size(), evaluation->ValuesPerParameter(), limits);
        auto shared =
            std::make_shared<const Evaluation<Curve>>(*std::move(evaluation));
        const uint64_t chunk_values = chunk * shared->ValuesPerParameter();
        return EvenChunks<v1::EvaluateCurveResponse>(
            {.memory_bytes = 2 * 8 * chunk_values * frame_->chunks_in_flight(),
             .heavy = true},
            count, chunk,
            [shared](size_t first, size_t last,
                     v1::EvaluateCurveResponse& response,
                     const ExecutionContext& execution) {
              return EvaluateChunk(*shared, first, last, execution, response);
            });
      });
}

grpc::ServerUnaryReactor* CurveServiceImpl::EvaluateBasis(
    grpc::CallbackServerContext* context,
    const v1::EvaluateBasisRequest* request,
    v1::EvaluateBasisResponse* response) {
  return frame_->Unary(
      "CurveService.EvaluateBasis", context, request, response,
      [this, request, response]() -> absl::StatusOr<UnaryWork> {
        const ServiceLimits& limits = frame_->limits();
        absl::StatusOr<Evaluation<CurveBasis>> evaluation =
            PrepareBasisEvaluation(*request, limits);
        if (!evaluation.ok()) return evaluation.status();
        RETURN_IF_ERROR(CheckMessageLimit(evaluation->Values(), limits));
        return UnaryWork{
            .plan = AnswerPlan(evaluation->Values(), 0, limits),
            .run = [evaluation = *std::move(evaluation),
                    response](const ExecutionContext& execution) {
              const size_t count = evaluation.parameters.size();
              response->set_function_count(
                  static_cast<uint32_t>(evaluation.dimension));
              response->set_count(static_cast<uint32_t>(count));
              const std::vector<absl::Span<double>> output = OutputArrays(
                  evaluation.orders, count * evaluation.dimension, [&] {
                    return response->add_derivatives()->mutable_values();
                  });
              ParameterStorage storage;
              // The core's EvaluateBasis (basis.h), not this RPC's.
              return ::freeform::EvaluateBasis(
                  evaluation.geometry,
                  evaluation.parameters.Values(0, count, storage), output,
                  execution);
            }};
      });
}

}  // namespace freeform::server
