#include "curve_service.h"

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "convert.h"
#include "errors.h"
#include "freeform/core/bezier.h"
#include "freeform/core/status.h"
#include "rpc.h"

namespace freeform::server {
namespace {

// A validated curve, ready to evaluate at parameters in its domain.
struct PreparedCurve {
  int dimension = 0;
  double domain_start = 0.0;
  double domain_end = 1.0;
  std::function<absl::Status(absl::Span<const double>, CurveOutput,
                             const ExecutionContext&)>
      evaluate;
};

absl::Status CheckDimension(uint32_t dimension, const ServiceLimits& limits,
                            absl::string_view field) {
  if (dimension < 1 ||
      dimension > static_cast<uint32_t>(limits.max_dimension)) {
    return InvalidFieldError(
        absl::StrCat(field, ".dimension"),
        absl::StrCat("dimension must be between 1 and ", limits.max_dimension,
                     ", got ", dimension));
  }
  return absl::OkStatus();
}

absl::Status CheckControlPointCount(size_t count, int degree,
                                    const ServiceLimits& limits,
                                    absl::string_view field) {
  if (count > limits.max_control_points) {
    return absl::ResourceExhaustedError(absl::StrCat(
        field, ": ", count, " control points exceed the server's limit of ",
        limits.max_control_points, " (--max_control_points)"));
  }
  if (degree > limits.max_degree) {
    return InvalidFieldError(
        field,
        absl::StrCat("degree ", degree, " exceeds the server's limit of ",
                     limits.max_degree, " (--max_degree)"));
  }
  return absl::OkStatus();
}

// Fields in errors are relative to the BezierCurve message.
absl::StatusOr<PreparedCurve> PrepareBezier(const v1::BezierCurve& message,
                                            const ServiceLimits& limits) {
  if (absl::Status status = CheckDimension(message.control_points().dimension(),
                                           limits, "control_points");
      !status.ok()) {
    return status;
  }
  const BezierCurveView curve = ViewOf(message);
  if (absl::Status status = ValidateBezierCurve(curve); !status.ok()) {
    return status;
  }
  if (absl::Status status =
          CheckControlPointCount(curve.control_points.size(), curve.degree(),
                                 limits, "control_points");
      !status.ok()) {
    return status;
  }
  PreparedCurve prepared;
  prepared.dimension = curve.control_points.dimension;
  prepared.evaluate = [curve](absl::Span<const double> parameters,
                              CurveOutput output,
                              const ExecutionContext& context) {
    return EvaluateBezierCurve(curve, parameters, output, context);
  };
  return prepared;
}

// Fields in errors are full paths from the request ("curve.bezier...").
absl::StatusOr<PreparedCurve> PrepareCurve(const v1::Curve& curve,
                                           const ServiceLimits& limits) {
  absl::StatusOr<PreparedCurve> prepared;
  absl::string_view prefix = "curve";
  switch (curve.kind_case()) {
    case v1::Curve::kBezier:
      prefix = "curve.bezier";
      prepared = PrepareBezier(curve.bezier(), limits);
      break;
    case v1::Curve::kBspline:
      return NotYetImplemented("Evaluating B-spline and NURBS curves",
                               "issue #3");
    case v1::Curve::kLagrange:
      return NotYetImplemented("Evaluating Lagrange curves", "issue #3");
    case v1::Curve::kHermite:
      return NotYetImplemented("Evaluating Hermite curves", "issue #3");
    case v1::Curve::kPower:
      return NotYetImplemented("Evaluating power-form curves", "issue #3");
    case v1::Curve::KIND_NOT_SET:
      return InvalidFieldError("curve", "set one curve kind (bezier, ...)");
  }
  if (!prepared.ok()) return PrefixFieldPath(prepared.status(), prefix);
  return prepared;
}

// Everything an evaluation request resolves to before any math runs.
struct EvaluationPlan {
  PreparedCurve curve;
  ParameterSet parameters;
  size_t orders = 1;  // derivative orders 0..orders-1

