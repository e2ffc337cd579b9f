#include "curve_service.h"

#include <algorithm>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "convert.h"
#include "errors.h"
#include "freeform/core/status.h"
#include "prepared_curve.h"
#include "rpc.h"

namespace freeform::server {
namespace {

// Everything an evaluation request resolves to before any math runs.
struct EvaluationPlan {
  PreparedCurve curve;
  ParameterSet parameters;
  size_t orders = 1;  // derivative orders 0..orders-1

  size_t ValuesPerParameter() const {
    return orders * static_cast<size_t>(curve.dimension);
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

// Resolves the parameters against the prepared curve's domain and checks
// the output limit.
absl::StatusOr<EvaluationPlan> PlanFor(absl::StatusOr<PreparedCurve> curve,
                                       const v1::Parameters& parameters,
                                       uint32_t derivative_order,
                                       const ServiceLimits& limits) {
  if (!curve.ok()) return curve.status();
  absl::StatusOr<ParameterSet> resolved =
      ParameterSet::Resolve(parameters, curve->domain_start, curve->domain_end,
                            limits.max_parameters);
  if (!resolved.ok()) return PrefixFieldPath(resolved.status(), "parameters");
  EvaluationPlan plan{.curve = *std::move(curve),
                      .parameters = *std::move(resolved),
                      .orders = derivative_order + 1u};
  if (absl::Status status = CheckOutputLimit(
          plan.parameters.size() * plan.ValuesPerParameter(), limits);
      !status.ok()) {
    return status;
  }
  return plan;
}

absl::StatusOr<EvaluationPlan> PlanEvaluation(
    const v1::EvaluateCurveRequest& request, const ServiceLimits& limits) {
  if (absl::Status status =
          CheckDerivativeOrder(request.derivative_order(), limits);
      !status.ok()) {
    return status;
  }
  return PlanFor(
      PrepareCurve(request.curve(), request.bezier_algorithm(), limits),
      request.parameters(), request.derivative_order(), limits);
}

absl::StatusOr<EvaluationPlan> PlanBasisEvaluation(
    const v1::EvaluateBasisRequest& request, const ServiceLimits& limits) {
  if (absl::Status status =
          CheckDerivativeOrder(request.derivative_order(), limits);
      !status.ok()) {
    return status;
  }
  return PlanFor(PrepareBasis(request.basis(), limits), request.parameters(),
                 request.derivative_order(), limits);
}

absl::Status CheckUnaryAnswerSize(const EvaluationPlan& plan,
                                  const ServiceLimits& limits,
                                  absl::string_view streaming_hint) {
  return CheckMessageLimit(plan.parameters.size() * plan.ValuesPerParameter(),
                           limits, streaming_hint);
}

// Adds the derivative arrays of `count` points to `response` and returns
// spans over their (uninitialized) storage.
std::vector<absl::Span<double>> AllocateDerivatives(
    const EvaluationPlan& plan, size_t first, size_t count,
    v1::EvaluateCurveResponse& response) {
  response.set_dimension(static_cast<uint32_t>(plan.curve.dimension));
  response.set_first_index(first);
  response.set_count(static_cast<uint32_t>(count));
  const size_t size = count * static_cast<size_t>(plan.curve.dimension);
  std::vector<absl::Span<double>> spans;
  spans.reserve(plan.orders);
  for (size_t k = 0; k < plan.orders; ++k) {
    v1::Points* points = response.add_derivatives();
    points->set_dimension(static_cast<uint32_t>(plan.curve.dimension));
    spans.push_back(UninitializedArray(*points->mutable_coordinates(), size));
  }
  return spans;
}

}  // namespace

CurveServiceImpl::CurveServiceImpl(ThreadPool* pool,
                                   const ServiceLimits& limits)
    : pool_(pool), limits_(limits), admission_(limits.max_concurrent_heavy) {}

grpc::Status CurveServiceImpl::Evaluate(grpc::ServerContext* context,
                                        const v1::EvaluateCurveRequest* request,
                                        v1::EvaluateCurveResponse* response) {
  return RunRpc(
      "CurveService.Evaluate", context, *request, response,
      [&](const CancellationToken& token) -> absl::Status {
        absl::StatusOr<EvaluationPlan> plan = PlanEvaluation(*request, limits_);
        if (!plan.ok()) return plan.status();
        const size_t count = plan->parameters.size();
        if (absl::Status status =
                CheckUnaryAnswerSize(*plan, limits_, "; use EvaluateStream");
            !status.ok()) {
          return status;
        }
        absl::StatusOr<HeavyWorkAdmission::Ticket> ticket =
            admission_.Admit(count > limits_.grain);
        if (!ticket.ok()) return ticket.status();
        std::vector<absl::Span<double>> output =
            AllocateDerivatives(*plan, 0, count, *response);
        std::vector<double> storage;
        const ExecutionContext execution{
            .pool = pool_, .cancellation = &token, .grain = limits_.grain};
        return plan->curve.evaluate(plan->parameters.Values(0, count, storage),
                                    output, execution);
      });
}

grpc::Status CurveServiceImpl::EvaluateStream(
    grpc::ServerContext* context, const v1::EvaluateCurveRequest* request,
    grpc::ServerWriter<v1::EvaluateCurveResponse>* writer) {
  size_t streamed_bytes = 0;
  return RunRpc(
      "CurveService.EvaluateStream", context, *request, nullptr,
      [&](const CancellationToken& token) -> absl::Status {
        absl::StatusOr<EvaluationPlan> plan = PlanEvaluation(*request, limits_);
        if (!plan.ok()) return plan.status();
        const size_t per_parameter_bytes = plan->ValuesPerParameter() * 8;
        const size_t max_chunk =
            std::max<size_t>(1, static_cast<size_t>(limits_.max_message_bytes) /
                                    2 / per_parameter_bytes);
        const size_t chunk =
            std::min(max_chunk, request->chunk_size() > 0
                                    ? request->chunk_size()
                                    : limits_.default_stream_chunk);
        absl::StatusOr<HeavyWorkAdmission::Ticket> ticket =
            admission_.Admit(plan->parameters.size() > limits_.grain);
        if (!ticket.ok()) return ticket.status();
        const ExecutionContext execution{
            .pool = pool_, .cancellation = &token, .grain = limits_.grain};
        std::vector<double> storage;
        return StreamChunks<v1::EvaluateCurveResponse>(
            plan->parameters.size(), chunk, token, writer, streamed_bytes,
            [&](size_t first, size_t last,
                v1::EvaluateCurveResponse& response) {
              std::vector<absl::Span<double>> output =
                  AllocateDerivatives(*plan, first, last - first, response);
              return plan->curve.evaluate(
                  plan->parameters.Values(first, last, storage), output,
                  execution);
            });
      },
      &streamed_bytes);
}

grpc::Status CurveServiceImpl::EvaluateBasis(
    grpc::ServerContext* context, const v1::EvaluateBasisRequest* request,
    v1::EvaluateBasisResponse* response) {
  return RunRpc(
      "CurveService.EvaluateBasis", context, *request, response,
      [&](const CancellationToken& token) -> absl::Status {
        absl::StatusOr<EvaluationPlan> plan =
            PlanBasisEvaluation(*request, limits_);
        if (!plan.ok()) return plan.status();
        if (absl::Status status = CheckUnaryAnswerSize(*plan, limits_, "");
            !status.ok()) {
          return status;
        }
        const size_t count = plan->parameters.size();
        absl::StatusOr<HeavyWorkAdmission::Ticket> ticket =
            admission_.Admit(count > limits_.grain);
        if (!ticket.ok()) return ticket.status();
        response->set_function_count(
            static_cast<uint32_t>(plan->curve.dimension));
        response->set_count(static_cast<uint32_t>(count));
        const size_t size = count * static_cast<size_t>(plan->curve.dimension);
        std::vector<absl::Span<double>> output;
        for (size_t k = 0; k < plan->orders; ++k) {
          output.push_back(UninitializedArray(
              *response->add_derivatives()->mutable_values(), size));
        }
        std::vector<double> storage;
        const ExecutionContext execution{
            .pool = pool_, .cancellation = &token, .grain = limits_.grain};
        return plan->curve.evaluate(plan->parameters.Values(0, count, storage),
                                    output, execution);
      });
}

}  // namespace freeform::server
