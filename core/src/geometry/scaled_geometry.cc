#include "geometry/scaled_geometry.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <variant>

#include "base/scaled.h"
#include "geometry/variant_dispatch.h"

namespace freeform::internal {
namespace {

// Scaled returns values * 2^-e.
std::vector<double> Scaled(absl::Span<const double> values, int e) {
  std::vector<double> result(values.size());
  for (size_t i = 0; i < values.size(); ++i) {
    result[i] = std::ldexp(values[i], -e);
  }
  return result;
}

// Whether a copy scales its coordinates by one exponent or each axis by
// its own (ScaledCurve::OfAxes).
enum class Axes { kTogether, kEach };

// AxisExponents returns, per axis of `dimension`, the exponent of its
// largest coordinate.
std::vector<int> AxisExponents(int dimension,
                               absl::Span<const double> coordinates) {
  const size_t d = static_cast<size_t>(dimension);
  std::vector<double> largest(d, 0.0);
  for (size_t c = 0; c < coordinates.size(); ++c) {
    largest[c % d] = std::max(largest[c % d], std::abs(coordinates[c]));
  }
  std::vector<int> exponents(d);
  for (size_t j = 0; j < d; ++j) exponents[j] = ExponentAbove(largest[j]);
  return exponents;
}

// ScaleCoordinates fills the coordinates (exponent e, or each axis's with
// Axes::kEach) and the weights (exponent f). A control point of weight 0 is
// a direction, whose homogeneous point (P, 0) is not w P: dividing the
// other weights by 2^f divides their homogeneous points by 2^f, so a
// direction is divided by 2^(e + f) to stay the same geometry (by 2^e
// alone it would count 2^f times as much). When that overflows the copy
// does not validate (the geometry itself is used).
void ScaleCoordinates(int dimension, absl::Span<const double> coordinates,
                      absl::Span<const double> weights, Axes axes,
                      ScaledValues& values) {
  values.coordinate_exponent = LargestExponent(coordinates);
  if (axes == Axes::kEach) {
    values.axis_exponents = AxisExponents(dimension, coordinates);
  }
  const size_t d = static_cast<size_t>(dimension);
  values.coordinates.resize(coordinates.size());
  for (size_t c = 0; c < coordinates.size(); ++c) {
    values.coordinates[c] =
        std::ldexp(coordinates[c], -values.AxisExponent(c % d));
  }
  const int weight_exponent = LargestExponent(weights);
  values.weights = Scaled(weights, weight_exponent);
  for (size_t i = 0; i < weights.size(); ++i) {
    if (weights[i] != 0.0) continue;
    for (size_t x = 0; x < d; ++x) {
      double& value = values.coordinates[i * d + x];
      value = std::ldexp(value, -weight_exponent);
    }
  }
}

// ScaleKnots fills `knots` scaled by the power of two at or above the
// domain's width, and returns that exponent.
int ScaleKnots(absl::Span<const double> knots, double width,
               std::vector<double>& scaled) {
  const int k = ExponentAbove(width);
  scaled = Scaled(knots, k);
  return k;
}

template <typename Made>
std::optional<Curve> CurveOf(Made made) {
  if (!made.ok()) return std::nullopt;
  return Curve(*std::move(made));
}

template <typename Made>
std::optional<Surface> SurfaceOf(Made made) {
  if (!made.ok()) return std::nullopt;
  return Surface(*std::move(made));
}

std::optional<Curve> Copy(const BezierCurve& curve, Axes axes,
                          ScaledValues& values) {
  const BezierCurveView& view = curve.view();
  ScaleCoordinates(view.control_points.dimension,
                   view.control_points.coordinates, view.weights, axes, values);
  return CurveOf(BezierCurve::Create(
      {.control_points = {view.control_points.dimension, values.coordinates},
       .weights = values.weights}));
}

std::optional<Curve> Copy(const BSplineCurve& curve, Axes axes,
                          ScaledValues& values) {
  const BSplineCurveView& view = curve.view();
  ScaleCoordinates(view.control_points.dimension,
                   view.control_points.coordinates, view.weights, axes, values);
  const ParameterDomain domain = curve.domain();
  values.u_exponent =
      ScaleKnots(view.knots, domain.end - domain.start, values.knots_u);
  return CurveOf(BSplineCurve::Create(
      {.degree = view.degree,
       .control_points = {view.control_points.dimension, values.coordinates},
       .knots = values.knots_u,
       .weights = values.weights}));
}

// NodeWidth returns the width of a node-based domain (0 without nodes).
double NodeWidth(absl::Span<const double> nodes) {
  return nodes.empty() ? 0.0 : nodes.back() - nodes.front();
}

// The polynomial kinds keep one exponent: without weights no product w P
// can lose a small axis.
std::optional<Curve> Copy(const LagrangeCurve& curve, Axes,
                          ScaledValues& values) {
  const LagrangeCurveView& view = curve.view();
  ScaleCoordinates(view.points.dimension, view.points.coordinates, {},
                   Axes::kTogether, values);
  values.u_exponent =
      ScaleKnots(view.nodes, NodeWidth(view.nodes), values.knots_u);
  return CurveOf(LagrangeCurve::Create(
      {.points = {view.points.dimension, values.coordinates},
       .nodes = values.knots_u}));
}

std::optional<Curve> Copy(const HermiteCurve& curve, Axes,
                          ScaledValues& values) {
  const HermiteCurveView& view = curve.view();
  // A piece reaches about |T| h / 3 beyond its end points (its Bezier
  // points), h the widest node spacing.
  double spacing = view.nodes.empty() ? 1.0 : 0.0;
  for (size_t i = 1; i < view.nodes.size(); ++i) {
    spacing = std::max(spacing, view.nodes[i] - view.nodes[i - 1]);
  }
  double reach = 0.0;
  for (const double t : view.tangents.coordinates) {
    reach = std::max(reach, std::abs(t) * spacing);
  }
  values.coordinate_exponent =
      std::max(LargestExponent(view.points.coordinates), ExponentAbove(reach));
  values.coordinates =
      Scaled(view.points.coordinates, values.coordinate_exponent);
  values.u_exponent =
      ScaleKnots(view.nodes, NodeWidth(view.nodes), values.knots_u);
  // dC/dt scales by 2^(k - e).
  values.tangents = Scaled(view.tangents.coordinates,
                           values.coordinate_exponent - values.u_exponent);
  return CurveOf(HermiteCurve::Create(
      {.points = {view.points.dimension, values.coordinates},
       .tangents = {view.tangents.dimension, values.tangents},
       .nodes = values.knots_u}));
}

ControlNetView ScaledNet(const ControlNetView& net,
                         const ScaledValues& values) {
  return {.dimension = net.dimension,
          .count_u = net.count_u,
          .count_v = net.count_v,
          .coordinates = values.coordinates};
}

std::optional<Surface> Copy(const BezierSurface& surface, Axes axes,
                            ScaledValues& values) {
  const BezierSurfaceView& view = surface.view();
  ScaleCoordinates(view.control_net.dimension, view.control_net.coordinates,
                   view.weights, axes, values);
  return SurfaceOf(
      BezierSurface::Create({.control_net = ScaledNet(view.control_net, values),
                             .weights = values.weights}));
}

std::optional<Surface> Copy(const BSplineSurface& surface, Axes axes,
                            ScaledValues& values) {
  const BSplineSurfaceView& view = surface.view();
  ScaleCoordinates(view.control_net.dimension, view.control_net.coordinates,
                   view.weights, axes, values);
  const SurfaceDomain domain = surface.domain();
  values.u_exponent =
      ScaleKnots(view.knots_u, domain.u_end - domain.u_start, values.knots_u);
  values.v_exponent =
      ScaleKnots(view.knots_v, domain.v_end - domain.v_start, values.knots_v);
  return SurfaceOf(BSplineSurface::Create(
      {.degree_u = view.degree_u,
       .degree_v = view.degree_v,
       .control_net = ScaledNet(view.control_net, values),
       .knots_u = values.knots_u,
       .knots_v = values.knots_v,
       .weights = values.weights}));
}

std::optional<Surface> Copy(const TriangularPatch& patch, Axes axes,
                            ScaledValues& values) {
  const TriangularPatchView& view = patch.view();
  ScaleCoordinates(view.control_points.dimension,
                   view.control_points.coordinates, view.weights, axes, values);
  // The domain triangle is kept as it is (its (u, v) are the answers').
  values.knots_u.assign(view.domain_triangle.begin(),
                        view.domain_triangle.end());
  return SurfaceOf(TriangularPatch::Create(
      {.degree = view.degree,
       .control_points = {view.control_points.dimension, values.coordinates},
       .weights = values.weights,
       .domain_triangle = values.knots_u}));
}

}  // namespace

// Copied makes the copy (each axis by its own exponent when `each_axis`), or
// keeps the geometry (exponents 0) when the copy does not validate.
ScaledCurve ScaledCurve::Copied(const Curve& curve, bool each_axis) {
  ScaledCurve result;
  const Axes axes = each_axis ? Axes::kEach : Axes::kTogether;
  result.curve_ = std::visit(
      [&](const auto& kind) { return Copy(kind, axes, result.values_); },
      curve);
  if (!result.curve_.has_value()) {
    result.values_ = ScaledValues{};
    result.curve_ = curve;
  }
  return result;
}

ScaledCurve ScaledCurve::Of(const Curve& curve) { return Copied(curve, false); }

ScaledCurve ScaledCurve::OfAxes(const Curve& curve) {
  return Copied(curve, true);
}

ScaledSurface ScaledSurface::Copied(const Surface& surface, bool each_axis) {
  ScaledSurface result;
  const Axes axes = each_axis ? Axes::kEach : Axes::kTogether;
  result.surface_ = std::visit(
      [&](const auto& kind) { return Copy(kind, axes, result.values_); },
      surface);
  if (!result.surface_.has_value()) {
    result.values_ = ScaledValues{};
    result.surface_ = surface;
  }
  return result;
}

ScaledSurface ScaledSurface::Of(const Surface& surface) {
  return Copied(surface, false);
}

ScaledSurface ScaledSurface::OfAxes(const Surface& surface) {
  return Copied(surface, true);
}

SurfaceSamples ScaledSurface::Samples(const SurfaceSamples& samples,
                                      std::vector<double>& storage) const {
  const int ku = values_.u_exponent;
  const int kv = values_.v_exponent;
  if (ku == 0 && kv == 0) return samples;
  if (!samples.grid) {
    storage.resize(samples.uv.size());
    for (size_t i = 0; i < samples.uv.size(); ++i) {
      storage[i] = std::ldexp(samples.uv[i], i % 2 == 0 ? -ku : -kv);
    }
    return SurfaceSamples::Pairs(storage);
  }
  storage.resize(samples.u.size() + samples.v.size());
  for (size_t i = 0; i < samples.u.size(); ++i) {
    storage[i] = std::ldexp(samples.u[i], -ku);
  }
  for (size_t j = 0; j < samples.v.size(); ++j) {
    storage[samples.u.size() + j] = std::ldexp(samples.v[j], -kv);
  }
  const absl::Span<const double> all(storage);
  return SurfaceSamples::Grid(all.subspan(0, samples.u.size()),
                              all.subspan(samples.u.size()));
}

namespace {

// The bytes of a copy holding `values` doubles twice in `blocks` heap
// blocks each, with glibc's header and rounding per block, and of a copy
// scaled per axis its exponents and their largest coordinates (one int and
// one double per axis, fewer than the values).
uint64_t CopyBytes(uint64_t values, uint64_t blocks) {
  return 2 * (8 * values + 32 * blocks) + sizeof(ScaledValues) +
         (4 + 8) * values + 2 * 32;
}

}  // namespace

uint64_t ScaledCopyBytes(const Curve& curve) {
  return std::visit(
      Overloaded{[](const BezierCurve& bezier) {
                   const BezierCurveView& view = bezier.view();
                   return CopyBytes(view.control_points.coordinates.size() +
                                        view.weights.size(),
                                    2) +
                          sizeof(Curve);
                 },
                 [](const BSplineCurve& bspline) {
                   const BSplineCurveView& view = bspline.view();
                   return CopyBytes(view.control_points.coordinates.size() +
                                        view.weights.size() + view.knots.size(),
                                    3) +
                          sizeof(Curve);
                 },
                 [](const LagrangeCurve& lagrange) {
                   const LagrangeCurveView& view = lagrange.view();
                   return CopyBytes(view.points.coordinates.size() +
                                        view.nodes.size(),
                                    2) +
                          sizeof(Curve);
                 },
                 [](const HermiteCurve& hermite) {
                   const HermiteCurveView& view = hermite.view();
                   return CopyBytes(view.points.coordinates.size() +
                                        view.tangents.coordinates.size() +
                                        view.nodes.size(),
                                    3) +
                          sizeof(Curve);
                 }},
      curve);
}

uint64_t ScaledCopyBytes(const Surface& surface) {
  return std::visit(
      Overloaded{[](const BezierSurface& bezier) {
                   const BezierSurfaceView& view = bezier.view();
                   return CopyBytes(view.control_net.coordinates.size() +
                                        view.weights.size(),
                                    2) +
                          sizeof(Surface);
                 },
                 [](const BSplineSurface& bspline) {
                   const BSplineSurfaceView& view = bspline.view();
                   return CopyBytes(view.control_net.coordinates.size() +
                                        view.weights.size() +
                                        view.knots_u.size() +
                                        view.knots_v.size(),
                                    4) +
                          sizeof(Surface);
                 },
                 [](const TriangularPatch& patch) {
                   const TriangularPatchView& view = patch.view();
                   return CopyBytes(view.control_points.coordinates.size() +
                                        view.weights.size() +
                                        view.domain_triangle.size(),
                                    3) +
                          sizeof(Surface);
                 }},
      surface);
}

}  // namespace freeform::internal
