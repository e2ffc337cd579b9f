#include "surface_service.h"

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "convert.h"
#include "freeform/core/normals.h"
#include "freeform/core/status.h"
#include "freeform/core/triangular.h"
#include "prepared_curve.h"
#include "prepared_surface.h"
#include "rpc.h"

namespace freeform::server {
namespace {

// Everything a surface evaluation request resolves to before any math runs.
struct SurfacePlan {
  PreparedSurface surface;
  // (u, v) pairs (a view into the request), or a grid.
  absl::Span<const double> uv;
  bool grid = false;
  std::vector<double> u;
  std::vector<double> v;
  // Partials returned, and partials computed (normals need order 2 for
  // the limit at degenerate points).
  int order = 0;
  int evaluated_order = 0;
  bool normals = false;

  size_t size() const { return grid ? u.size() * v.size() : uv.size() / 2; }

  // Samples of points [first, last); on a grid both must be row multiples.
  SurfaceSamples Chunk(size_t first, size_t last) const {
    if (!grid) {
      return SurfaceSamples::Pairs(uv.subspan(2 * first, 2 * (last - first)));
    }
    const size_t row = v.size();
    return SurfaceSamples::Grid(
        absl::MakeConstSpan(u).subspan(first / row, (last - first) / row), v);
  }

