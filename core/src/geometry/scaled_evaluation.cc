#include "geometry/scaled_evaluation.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "base/scaled.h"
#include "freeform/core/status_macros.h"
#include "geometry/scaled_geometry.h"
#include "geometry/variant_dispatch.h"

namespace freeform::internal {
namespace {

// Products beyond these exponents leave the safe range of w P.
constexpr int kSafeProductExponent = 960;

bool ProductsLeaveTheSafeRange(absl::Span<const double> coordinates,
                               absl::Span<const double> weights) {
  if (weights.empty()) return false;
  double smallest_weight = 0.0;
  for (const double w : weights) {
    if (w > 0.0 && (smallest_weight == 0.0 || w < smallest_weight)) {
      smallest_weight = w;
    }
  }
  if (smallest_weight == 0.0) return false;
  // Points all at the origin give e = 0 as coordinates near 1 do: either
  // way the copy evaluates right.
  const int e = LargestExponent(coordinates);
  return e + ExponentAbove(smallest_weight) < -kSafeProductExponent ||
         e + LargestExponent(weights) > kSafeProductExponent;
}

// Rescale multiplies every value of `buffer` by 2^exponent.
void Rescale(absl::Span<double> buffer, int exponent) {
  if (exponent == 0) return;
  for (double& value : buffer) value = std::ldexp(value, exponent);
}

}  // namespace

bool NeedsScaledEvaluation(const Curve& curve) {
  return std::visit(Overloaded{[](const BezierCurve& bezier) {
                                 return ProductsLeaveTheSafeRange(
                                     bezier.view().control_points.coordinates,
                                     bezier.view().weights);
                               },
                               [](const BSplineCurve& bspline) {
                                 return ProductsLeaveTheSafeRange(
                                     bspline.view().control_points.coordinates,
                                     bspline.view().weights);
                               },
                               [](const LagrangeCurve&) { return false; },
                               [](const HermiteCurve&) { return false; }},
                    curve);
}

bool NeedsScaledEvaluation(const Surface& surface) {
  return std::visit(
      Overloaded{
          [](const BezierSurface& bezier) {
            return ProductsLeaveTheSafeRange(
                bezier.view().control_net.coordinates, bezier.view().weights);
          },
          [](const BSplineSurface& bspline) {
            return ProductsLeaveTheSafeRange(
                bspline.view().control_net.coordinates, bspline.view().weights);
          },
          [](const TriangularPatch& patch) {
            return ProductsLeaveTheSafeRange(
                patch.view().control_points.coordinates, patch.view().weights);
          }},
      surface);
}

absl::Status EvaluateScaledCurve(const Curve& curve,
                                 absl::Span<const double> parameters,
                                 CurveOutput output,
                                 const ExecutionContext& context) {
  const ScaledCurve scaled = ScaledCurve::Of(curve);
  std::vector<double> mapped(parameters.size());
  for (size_t r = 0; r < parameters.size(); ++r) {
    mapped[r] = scaled.ToScaled(parameters[r]);
  }
  RETURN_IF_ERROR(EvaluateKind(scaled.curve(), absl::MakeConstSpan(mapped),
                               output, context));
  const ScaledValues& values = scaled.scale();
  for (size_t k = 0; k < output.size(); ++k) {
    Rescale(output[k], values.coordinate_exponent -
                           static_cast<int>(k) * values.u_exponent);
  }
  return absl::OkStatus();
}

absl::Status EvaluateScaledSurface(const Surface& surface,
                                   const SurfaceSamples& samples,
                                   SurfaceOutput output,
                                   const ExecutionContext& context) {
  const ScaledSurface scaled = ScaledSurface::Of(surface);
  std::vector<double> storage;
  RETURN_IF_ERROR(EvaluateKind(
      scaled.surface(), scaled.Samples(samples, storage), output, context));
  const ScaledValues& values = scaled.scale();
  for (int total = 0; PartialIndex(total, 0) < output.size(); ++total) {
    for (int order_v = 0; order_v <= total; ++order_v) {
      const size_t index = PartialIndex(total - order_v, order_v);
      if (index >= output.size()) break;
      Rescale(output[index], values.coordinate_exponent -
                                 (total - order_v) * values.u_exponent -
                                 order_v * values.v_exponent);
    }
  }
  return absl::OkStatus();
}

}  // namespace freeform::internal
