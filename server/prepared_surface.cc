#include "prepared_surface.h"

#include <memory>
#include <utility>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "convert.h"
#include "freeform/core/patches.h"
#include "freeform/core/status.h"
#include "freeform/core/tensor_surface.h"
#include "freeform/core/triangular.h"

namespace freeform::server {
namespace {

// Dimension, size and degree limits of a net, then its own validation.
absl::StatusOr<ControlNetView> NetOf(const v1::ControlNet& net,
                                     const ServiceLimits& limits,
                                     absl::string_view field,
                                     bool degrees_from_counts) {
  if (absl::Status status = CheckDimensionLimit(net.dimension(), limits, field);
      !status.ok()) {
    return status;
  }
  if (absl::Status status = CheckPointLimit(
          uint64_t{net.count_u()} * net.count_v(), limits, field);
      !status.ok()) {
    return status;
  }
  if (degrees_from_counts) {
    for (auto [count, name] : {std::pair{net.count_u(), "count_u"},
                               std::pair{net.count_v(), "count_v"}}) {
      if (absl::Status status = CheckDegreeLimit(
              int64_t{count} - 1, limits, absl::StrCat(field, ".", name));
          !status.ok()) {
        return status;
      }
    }
  }
  const ControlNetView view{.dimension = static_cast<int>(net.dimension()),
                            .count_u = static_cast<int>(net.count_u()),
                            .count_v = static_cast<int>(net.count_v()),
                            .coordinates = SpanOf(net.coordinates())};
  if (absl::Status status = ValidateControlNet(view, field); !status.ok()) {
    return status;
  }
  return view;
}

PreparedSurface Tensor(int dimension, SurfaceDomain domain,
                       SurfaceEvaluator evaluate) {
  return PreparedSurface{.dimension = dimension,
                         .u_start = domain.u_start,
                         .u_end = domain.u_end,
                         .v_start = domain.v_start,
                         .v_end = domain.v_end,
                         .triangular = false,
                         .evaluate = std::move(evaluate)};
}

// A bicubic Bezier surface over a net the prepared surface owns.
PreparedSurface OwnedBicubic(std::vector<double> net, int dimension) {
  auto owned = std::make_shared<const std::vector<double>>(std::move(net));
  return Tensor(
      dimension, BezierSurfaceDomain(),
      [owned, dimension](const SurfaceSamples& samples, SurfaceOutput output,
                         const ExecutionContext& context) {
        const BezierSurfaceView surface{.control_net = {.dimension = dimension,
                                                        .count_u = 4,
                                                        .count_v = 4,
                                                        .coordinates = *owned},
                                        .weights = {}};
        return EvaluateBezierSurface(surface, samples, output, context);
      });
}

absl::StatusOr<PreparedSurface> PrepareBezier(const v1::BezierSurface& message,
                                              const ServiceLimits& limits) {
  absl::StatusOr<BezierSurfaceView> surface =
      ValidatedBezierSurface(message, limits);
  if (!surface.ok()) return surface.status();
  return Tensor(
      surface->control_net.dimension, BezierSurfaceDomain(),
      [surface = *surface](const SurfaceSamples& samples, SurfaceOutput output,
                           const ExecutionContext& context) {
        return EvaluateBezierSurface(surface, samples, output, context);
      });
}

absl::StatusOr<PreparedSurface> PrepareBSpline(
    const v1::BSplineSurface& message, const ServiceLimits& limits) {
  absl::StatusOr<BSplineSurfaceView> surface =
      ValidatedBSplineSurface(message, limits);
  if (!surface.ok()) return surface.status();
  return Tensor(
      surface->control_net.dimension, BSplineSurfaceDomain(*surface),
      [surface = *surface](const SurfaceSamples& samples, SurfaceOutput output,
                           const ExecutionContext& context) {
        return EvaluateBSplineSurface(surface, samples, output, context);
      });
}

// A 2 x 2 (or, when `optional`, empty) net of the given dimension.
absl::Status CheckCornerNet(const v1::ControlNet& net, uint32_t dimension,
                            absl::string_view field, bool optional) {
  if (optional && net.coordinates_size() == 0) return absl::OkStatus();
  if (net.dimension() != dimension) {
    return InvalidFieldError(
        absl::StrCat(field, ".dimension"),
        absl::StrCat("must equal the positions' dimension ", dimension));
  }
  if (net.count_u() != 2 || net.count_v() != 2) {
    return InvalidFieldError(absl::StrCat(field, ".count_u"),
                             "a Hermite patch has 2 x 2 corners");
  }
  const ControlNetView view{.dimension = static_cast<int>(dimension),
                            .count_u = 2,
                            .count_v = 2,
                            .coordinates = SpanOf(net.coordinates())};
  return ValidateControlNet(view, field);
}

absl::StatusOr<PreparedSurface> PrepareHermite(
    const v1::BicubicHermitePatch& message, const ServiceLimits& limits) {
  const uint32_t dimension = message.positions().dimension();
  if (absl::Status status = CheckDimensionLimit(dimension, limits, "positions");
      !status.ok()) {
    return status;
  }
  for (const auto& [net, field, optional] :
       {std::tuple{&message.positions(), "positions", false},
        std::tuple{&message.derivatives_u(), "derivatives_u", false},
        std::tuple{&message.derivatives_v(), "derivatives_v", false},
        std::tuple{&message.twists(), "twists", true}}) {
    if (absl::Status status = CheckCornerNet(*net, dimension, field, optional);
        !status.ok()) {
      return status;
    }
  }
  return OwnedBicubic(
      HermiteToBezierNet(static_cast<int>(dimension),
                         SpanOf(message.positions().coordinates()),
                         SpanOf(message.derivatives_u().coordinates()),
                         SpanOf(message.derivatives_v().coordinates()),
                         SpanOf(message.twists().coordinates())),
      static_cast<int>(dimension));
}

absl::StatusOr<PreparedSurface> PrepareInterpolating(
    const v1::BicubicInterpolatingPatch& message, const ServiceLimits& limits) {
  absl::StatusOr<ControlNetView> net =
      NetOf(message.points(), limits, "points", true);
  if (!net.ok()) return net.status();
  if (net->count_u != 4 || net->count_v != 4) {
    return InvalidFieldError(
        net->count_u != 4 ? "points.count_u" : "points.count_v",
        absl::StrCat("the interpolating patch takes 4 x 4 points, got ",
                     net->count_u, " x ", net->count_v));
  }
  return OwnedBicubic(
      InterpolatingToBezierNet(net->dimension, net->coordinates),
      net->dimension);
}

absl::StatusOr<PreparedSurface> PrepareTriangular(
    const v1::TriangularBezierPatch& message, const ServiceLimits& limits) {
  absl::StatusOr<TriangularPatchView> patch =
      ValidatedTriangularPatch(message, limits);
  if (!patch.ok()) return patch.status();
  return PreparedSurface{
      .dimension = patch->control_points.dimension,
      .triangular = true,
      .evaluate = [patch = *patch](const SurfaceSamples& samples,
                                   SurfaceOutput output,
                                   const ExecutionContext& context) {
        return EvaluateTriangularPatch(patch, samples.uv, output, context);
      }};
}

absl::StatusOr<PreparedSurface> WithPrefix(
    absl::StatusOr<PreparedSurface> prepared, absl::string_view prefix) {
  if (!prepared.ok()) return PrefixFieldPath(prepared.status(), prefix);
  return prepared;
}

}  // namespace

absl::StatusOr<ControlNetView> ValidatedNet(const v1::ControlNet& net,
                                            const ServiceLimits& limits,
                                            absl::string_view field) {
  return NetOf(net, limits, field, false);
}

absl::StatusOr<BezierSurfaceView> ValidatedBezierSurface(
    const v1::BezierSurface& message, const ServiceLimits& limits) {
  absl::StatusOr<ControlNetView> net =
      NetOf(message.control_net(), limits, "control_net", true);
  if (!net.ok()) return net.status();
  const BezierSurfaceView surface{.control_net = *net,
                                  .weights = SpanOf(message.weights())};
  if (absl::Status status = ValidateBezierSurface(surface); !status.ok()) {
    return status;
  }
  return surface;
}

absl::StatusOr<BSplineSurfaceView> ValidatedBSplineSurface(
    const v1::BSplineSurface& message, const ServiceLimits& limits) {
  if (absl::Status status =
          CheckDegreeLimit(message.degree_u(), limits, "degree_u");
      !status.ok()) {
    return status;
  }
  if (absl::Status status =
          CheckDegreeLimit(message.degree_v(), limits, "degree_v");
      !status.ok()) {
    return status;
  }
  absl::StatusOr<ControlNetView> net =
      NetOf(message.control_net(), limits, "control_net", false);
  if (!net.ok()) return net.status();
  const BSplineSurfaceView surface{
      .degree_u = static_cast<int>(message.degree_u()),
      .degree_v = static_cast<int>(message.degree_v()),
      .control_net = *net,
      .knots_u = SpanOf(message.knots_u()),
      .knots_v = SpanOf(message.knots_v()),
      .weights = SpanOf(message.weights())};
  if (absl::Status status = ValidateBSplineSurface(surface); !status.ok()) {
    return status;
  }
  return surface;
}

absl::StatusOr<TriangularPatchView> ValidatedTriangularPatch(
    const v1::TriangularBezierPatch& message, const ServiceLimits& limits) {
  if (absl::Status status =
          CheckDegreeLimit(message.degree(), limits, "degree");
      !status.ok()) {
    return status;
  }
  if (absl::Status status = CheckDimensionLimit(
          message.control_points().dimension(), limits, "control_points");
      !status.ok()) {
    return status;
  }
  const TriangularPatchView patch{
      .degree = static_cast<int>(message.degree()),
      .control_points = {static_cast<int>(message.control_points().dimension()),
                         SpanOf(message.control_points().coordinates())},
      .weights = SpanOf(message.weights()),
      .domain_triangle = SpanOf(message.domain_triangle().coordinates())};
  if (absl::Status status = ValidateTriangularPatch(patch); !status.ok()) {
    // The core names the triangle's values "domain_triangle[i]"; in the
    // request they are a Points message.
    const std::string path = FieldPathOf(status).value_or("");
    if (absl::StartsWith(path, "domain_triangle[")) {
      return InvalidFieldError(
          absl::StrCat("domain_triangle.coordinates",
                       path.substr(std::string("domain_triangle").size())),
          FieldRuleOf(status));
    }
    return status;
  }
  return patch;
}

absl::StatusOr<PreparedSurface> PrepareSurface(const v1::Surface& surface,
                                               const ServiceLimits& limits) {
  switch (surface.kind_case()) {
    case v1::Surface::kBezier:
      return WithPrefix(PrepareBezier(surface.bezier(), limits),
                        "surface.bezier");
    case v1::Surface::kBspline:
      return WithPrefix(PrepareBSpline(surface.bspline(), limits),
                        "surface.bspline");
    case v1::Surface::kBicubicInterpolating:
      return WithPrefix(
          PrepareInterpolating(surface.bicubic_interpolating(), limits),
          "surface.bicubic_interpolating");
    case v1::Surface::kBicubicHermite:
      return WithPrefix(PrepareHermite(surface.bicubic_hermite(), limits),
                        "surface.bicubic_hermite");
    case v1::Surface::kTriangularBezier:
      return WithPrefix(PrepareTriangular(surface.triangular_bezier(), limits),
                        "surface.triangular_bezier");
    case v1::Surface::KIND_NOT_SET:
      break;
  }
  return InvalidFieldError(
      "surface",
      "set one surface kind: bezier, bspline, bicubic_interpolating, "
      "bicubic_hermite, triangular_bezier");
}

}  // namespace freeform::server