  size_t ValuesPerPoint() const {
    return PartialCount(order) * static_cast<size_t>(surface.dimension) +
           (normals ? 3 : 0);
  }
};

absl::StatusOr<std::vector<double>> ResolveAxis(const v1::Parameters& axis,
                                                double start, double end,
                                                const ServiceLimits& limits,
                                                absl::string_view field) {
  absl::StatusOr<ParameterSet> set =
      ParameterSet::Resolve(axis, start, end, limits.max_parameters);
  if (!set.ok()) return PrefixFieldPath(set.status(), field);
  std::vector<double> storage;
  const absl::Span<const double> values = set->Values(0, set->size(), storage);
  return std::vector<double>(values.begin(), values.end());
}

absl::Status ResolveSamples(const v1::SurfaceParameters& parameters,
                            const ServiceLimits& limits, SurfacePlan& plan) {
  const PreparedSurface& surface = plan.surface;
  switch (parameters.kind_case()) {
    case v1::SurfaceParameters::kPoints: {
      const auto& uv = parameters.points().uv();
      plan.uv = absl::MakeConstSpan(uv.data(), uv.size());
      if (plan.uv.empty()) {
        return InvalidFieldError("parameters.points.uv",
                                 "needs at least one (u, v) pair");
      }
      if (plan.uv.size() / 2 > limits.max_parameters) {
        return absl::ResourceExhaustedError(
            absl::StrCat("parameters.points.uv: ", plan.uv.size() / 2,
                         " points exceed the server's limit of ",
                         limits.max_parameters, " (--max_parameters)"));
      }
      if (surface.triangular) return absl::OkStatus();  // checked by the core
      return PrefixFieldPath(
          ValidateSurfaceSamples(SurfaceSamples::Pairs(plan.uv),
                                 surface.u_start, surface.u_end,
                                 surface.v_start, surface.v_end),
          "parameters.points");
    }
    case v1::SurfaceParameters::kGrid: {
      if (surface.triangular) {
        return InvalidFieldError(
            "parameters.grid",
            "a triangular patch takes (u, v) points, not a grid");
      }
      absl::StatusOr<std::vector<double>> u =
          ResolveAxis(parameters.grid().u(), surface.u_start, surface.u_end,
                      limits, "parameters.grid.u");
      if (!u.ok()) return u.status();
      absl::StatusOr<std::vector<double>> v =
          ResolveAxis(parameters.grid().v(), surface.v_start, surface.v_end,
                      limits, "parameters.grid.v");
      if (!v.ok()) return v.status();
      plan.grid = true;
      plan.u = *std::move(u);
      plan.v = *std::move(v);
      if (plan.size() > limits.max_parameters) {
        return absl::ResourceExhaustedError(
            absl::StrCat("parameters.grid: ", plan.size(),
                         " points exceed the server's limit of ",
                         limits.max_parameters, " (--max_parameters)"));
      }
      return absl::OkStatus();
    }
    case v1::SurfaceParameters::KIND_NOT_SET:
      break;
  }
  return InvalidFieldError("parameters", "set either points or a grid");
}

absl::StatusOr<SurfacePlan> PlanSurfaceEvaluation(
    const v1::EvaluateSurfaceRequest& request, const ServiceLimits& limits) {
  if (request.derivative_order() >
      static_cast<uint32_t>(limits.max_derivative_order)) {
    return InvalidFieldError(
        "derivative_order",
        absl::StrCat("must be at most ", limits.max_derivative_order, ", got ",
                     request.derivative_order()));
  }
  absl::StatusOr<PreparedSurface> surface =
      PrepareSurface(request.surface(), limits);
  if (!surface.ok()) return surface.status();
  if (request.normals() && surface->dimension != 3) {
    return InvalidFieldError(
        "normals", absl::StrCat("normals need a 3D surface, this one is ",
                                surface->dimension, "D"));
  }
  SurfacePlan plan;
  plan.surface = *std::move(surface);
  plan.order = static_cast<int>(request.derivative_order());
  plan.normals = request.normals();
  plan.evaluated_order =
      request.normals() ? std::max(plan.order, 2) : plan.order;
  if (absl::Status status = ResolveSamples(request.parameters(), limits, plan);
      !status.ok()) {
    return status;
  }
  if (absl::Status status =
          CheckOutputLimit(plan.size() * plan.ValuesPerPoint(), limits);
      !status.ok()) {
    return status;
  }
  return plan;
}

// Evaluates points [first, last) of the plan into `response`.
absl::Status EvaluateChunk(const SurfacePlan& plan, size_t first, size_t last,
                           const ExecutionContext& execution,
                           v1::EvaluateSurfaceResponse& response) {
  const size_t count = last - first;
  const int dimension = plan.surface.dimension;
  const size_t size = count * static_cast<size_t>(dimension);
  response.set_dimension(static_cast<uint32_t>(dimension));
  response.set_first_index(first);
  response.set_count(static_cast<uint32_t>(count));
  // Returned partials go straight into the response; the extra ones the
  // normals need into local storage.
  std::vector<absl::Span<double>> output;
  std::vector<std::vector<double>> extra;
  extra.reserve(PartialCount(plan.evaluated_order));
  for (int total = 0; total <= plan.evaluated_order; ++total) {
    for (int order_v = 0; order_v <= total; ++order_v) {
      if (total <= plan.order) {
        v1::PartialDerivative* partial = response.add_partials();
        partial->set_order_u(static_cast<uint32_t>(total - order_v));
        partial->set_order_v(static_cast<uint32_t>(order_v));
        partial->mutable_values()->set_dimension(
            static_cast<uint32_t>(dimension));
        output.push_back(UninitializedArray(
            *partial->mutable_values()->mutable_coordinates(), size));
      } else {
        output.push_back(absl::MakeSpan(extra.emplace_back(size)));
      }
    }
  }
  const SurfaceSamples samples = plan.Chunk(first, last);
  if (absl::Status status = plan.surface.evaluate(samples, output, execution);
      !status.ok()) {
    return status;
  }
  if (!plan.normals) return absl::OkStatus();
  response.mutable_normals()->set_dimension(3);
  const absl::Span<double> normals = UninitializedArray(
      *response.mutable_normals()->mutable_coordinates(), 3 * count);
  if (plan.surface.triangular) {
    return ComputeUnitNormals(output, count, normals);
  }
  const SurfaceDomain domain{.u_start = plan.surface.u_start,
                             .u_end = plan.surface.u_end,
                             .v_start = plan.surface.v_start,
                             .v_end = plan.surface.v_end};
  return ComputeUnitNormals(output, samples, domain, normals);
}

}  // namespace

SurfaceServiceImpl::SurfaceServiceImpl(ThreadPool* pool,
                                       const ServiceLimits& limits)
    : pool_(pool), limits_(limits), admission_(limits.max_concurrent_heavy) {}

grpc::Status SurfaceServiceImpl::Evaluate(
    grpc::ServerContext* context, const v1::EvaluateSurfaceRequest* request,
    v1::EvaluateSurfaceResponse* response) {
  return RunRpc(
      "SurfaceService.Evaluate", context, *request, response,
      [&](const CancellationToken& token) -> absl::Status {
        absl::StatusOr<SurfacePlan> plan =
            PlanSurfaceEvaluation(*request, limits_);
        if (!plan.ok()) return plan.status();
        if (absl::Status status =
                CheckMessageLimit(plan->size() * plan->ValuesPerPoint(),
                                  limits_, "; use EvaluateStream");
            !status.ok()) {
          return status;
        }
        absl::StatusOr<HeavyWorkAdmission::Ticket> ticket =
            admission_.Admit(plan->size() > limits_.grain);
        if (!ticket.ok()) return ticket.status();
        const ExecutionContext execution{
            .pool = pool_, .cancellation = &token, .grain = limits_.grain};
        return EvaluateChunk(*plan, 0, plan->size(), execution, *response);
      });
}

grpc::Status SurfaceServiceImpl::EvaluateStream(
    grpc::ServerContext* context, const v1::EvaluateSurfaceRequest* request,
    grpc::ServerWriter<v1::EvaluateSurfaceResponse>* writer) {
  size_t streamed_bytes = 0;
  return RunRpc(
      "SurfaceService.EvaluateStream", context, *request, nullptr,
      [&](const CancellationToken& token) -> absl::Status {
        absl::StatusOr<SurfacePlan> plan =
            PlanSurfaceEvaluation(*request, limits_);
        if (!plan.ok()) return plan.status();
        const size_t max_points =
            std::max<size_t>(1, static_cast<size_t>(limits_.max_message_bytes) /
                                    2 / (plan->ValuesPerPoint() * 8));
        size_t chunk = std::min(max_points, request->chunk_size() > 0
                                                ? request->chunk_size()
                                                : limits_.default_stream_chunk);
        if (plan->grid) {  // whole rows of the grid
          const size_t row = plan->v.size();
          chunk = std::max<size_t>(1, chunk / row) * row;
        }
        absl::StatusOr<HeavyWorkAdmission::Ticket> ticket =
            admission_.Admit(plan->size() > limits_.grain);
        if (!ticket.ok()) return ticket.status();
        const ExecutionContext execution{
            .pool = pool_, .cancellation = &token, .grain = limits_.grain};
        return StreamChunks<v1::EvaluateSurfaceResponse>(
            plan->size(), chunk, token, writer, streamed_bytes,
            [&](size_t first, size_t last,
                v1::EvaluateSurfaceResponse& response) {
              return EvaluateChunk(*plan, first, last, execution, response);
            });
      },
      &streamed_bytes);
}

namespace {

// Values of one curve basis at `parameters`: [r * functions + i].
absl::StatusOr<std::vector<double>> CurveBasisValues(
    const PreparedCurve& basis, absl::Span<const double> parameters,
    const ExecutionContext& execution) {
  std::vector<double> values(parameters.size() *
                             static_cast<size_t>(basis.dimension));
  const absl::Span<double> output[] = {absl::MakeSpan(values)};
  if (absl::Status status = basis.evaluate(parameters, output, execution);
      !status.ok()) {
    return status;
  }
  return values;
}

// The u (or v) coordinate of every (u, v) pair.
std::vector<double> PairCoordinate(absl::Span<const double> uv, size_t which) {
  std::vector<double> values(uv.size() / 2);
  for (size_t r = 0; r < values.size(); ++r) values[r] = uv[2 * r + which];
  return values;
}

// Tensor-product basis: value of function (i, j) at point r is
// U_i(u_r) V_j(v_r), stored at r * (fu * fv) + i * fv + j.
absl::Status TensorBasis(const v1::EvaluateSurfaceBasisRequest& request,
                         const ServiceLimits& limits,
                         const ExecutionContext& execution,
                         v1::EvaluateSurfaceBasisResponse& response) {
  absl::StatusOr<PreparedCurve> u_basis =
      PrepareBasis(request.tensor().u(), limits, "tensor.u");
  if (!u_basis.ok()) return u_basis.status();
  absl::StatusOr<PreparedCurve> v_basis =
      PrepareBasis(request.tensor().v(), limits, "tensor.v");
  if (!v_basis.ok()) return v_basis.status();
  SurfacePlan plan;
  plan.surface = {.dimension = 1,
                  .u_start = u_basis->domain_start,
                  .u_end = u_basis->domain_end,
                  .v_start = v_basis->domain_start,
                  .v_end = v_basis->domain_end,
                  .triangular = false,
                  .evaluate = {}};
  if (absl::Status status = ResolveSamples(request.parameters(), limits, plan);
      !status.ok()) {
    return status;
  }
  const size_t fu = static_cast<size_t>(u_basis->dimension);
  const size_t fv = static_cast<size_t>(v_basis->dimension);
  const size_t values = plan.size() * fu * fv;
  if (absl::Status status = CheckOutputLimit(values, limits); !status.ok()) {
    return status;
  }
  if (absl::Status status = CheckMessageLimit(values, limits); !status.ok()) {
    return status;
  }
  const std::vector<double> u_values =
      plan.grid ? plan.u : PairCoordinate(plan.uv, 0);
  const std::vector<double> v_values =
      plan.grid ? plan.v : PairCoordinate(plan.uv, 1);
  absl::StatusOr<std::vector<double>> u =
      CurveBasisValues(*u_basis, u_values, execution);
  if (!u.ok()) return u.status();
  absl::StatusOr<std::vector<double>> v =
      CurveBasisValues(*v_basis, v_values, execution);
  if (!v.ok()) return v.status();
  response.set_function_count(static_cast<uint32_t>(fu * fv));
  response.set_count(static_cast<uint32_t>(plan.size()));
  const absl::Span<double> out =
      UninitializedArray(*response.mutable_values(), values);
  for (size_t r = 0; r < plan.size(); ++r) {
    const size_t ru = plan.grid ? r / plan.v.size() : r;
    const size_t rv = plan.grid ? r % plan.v.size() : r;
    for (size_t i = 0; i < fu; ++i) {
      for (size_t j = 0; j < fv; ++j) {
        out[(r * fu + i) * fv + j] = (*u)[ru * fu + i] * (*v)[rv * fv + j];
      }
    }
  }
  return absl::OkStatus();
}

absl::Status TriangularBasis(const v1::EvaluateSurfaceBasisRequest& request,
                             const ServiceLimits& limits,
                             const ExecutionContext& execution,
                             v1::EvaluateSurfaceBasisResponse& response) {
  const uint32_t degree = request.triangular_degree();
  if (degree > static_cast<uint32_t>(limits.max_degree)) {
    return InvalidFieldError(
        "triangular_degree",
        absl::StrCat("degree ", degree, " exceeds the server's limit of ",
                     limits.max_degree, " (--max_degree)"));
  }
  if (!request.parameters().has_points()) {
    return InvalidFieldError(
        "parameters.points",
        "triangular Bernstein polynomials take (u, v) points");
  }
  const auto& uv = request.parameters().points().uv();
  const size_t count = static_cast<size_t>(uv.size()) / 2;
  const size_t functions = TriangularPointCount(static_cast<int>(degree));
  const size_t values = count * functions;
  if (absl::Status status = CheckOutputLimit(values, limits); !status.ok()) {
    return status;
  }
  if (absl::Status status = CheckMessageLimit(values, limits); !status.ok()) {
    return status;
  }
  response.set_function_count(static_cast<uint32_t>(functions));
  response.set_count(static_cast<uint32_t>(count));
  return PrefixFieldPath(
      EvaluateTriangularBasis(
          static_cast<int>(degree), absl::MakeConstSpan(uv.data(), uv.size()),
          UninitializedArray(*response.mutable_values(), values), execution),
      "parameters.points");
}

}  // namespace

grpc::Status SurfaceServiceImpl::EvaluateBasis(
    grpc::ServerContext* context,
    const v1::EvaluateSurfaceBasisRequest* request,
    v1::EvaluateSurfaceBasisResponse* response) {
  return RunRpc(
      "SurfaceService.EvaluateBasis", context, *request, response,
      [&](const CancellationToken& token) -> absl::Status {
        const ExecutionContext execution{
            .pool = pool_, .cancellation = &token, .grain = limits_.grain};
        switch (request->kind_case()) {
          case v1::EvaluateSurfaceBasisRequest::kTensor:
            return TensorBasis(*request, limits_, execution, *response);
          case v1::EvaluateSurfaceBasisRequest::kTriangularDegree:
            return TriangularBasis(*request, limits_, execution, *response);
          case v1::EvaluateSurfaceBasisRequest::KIND_NOT_SET:
            break;
        }
        return InvalidFieldError("tensor",
                                 "set a tensor basis or a triangular_degree");
      });
}

}  // namespace freeform::server
