// CurveService evaluation RPCs: Evaluate, EvaluateStream and EvaluateBasis.
#include "curve_service.h"

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "convert.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "plan.h"
#include "prepare.h"
#include "prepare_options.h"

namespace freeform::server {
namespace {

// What an evaluation resolves to before any math runs: a curve or a basis,
// the parameters, and the orders wanted.
template <typename Geometry>
struct Evaluation {
  Geometry geometry;
  ParameterSet parameters;
  size_t orders = 1;  // derivative orders 0..orders-1
  int dimension = 0;  // values per point and order

  uint64_t ValuesPerParameter() const {
    return orders * static_cast<uint64_t>(dimension);
  }
  uint64_t Values() const { return parameters.size() * ValuesPerParameter(); }

  absl::Status Run(absl::Span<const double> values, CurveOutput output,
                   const ExecutionContext& execution) const {
    if constexpr (std::is_same_v<Geometry, Curve>) {
      return EvaluateCurve(geometry, values, output, execution);
    } else {
      return EvaluateBasis(geometry, values, output, execution);
    }
  }
};

absl::Status CheckDerivativeOrder(uint32_t order, const ServiceLimits& limits) {
  if (order > static_cast<uint32_t>(limits.max_derivative_order)) {
    return InvalidFieldError(
        "derivative_order",
        absl::StrCat("must be at most ", limits.max_derivative_order, ", got ",
                     order));
  }
  return absl::OkStatus();
}

// Resolves the parameters against the domain and checks the output limit.
template <typename Geometry>
absl::StatusOr<Evaluation<Geometry>> Resolve(absl::StatusOr<Geometry> geometry,
                                             int dimension,
                                             const v1::Parameters& parameters,
                                             uint32_t derivative_order,
                                             const ServiceLimits& limits) {
  if (!geometry.ok()) return geometry.status();
  const ParameterDomain domain = DomainOf(*geometry);
  absl::StatusOr<ParameterSet> resolved = ParameterSet::Resolve(
      parameters, domain.start, domain.end, limits.max_parameters);
  if (!resolved.ok()) return PrefixFieldPath(resolved.status(), "parameters");
  Evaluation<Geometry> evaluation{.geometry = *std::move(geometry),
                                  .parameters = *std::move(resolved),
                                  .orders = derivative_order + size_t{1},
                                  .dimension = dimension};
  RETURN_IF_ERROR(CheckOutputLimit(evaluation.Values(), limits));
  return evaluation;
}

absl::StatusOr<Evaluation<Curve>> CurveEvaluation(
    const v1::EvaluateCurveRequest& request, const ServiceLimits& limits) {
  RETURN_IF_ERROR(CheckDerivativeOrder(request.derivative_order(), limits));
  RETURN_IF_ERROR(CheckEnum(request.bezier_algorithm(),
                            v1::BezierAlgorithm_IsValid, "bezier_algorithm"));
  absl::StatusOr<Curve> curve = PrepareCurveToEvaluate(
      request.curve(), limits, "curve", request.bezier_algorithm());
  const int dimension = curve.ok() ? DimensionOf(*curve) : 0;
  return Resolve(std::move(curve), dimension, request.parameters(),
                 request.derivative_order(), limits);
}

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
  return evaluation.Run(evaluation.parameters.Values(first, last, storage),
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
            CurveEvaluation(*request, limits);
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
            CurveEvaluation(*request, limits);
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
        RETURN_IF_ERROR(
            CheckDerivativeOrder(request->derivative_order(), limits));
        absl::StatusOr<CurveBasis> basis =
            PrepareBasis(request->basis(), limits);
        const int functions = basis.ok() ? FunctionCountOf(*basis) : 0;
        absl::StatusOr<Evaluation<CurveBasis>> evaluation =
            Resolve(std::move(basis), functions, request->parameters(),
                    request->derivative_order(), limits);
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
              return evaluation.Run(
                  evaluation.parameters.Values(0, count, storage), output,
                  execution);
            }};
      });
}

}  // namespace freeform::server
