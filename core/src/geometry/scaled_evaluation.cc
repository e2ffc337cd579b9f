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

// ProductsLeaveTheSafeRange says whether, on some axis of `dimension`, the
// largest coordinate times the smallest nonzero weight or the largest
// weight leaves the safe range (each axis is scaled by its own exponent).
bool ProductsLeaveTheSafeRange(int dimension,
                               absl::Span<const double> coordinates,
                               absl::Span<const double> weights) {
  if (weights.empty()) return false;
  double smallest_weight = 0.0;
  for (const double w : weights) {
    if (w > 0.0 && (smallest_weight == 0.0 || w < smallest_weight)) {
      smallest_weight = w;
    }
  }
  if (smallest_weight == 0.0) return false;
  const size_t d = static_cast<size_t>(dimension);
  std::vector<double> largest(d, 0.0);
  for (size_t c = 0; c < coordinates.size(); ++c) {
    largest[c % d] = std::max(largest[c % d], std::abs(coordinates[c]));
  }
  // An axis all at the origin gives e = 0 as coordinates near 1 do: either
  // way the copy evaluates right.
  const int low = ExponentAbove(smallest_weight);
  const int high = LargestExponent(weights);
  return std::any_of(largest.begin(), largest.end(), [&](double x) {
    const int e = ExponentAbove(x);
    return e + low < -kSafeProductExponent || e + high > kSafeProductExponent;
  });
}

// Rescale multiplies coordinate j of every point (`dimension` values each)
// of `buffer` by 2^(e_j + offset), e_j the copy's exponent of axis j.
void Rescale(absl::Span<double> buffer, int dimension,
             const ScaledValues& values, int offset) {
  const size_t d = static_cast<size_t>(dimension);
  for (size_t i = 0; i < buffer.size(); ++i) {
    const int exponent = values.AxisExponent(i % d) + offset;
    if (exponent != 0) buffer[i] = std::ldexp(buffer[i], exponent);
  }
}

}  // namespace

bool NeedsScaledEvaluation(const Curve& curve) {
  return std::visit(Overloaded{[](const BezierCurve& bezier) {
                                 return ProductsLeaveTheSafeRange(
                                     bezier.view().control_points.dimension,
                                     bezier.view().control_points.coordinates,
                                     bezier.view().weights);
                               },
                               [](const BSplineCurve& bspline) {
                                 return ProductsLeaveTheSafeRange(
                                     bspline.view().control_points.dimension,
                                     bspline.view().control_points.coordinates,
                                     bspline.view().weights);
                               },
                               [](const LagrangeCurve&) { return false; },
                               [](const HermiteCurve&) { return false; }},
                    curve);
}

bool NeedsScaledEvaluation(const Surface& surface) {
  return std::visit(Overloaded{[](const BezierSurface& bezier) {
                                 return ProductsLeaveTheSafeRange(
                                     bezier.view().control_net.dimension,
                                     bezier.view().control_net.coordinates,
                                     bezier.view().weights);
                               },
                               [](const BSplineSurface& bspline) {
                                 return ProductsLeaveTheSafeRange(
                                     bspline.view().control_net.dimension,
                                     bspline.view().control_net.coordinates,
                                     bspline.view().weights);
                               },
                               [](const TriangularPatch& patch) {
                                 return ProductsLeaveTheSafeRange(
                                     patch.view().control_points.dimension,
                                     patch.view().control_points.coordinates,
                                     patch.view().weights);
                               }},
                    surface);
}

absl::Status EvaluateScaledCurve(const Curve& curve,
                                 absl::Span<const double> parameters,
                                 CurveOutput output,
                                 const ExecutionContext& context) {
  // Each axis by its own power of two: a point's coordinates are each a
  // ratio of sums over one axis, so a huge axis costs another no digits.
  const ScaledCurve scaled = ScaledCurve::OfAxes(curve);
  std::vector<double> mapped(parameters.size());
  for (size_t r = 0; r < parameters.size(); ++r) {
    mapped[r] = scaled.ToScaled(parameters[r]);
  }
  RETURN_IF_ERROR(EvaluateKind(scaled.curve(), absl::MakeConstSpan(mapped),
                               output, context));
  const ScaledValues& values = scaled.scale();
  for (size_t k = 0; k < output.size(); ++k) {
    Rescale(output[k], DimensionOf(curve), values,
            -static_cast<int>(k) * values.u_exponent);
  }
  return absl::OkStatus();
}

absl::Status EvaluateScaledSurface(const Surface& surface,
                                   const SurfaceSamples& samples,
                                   SurfaceOutput output,
                                   const ExecutionContext& context) {
  const ScaledSurface scaled = ScaledSurface::OfAxes(surface);
  std::vector<double> storage;
  RETURN_IF_ERROR(EvaluateKind(
      scaled.surface(), scaled.Samples(samples, storage), output, context));
  const ScaledValues& values = scaled.scale();
  for (int total = 0; PartialIndex(total, 0) < output.size(); ++total) {
    for (int order_v = 0; order_v <= total; ++order_v) {
      const size_t index = PartialIndex(total - order_v, order_v);
      if (index >= output.size()) break;
      Rescale(
          output[index], DimensionOf(surface), values,
          -(total - order_v) * values.u_exponent - order_v * values.v_exponent);
    }
  }
  return absl::OkStatus();
}

}  // namespace freeform::internal
