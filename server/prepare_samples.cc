#include "prepare_samples.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "absl/strings/str_cat.h"
#include "freeform/core/arc_length.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/triangular.h"
#include "plan.h"
#include "prepare.h"
#include "prepare_options.h"

namespace freeform::server {
namespace {

absl::Status CheckCount(size_t count, size_t max_count,
                        absl::string_view field) {
  if (count == 0) {
    return InvalidFieldError(field, "needs at least one parameter");
  }
  if (count > max_count) {
    return ExhaustedFieldError(
        field, absl::StrCat(count, " parameters exceed the server's limit of ",
                            max_count, " (--max_parameters)"));
  }
  return absl::OkStatus();
}

absl::StatusOr<double> RangeEnd(bool has_value, double value, double fallback,
                                double lo, double hi, absl::string_view field) {
  if (!has_value) return fallback;
  if (!std::isfinite(value)) {
    return InvalidFieldError(field,
                             absl::StrCat("must be finite, got ", value));
  }
  if (value < lo || value > hi) {
    return InvalidFieldError(
        field,
        absl::StrCat(value, " is outside the domain [", lo, ", ", hi, "]"));
  }
  return value;
}

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

absl::StatusOr<ParameterSet> ResolveAxis(const v1::Parameters& axis,
                                         double start, double end,
                                         const ServiceLimits& limits,
                                         absl::string_view field) {
  absl::StatusOr<ParameterSet> set =
      ParameterSet::Resolve(axis, start, end, limits.max_parameters);
  if (!set.ok()) return PrefixFieldPath(set.status(), field);
  return set;
}

std::vector<double> AllValues(const ParameterSet& set) {
  ParameterStorage storage;
  const absl::Span<const double> values = set.Values(0, set.size(), storage);
  return std::vector<double>(values.begin(), values.end());
}

// CheckSampleCount checks `count` samples of `values_per_point` numbers
// each against the parameter and output limits, naming `field`.
absl::Status CheckSampleCount(uint64_t count, uint64_t values_per_point,
                              const ServiceLimits& limits,
                              absl::string_view field) {
  if (count > limits.max_parameters) {
    return ExhaustedFieldError(
        field, absl::StrCat(count, " points exceed the server's limit of ",
                            limits.max_parameters, " (--max_parameters)"));
  }
  return CheckOutputLimit(SaturatingProduct(count, values_per_point), limits,
                          field);
}

// ResolvePairs returns the (u, v) pairs of `points` once they are pairs
// (an even, non-zero number of values) within the limits, with
// `values_per_point` numbers of answer each.
absl::StatusOr<absl::Span<const double>> ResolvePairs(
    const v1::SurfacePoints& points, uint64_t values_per_point,
    const ServiceLimits& limits) {
  const absl::Span<const double> uv =
      absl::MakeConstSpan(points.uv().data(), points.uv().size());
  if (uv.empty()) {
    return InvalidFieldError("parameters.points.uv",
                             "needs at least one (u, v) pair");
  }
  if (uv.size() % 2 != 0) {
    return InvalidFieldError(
        "parameters.points.uv",
        absl::StrCat("holds ", uv.size(), " values, not (u, v) pairs"));
  }
  RETURN_IF_ERROR(CheckSampleCount(uv.size() / 2, values_per_point, limits,
                                   "parameters.points.uv"));
  return uv;
}

// ResolveSamples resolves the (u, v) points or the grid into `plan`, after
// checking their number, with `values_per_point` numbers each, against the
// limits: nothing as large as the answer is made before that. `plan` holds
// the surface (or, for a basis, its domain) already.
absl::Status ResolveSamples(const v1::SurfaceParameters& parameters,
                            const ServiceLimits& limits,
                            uint64_t values_per_point, SurfacePlan& plan) {
  switch (parameters.kind_case()) {
    case v1::SurfaceParameters::kPoints: {
      absl::StatusOr<absl::Span<const double>> uv =
          ResolvePairs(parameters.points(), values_per_point, limits);
      if (!uv.ok()) return uv.status();
      plan.uv = *uv;
      if (plan.triangular) {
        return PrefixFieldPath(
            ValidateSamples(*plan.surface, SurfaceSamples::Pairs(plan.uv)),
            "parameters.points");
      }
      return PrefixFieldPath(
          ValidateSurfaceSamples(SurfaceSamples::Pairs(plan.uv),
                                 plan.domain.u_start, plan.domain.u_end,
                                 plan.domain.v_start, plan.domain.v_end),
          "parameters.points");
    }
    case v1::SurfaceParameters::kGrid: {
      if (plan.triangular) {
        return InvalidFieldError(
            "parameters.grid",
            "a triangular patch takes (u, v) points, not a grid");
      }
      absl::StatusOr<ParameterSet> u =
          ResolveAxis(parameters.grid().u(), plan.domain.u_start,
                      plan.domain.u_end, limits, "parameters.grid.u");
      if (!u.ok()) return u.status();
      absl::StatusOr<ParameterSet> v =
          ResolveAxis(parameters.grid().v(), plan.domain.v_start,
                      plan.domain.v_end, limits, "parameters.grid.v");
      if (!v.ok()) return v.status();
      RETURN_IF_ERROR(CheckSampleCount(SaturatingProduct(u->size(), v->size()),
                                       values_per_point, limits,
                                       "parameters.grid"));
      plan.grid = true;
      plan.u = AllValues(*u);
      plan.v = AllValues(*v);
      return absl::OkStatus();
    }
    case v1::SurfaceParameters::KIND_NOT_SET:
      break;
  }
  return InvalidFieldError("parameters", "set either points or a grid");
}

// PlanOf returns the plan of `surface`'s samples: its dimension, domain
// and kind, samples still to resolve.
SurfacePlan PlanOf(Surface surface) {
  SurfacePlan plan;
  plan.dimension = DimensionOf(surface);
  plan.domain = DomainOf(surface);
  plan.triangular = IsTriangular(surface);
  plan.surface = std::move(surface);
  return plan;
}

// ResolveInterval returns [start, end], an absent end taken from `curve`'s
// domain, checked by ValidateArcLengthInterval; errors are under `field`.
absl::StatusOr<ParameterDomain> ResolveInterval(bool has_start, double start,
                                                bool has_end, double end,
                                                const Curve& curve,
                                                absl::string_view field) {
  const ParameterDomain domain = DomainOf(curve);
  const ParameterDomain interval = {.start = has_start ? start : domain.start,
                                    .end = has_end ? end : domain.end};
  RETURN_IF_ERROR(PrefixFieldPath(
      ValidateArcLengthInterval(curve, interval.start, interval.end), field));
  return interval;
}

}  // namespace

absl::StatusOr<ParameterSet> ParameterSet::Resolve(
    const v1::Parameters& parameters, double lo, double hi, size_t max_count) {
  ParameterSet set;
  switch (parameters.kind_case()) {
    case v1::Parameters::kList: {
      const auto& values = parameters.list().values();
      RETURN_IF_ERROR(CheckCount(static_cast<size_t>(values.size()), max_count,
                                 "list.values"));
      set.list_ = absl::MakeConstSpan(values.data(), values.size());
      RETURN_IF_ERROR(ValidateInRange(set.list_, lo, hi, "list.values"));
      set.count_ = set.list_.size();
      return set;
    }
    case v1::Parameters::kRange: {
      const v1::UniformRange& range = parameters.range();
      RETURN_IF_ERROR(CheckCount(range.count(), max_count, "range.count"));
      absl::StatusOr<double> start =
          RangeEnd(range.has_start(), range.start(), lo, lo, hi, "range.start");
      if (!start.ok()) return start.status();
      absl::StatusOr<double> end =
          RangeEnd(range.has_end(), range.end(), hi, lo, hi, "range.end");
      if (!end.ok()) return end.status();
      set.is_range_ = true;
      set.start_ = *start;
      set.end_ = *end;
      set.count_ = range.count();
      return set;
    }
    case v1::Parameters::KIND_NOT_SET:
      break;
  }
  return InvalidFieldError("", "set either a parameter list or a range");
}

absl::Span<const double> ParameterSet::Values(size_t begin, size_t end,
                                              ParameterStorage& storage) const {
  if (!is_range_) return list_.subspan(begin, end - begin);
  const size_t count = end - begin;
  if (storage.capacity < count) {
    storage.values.reset(new double[count]);
    storage.capacity = count;
  }
  double* values = storage.values.get();
  // numpy.linspace's values: start + k step, the last one exactly `end`
  // (kept inside the range against rounding).
  const double step =
      count_ > 1 ? (end_ - start_) / static_cast<double>(count_ - 1) : 0.0;
  const double lo = std::min(start_, end_);
  const double hi = std::max(start_, end_);
  // The index counts in a double (exact below 2^53, far above any count
  // allowed): converting a size_t per value costs more than the rest.
  double index = static_cast<double>(begin);
  for (size_t k = 0; k < count; ++k, index += 1.0) {
    values[k] = std::min(std::max(start_ + index * step, lo), hi);
  }
  if (count_ > 1 && end == count_) values[count - 1] = end_;
  return absl::MakeConstSpan(values, count);
}

absl::StatusOr<std::vector<double>> ResolveParameters(
    const v1::Parameters& parameters, const Curve& curve,
    const ServiceLimits& limits) {
  const ParameterDomain domain = DomainOf(curve);
  absl::StatusOr<ParameterSet> set = ParameterSet::Resolve(
      parameters, domain.start, domain.end, limits.max_parameters);
  if (!set.ok()) return PrefixFieldPath(set.status(), "parameters");
  ParameterStorage storage;
  const absl::Span<const double> values = set->Values(0, set->size(), storage);
  return std::vector<double>(values.begin(), values.end());
}

absl::StatusOr<Evaluation<Curve>> PrepareCurveEvaluation(
    const v1::EvaluateCurveRequest& request, const ServiceLimits& limits) {
  RETURN_IF_ERROR(CheckDerivativeOrder(request.derivative_order(), limits));
  RETURN_IF_ERROR(CheckEnum(request.bezier_algorithm(),
                            v1::BezierAlgorithm_IsValid, "bezier_algorithm"));
  absl::StatusOr<Curve> curve = PrepareCurveToEvaluate(
      request.curve(), limits, "curve", ToCore(request.bezier_algorithm()));
  const int dimension = curve.ok() ? DimensionOf(*curve) : 0;
  return Resolve(std::move(curve), dimension, request.parameters(),
                 request.derivative_order(), limits);
}

absl::StatusOr<Evaluation<CurveBasis>> PrepareBasisEvaluation(
    const v1::EvaluateBasisRequest& request, const ServiceLimits& limits) {
  RETURN_IF_ERROR(CheckDerivativeOrder(request.derivative_order(), limits));
  absl::StatusOr<CurveBasis> basis = PrepareBasis(request.basis(), limits);
  const int functions = basis.ok() ? FunctionCountOf(*basis) : 0;
  return Resolve(std::move(basis), functions, request.parameters(),
                 request.derivative_order(), limits);
}

std::vector<SurfacePlan::Piece> SurfacePlan::Pieces(size_t first,
                                                    size_t last) const {
  if (!grid) {
    return {{.offset = 0,
             .samples = SurfaceSamples::Pairs(
                 uv.subspan(2 * first, 2 * (last - first)))}};
  }
  const size_t row = v.size();
  const absl::Span<const double> all_u = absl::MakeConstSpan(u);
  const absl::Span<const double> all_v = absl::MakeConstSpan(v);
  std::vector<Piece> pieces;
  size_t at = first;
  while (at < last) {
    const size_t i = at / row, j = at % row;
    size_t rows = 1, columns = std::min(row - j, last - at);
    if (j == 0 && last - at >= row) {  // whole rows
      rows = (last - at) / row;
      columns = row;
    }
    pieces.push_back({.offset = at - first,
                      .samples = SurfaceSamples::Grid(
                          all_u.subspan(i, rows), all_v.subspan(j, columns))});
    at += rows * columns;
  }
  return pieces;
}

absl::StatusOr<SurfacePlan> PrepareSurfaceEvaluation(
    const v1::EvaluateSurfaceRequest& request, const ServiceLimits& limits) {
  RETURN_IF_ERROR(CheckDerivativeOrder(request.derivative_order(), limits));
  ASSIGN_OR_RETURN(Surface surface, PrepareSurface(request.surface(), limits));
  return PrepareEvaluationOf(std::move(surface), request.parameters(),
                             request.derivative_order(), request.normals(), 0,
                             limits);
}

absl::StatusOr<SurfacePlan> PrepareEvaluationOf(
    Surface surface, const v1::SurfaceParameters& parameters,
    uint32_t derivative_order, bool normals, uint64_t extra_values_per_point,
    const ServiceLimits& limits) {
  RETURN_IF_ERROR(CheckDerivativeOrder(derivative_order, limits));
  SurfacePlan plan = PlanOf(std::move(surface));
  if (normals && plan.dimension != 3) {
    return InvalidFieldError(
        "normals", absl::StrCat("normals need a 3D surface, this one is ",
                                plan.dimension, "D"));
  }
  plan.order = static_cast<int>(derivative_order);
  plan.normals = normals;
  RETURN_IF_ERROR(ResolveSamples(parameters, limits,
                                 plan.ValuesPerPoint() + extra_values_per_point,
                                 plan));
  return plan;
}

absl::StatusOr<SurfacePlan> PrepareSamplesOn(
    Surface surface, const v1::SurfaceParameters& parameters,
    uint64_t values_per_point, const ServiceLimits& limits) {
  SurfacePlan plan = PlanOf(std::move(surface));
  RETURN_IF_ERROR(ResolveSamples(parameters, limits, values_per_point, plan));
  return plan;
}

absl::StatusOr<SurfacePlan> PrepareSurfaceCurvature(
    const v1::SurfaceCurvatureRequest& request, uint64_t values_per_point,
    const ServiceLimits& limits) {
  ASSIGN_OR_RETURN(Surface surface, PrepareSurface(request.surface(), limits));
  SurfacePlan plan = PlanOf(std::move(surface));
  if (plan.dimension != 3) {
    return InvalidFieldError(
        "surface", absl::StrCat("curvatures need a 3D surface, this one is ",
                                plan.dimension, "D"));
  }
  RETURN_IF_ERROR(
      ResolveSamples(request.parameters(), limits, values_per_point, plan));
  return plan;
}

absl::StatusOr<TensorBasisEvaluation> PrepareTensorBasisEvaluation(
    const v1::EvaluateSurfaceBasisRequest& request,
    const ServiceLimits& limits) {
  ASSIGN_OR_RETURN(CurveBasis u,
                   PrepareBasis(request.tensor().u(), limits, "tensor.u"));
  ASSIGN_OR_RETURN(CurveBasis v,
                   PrepareBasis(request.tensor().v(), limits, "tensor.v"));
  TensorBasisEvaluation evaluation{
      .u = std::move(u), .v = std::move(v), .samples = {}};
  SurfacePlan& samples = evaluation.samples;
  samples.dimension = 1;
  const ParameterDomain du = DomainOf(evaluation.u);
  const ParameterDomain dv = DomainOf(evaluation.v);
  samples.domain = {.u_start = du.start,
                    .u_end = du.end,
                    .v_start = dv.start,
                    .v_end = dv.end};
  RETURN_IF_ERROR(ResolveSamples(request.parameters(), limits,
                                 evaluation.FunctionCount(), samples));
  return evaluation;
}

uint64_t TriangularBasisEvaluation::FunctionCount() const {
  return TriangularPointCount(degree);
}

absl::StatusOr<TriangularBasisEvaluation> PrepareTriangularBasisEvaluation(
    const v1::EvaluateSurfaceBasisRequest& request,
    const ServiceLimits& limits) {
  const uint32_t degree = request.triangular_degree();
  RETURN_IF_ERROR(CheckDegreeLimit(degree, limits, "triangular_degree"));
  if (!request.parameters().has_points()) {
    return InvalidFieldError(
        "parameters.points",
        "triangular Bernstein polynomials take (u, v) points");
  }
  TriangularBasisEvaluation evaluation{.degree = static_cast<int>(degree)};
  ASSIGN_OR_RETURN(evaluation.uv,
                   ResolvePairs(request.parameters().points(),
                                evaluation.FunctionCount(), limits));
  return evaluation;
}

absl::StatusOr<ParameterDomain> PrepareInterval(
    const v1::ParameterInterval& interval, const Curve& curve,
    absl::string_view field) {
  return ResolveInterval(interval.has_start(), interval.start(),
                         interval.has_end(), interval.end(), curve, field);
}

absl::StatusOr<double> PrepareArcLengthStart(
    const v1::ParametersAtArcLengthRequest& request, const Curve& curve) {
  ASSIGN_OR_RETURN(const ParameterDomain interval,
                   ResolveInterval(request.has_start(), request.start(),
                                   /*has_end=*/false, 0.0, curve, ""));
  return interval.start;
}

}  // namespace freeform::server
