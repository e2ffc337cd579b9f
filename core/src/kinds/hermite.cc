#include "freeform/core/hermite.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "freeform/core/bezier.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "kinds/validated_hermite.h"

namespace freeform {
namespace {

absl::Status ValidateStrictlyIncreasing(absl::Span<const double> values,
                                        absl::string_view field) {
  RETURN_IF_ERROR(ValidateFinite(values, field));
  for (size_t i = 1; i < values.size(); ++i) {
    if (!(values[i] > values[i - 1])) {
      return InvalidFieldError(
          IndexedField(field, i),
          absl::StrCat("must be strictly increasing: ", values[i], " follows ",
                       values[i - 1]));
    }
  }
  return absl::OkStatus();
}

// The segment k with t_k <= t < t_{k+1}; the last one at the domain's end.
size_t FindSegment(absl::Span<const double> nodes, double t) {
  const auto after = std::upper_bound(nodes.begin(), nodes.end(), t);
  const size_t index = static_cast<size_t>(after - nodes.begin());
  return std::clamp<size_t>(index, 1, nodes.size() - 1) - 1;
}

}  // namespace

absl::Status ValidateHermiteCurve(const HermiteCurveView& curve) {
  RETURN_IF_ERROR(ValidatePoints(curve.points, "points", 2));
  if (curve.tangents.dimension != curve.points.dimension) {
    return InvalidFieldError("tangents.dimension",
                             absl::StrCat("must equal the points' dimension ",
                                          curve.points.dimension, ", got ",
                                          curve.tangents.dimension));
  }
  RETURN_IF_ERROR(ValidatePoints(curve.tangents, "tangents"));
  if (curve.tangents.size() != curve.points.size()) {
    return InvalidFieldError(
        "tangents.coordinates",
        absl::StrCat("has ", curve.tangents.size(), " tangents for ",
                     curve.points.size(), " points"));
  }
  if (curve.nodes.empty()) return absl::OkStatus();
  if (curve.nodes.size() != curve.points.size()) {
    return InvalidFieldError(
        "nodes", absl::StrCat("has ", curve.nodes.size(), " nodes for ",
                              curve.points.size(), " points"));
  }
  return ValidateStrictlyIncreasing(curve.nodes, "nodes");
}

std::vector<double> HermiteNodes(const HermiteCurveView& curve) {
  if (!curve.nodes.empty()) {
    return std::vector<double>(curve.nodes.begin(), curve.nodes.end());
  }
  std::vector<double> nodes(curve.points.size());
  for (size_t i = 0; i < nodes.size(); ++i) nodes[i] = static_cast<double>(i);
  return nodes;
}

std::pair<double, double> HermiteDomain(const HermiteCurveView& curve) {
  if (!curve.nodes.empty()) return {curve.nodes.front(), curve.nodes.back()};
  return {0.0, static_cast<double>(curve.points.size() - 1)};
}

std::vector<double> HermiteSegmentBezier(const HermiteCurveView& curve,
                                         absl::Span<const double> nodes,
                                         size_t segment) {
  const size_t dim = static_cast<size_t>(curve.points.dimension);
  const double third = (nodes[segment + 1] - nodes[segment]) / 3.0;
  const double* p0 = curve.points.point(segment);
  const double* p1 = curve.points.point(segment + 1);
  const double* t0 = curve.tangents.point(segment);
  const double* t1 = curve.tangents.point(segment + 1);
  std::vector<double> control(4 * dim);
  for (size_t j = 0; j < dim; ++j) {
    control[j] = p0[j];
    control[dim + j] = p0[j] + third * t0[j];
    control[2 * dim + j] = p1[j] - third * t1[j];
    control[3 * dim + j] = p1[j];
  }
  return control;
}

absl::Status EvaluateHermiteCurve(const HermiteCurveView& curve,
                                  absl::Span<const double> parameters,
                                  CurveOutput output,
                                  const ExecutionContext& context) {
  RETURN_IF_ERROR(ValidateHermiteCurve(curve));
  return internal::EvaluateValidHermiteCurve(curve, parameters, output,
                                             context);
}

namespace internal {

absl::Status EvaluateValidHermiteCurve(const HermiteCurveView& curve,
                                       absl::Span<const double> parameters,
                                       CurveOutput output,
                                       const ExecutionContext& context) {
  const auto [start, end] = HermiteDomain(curve);
  const int dimension = curve.points.dimension;
  RETURN_IF_ERROR(ValidateBatch(parameters, start, end, output, dimension));
  const std::vector<double> nodes = HermiteNodes(curve);
  const int max_order = static_cast<int>(output.size()) - 1;
  std::vector<BezierPointEvaluator> segments;
  segments.reserve(nodes.size() - 1);
  for (size_t k = 0; k + 1 < nodes.size(); ++k) {
    const std::vector<double> control = HermiteSegmentBezier(curve, nodes, k);
    segments.emplace_back(
        BezierCurveView{.control_points = {dimension, control}, .weights = {}},
        max_order);
  }
  const size_t dim = static_cast<size_t>(dimension);
  const size_t orders = output.size();
  return ParallelFor(
      parameters.size(), context, [&](size_t begin, size_t stop) {
        std::vector<double> scratch(segments[0].scratch_size() + orders * dim);
        double* derivatives = scratch.data() + segments[0].scratch_size();
        for (size_t r = begin; r < stop; ++r) {
          const size_t k = FindSegment(nodes, parameters[r]);
          const double width = nodes[k + 1] - nodes[k];
          const double local =
              std::clamp((parameters[r] - nodes[k]) / width, 0.0, 1.0);
          segments[k].Evaluate(local, scratch.data(), derivatives);
          double chain = 1.0;  // (dt_local / dt)^k
          for (size_t order = 0; order < orders; ++order) {
            double* out = output[order].data() + r * dim;
            for (size_t j = 0; j < dim; ++j) {
              out[j] = chain * derivatives[order * dim + j];
            }
            chain /= width;
          }
        }
      });
}

}  // namespace internal

absl::Status EvaluateHermiteBasis(absl::Span<const double> parameters,
                                  CurveOutput output,
                                  const ExecutionContext& context) {
  // The basis functions are the 4D Hermite curve with P0 = e0,
  // P1 = e1, T0 = e2, T1 = e3, so C(t) = (H0, H1, H2, H3)(t).
  const std::vector<double> points = {1, 0, 0, 0, 0, 1, 0, 0};
  const std::vector<double> tangents = {0, 0, 1, 0, 0, 0, 0, 1};
  const HermiteCurveView basis{
      .points = {4, points}, .tangents = {4, tangents}, .nodes = {}};
  return EvaluateHermiteCurve(basis, parameters, output, context);
}

}  // namespace freeform
