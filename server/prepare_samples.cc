#include "prepare_samples.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "convert.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/triangular.h"
#include "plan.h"

namespace freeform::server {
namespace {

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

}  // namespace

// ResolvePairs returns the (u, v) pairs of `points` once they are pairs
// (an even, non-zero number of values) within the limits.
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

}  // namespace freeform::server