  size_t ValuesPerParameter() const {
    return orders * static_cast<size_t>(curve.dimension);
  }
};

absl::StatusOr<EvaluationPlan> PlanEvaluation(
    const v1::EvaluateCurveRequest& request, const ServiceLimits& limits) {
  if (request.derivative_order() >
      static_cast<uint32_t>(limits.max_derivative_order)) {
    return InvalidFieldError(
        "derivative_order",
        absl::StrCat("must be at most ", limits.max_derivative_order, ", got ",
                     request.derivative_order()));
  }
  switch (request.bezier_algorithm()) {
    case v1::BEZIER_ALGORITHM_AUTO:
    case v1::BEZIER_ALGORITHM_DE_CASTELJAU:
      break;
    default:
      if (request.curve().has_bezier()) {
        return NotYetImplemented("This Bezier algorithm", "issue #3");
      }
  }
  absl::StatusOr<PreparedCurve> curve = PrepareCurve(request.curve(), limits);
  if (!curve.ok()) return curve.status();
  absl::StatusOr<ParameterSet> parameters =
      ParameterSet::Resolve(request.parameters(), curve->domain_start,
                            curve->domain_end, limits.max_parameters);
  if (!parameters.ok()) {
    return PrefixFieldPath(parameters.status(), "parameters");
  }
  EvaluationPlan plan{.curve = *std::move(curve),
                      .parameters = *std::move(parameters),
                      .orders = request.derivative_order() + 1u};
  const size_t values = plan.parameters.size() * plan.ValuesPerParameter();
  if (values > limits.max_output_values) {
    return absl::ResourceExhaustedError(
        absl::StrCat("parameters: the answer would hold ", values,
                     " numbers, over the server's limit of ",
                     limits.max_output_values, " (--max_output_values)"));
  }
  return plan;
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
    google::protobuf::RepeatedField<double>* coordinates =
        points->mutable_coordinates();
    coordinates->Reserve(static_cast<int>(size));
    spans.emplace_back(coordinates->AddNAlreadyReserved(static_cast<int>(size)),
                       size);
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
        const size_t bytes = count * plan->ValuesPerParameter() * 8;
        if (bytes > static_cast<size_t>(limits_.max_message_bytes)) {
          return absl::ResourceExhaustedError(
              absl::StrCat("parameters: the answer would take ", bytes,
                           " bytes, over the message limit of ",
                           limits_.max_message_bytes, "; use EvaluateStream"));
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
        v1::EvaluateCurveResponse response;
        for (size_t first = 0; first < plan->parameters.size();
             first += chunk) {
          if (token.IsCancelled()) return token.status();
          const size_t last = std::min(plan->parameters.size(), first + chunk);
          response.Clear();
          std::vector<absl::Span<double>> output =
              AllocateDerivatives(*plan, first, last - first, response);
          if (absl::Status status = plan->curve.evaluate(
                  plan->parameters.Values(first, last, storage), output,
                  execution);
              !status.ok()) {
            return status;
          }
          streamed_bytes += response.ByteSizeLong();
          if (!writer->Write(response)) {
            return absl::CancelledError("the client stopped reading");
          }
        }
        return absl::OkStatus();
      },
      &streamed_bytes);
}

grpc::Status CurveServiceImpl::EvaluateBasis(
    grpc::ServerContext* context, const v1::EvaluateBasisRequest* request,
    v1::EvaluateBasisResponse*) {
  return RunUnimplemented("CurveService.EvaluateBasis", context, *request,
                          "issue #3");
}

grpc::Status CurveServiceImpl::Split(grpc::ServerContext* context,
                                     const v1::SplitCurveRequest* request,
                                     v1::SplitCurveResponse*) {
  return RunUnimplemented("CurveService.Split", context, *request, "issue #5");
}

grpc::Status CurveServiceImpl::InsertKnots(
    grpc::ServerContext* context, const v1::InsertKnotsRequest* request,
    v1::InsertKnotsResponse*) {
  return RunUnimplemented("CurveService.InsertKnots", context, *request,
                          "issue #5");
}

grpc::Status CurveServiceImpl::Decompose(
    grpc::ServerContext* context, const v1::DecomposeCurveRequest* request,
    v1::DecomposeCurveResponse*) {
  return RunUnimplemented("CurveService.Decompose", context, *request,
                          "issue #5");
}

grpc::Status CurveServiceImpl::Subdivide(grpc::ServerContext* context,
                                         const v1::SubdivideRequest* request,
                                         v1::SubdivideResponse*) {
  return RunUnimplemented("CurveService.Subdivide", context, *request,
                          "issue #5");
}

grpc::Status CurveServiceImpl::Tessellate(
    grpc::ServerContext* context, const v1::TessellateCurveRequest* request,
    v1::TessellateCurveResponse*) {
  return RunUnimplemented("CurveService.Tessellate", context, *request,
                          "issue #5");
}

grpc::Status CurveServiceImpl::ElevateDegree(
    grpc::ServerContext* context, const v1::ElevateCurveDegreeRequest* request,
    v1::ElevateCurveDegreeResponse*) {
  return RunUnimplemented("CurveService.ElevateDegree", context, *request,
                          "issue #6");
}

grpc::Status CurveServiceImpl::ReduceDegree(
    grpc::ServerContext* context, const v1::ReduceCurveDegreeRequest* request,
    v1::ReduceCurveDegreeResponse*) {
  return RunUnimplemented("CurveService.ReduceDegree", context, *request,
                          "issue #6");
}

grpc::Status CurveServiceImpl::Interpolate(
    grpc::ServerContext* context, const v1::InterpolateCurveRequest* request,
    v1::InterpolateCurveResponse*) {
  return RunUnimplemented("CurveService.Interpolate", context, *request,
                          "issue #7");
}

}  // namespace freeform::server
