#include "prepare.h"

#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <variant>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "convert.h"
#include "freeform/core/lagrange.h"
#include "freeform/core/overloaded.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"

namespace freeform::server {
namespace {

std::string Join(absl::string_view prefix, absl::string_view name) {
  return absl::StrCat(prefix, ".", name);
}

// Puts `prefix` in front of the field path of an error.
template <typename T>
absl::StatusOr<T> Prefixed(absl::StatusOr<T> result, absl::string_view prefix) {
  if (!result.ok()) return PrefixFieldPath(result.status(), prefix);
  return result;
}

// The point limit and the degree limit for `count` points of a curve of
// degree `degree`, both named `field`.
absl::Status CheckCountAndDegree(uint64_t count, int64_t degree,
                                 const ServiceLimits& limits,
                                 absl::string_view field) {
  RETURN_IF_ERROR(CheckPointLimit(count, limits, field));
  return CheckDegreeLimit(degree, limits, field);
}

// Dimension limit (`field`.dimension), then the count and degree limits on
// the points of `message`, whose degree is their count - 1 plus `extra`.
absl::StatusOr<PointsView> LimitedPoints(const v1::Points& message,
                                         const ServiceLimits& limits,
                                         absl::string_view field,
                                         bool degree_from_count) {
  RETURN_IF_ERROR(CheckDimensionLimit(message.dimension(), limits, field));
  const PointsView points = ViewOf(message);
  const uint64_t count = points.size();
  RETURN_IF_ERROR(CheckCountAndDegree(
      count, degree_from_count ? static_cast<int64_t>(count) - 1 : 0, limits,
      field));
  return points;
}

absl::StatusOr<Curve> BezierOf(const v1::BezierCurve& message,
                               BezierAlgorithm algorithm,
                               const ServiceLimits& limits) {
  absl::StatusOr<PointsView> points =
      LimitedPoints(message.control_points(), limits, "control_points", true);
  if (!points.ok()) return points.status();
  return BezierCurve::Create(
      {.control_points = *points, .weights = SpanOf(message.weights())},
      algorithm);
}

absl::StatusOr<Curve> PowerOf(const v1::PowerCurve& message,
                              BezierAlgorithm algorithm,
                              const ServiceLimits& limits) {
  absl::StatusOr<PointsView> coefficients =
      LimitedPoints(message.coefficients(), limits, "coefficients", true);
  if (!coefficients.ok()) return coefficients.status();
  return BezierCurve::FromPowerForm(*coefficients, algorithm);
}

absl::StatusOr<Curve> BSplineOf(const v1::BSplineCurve& message,
                                const ServiceLimits& limits) {
  RETURN_IF_ERROR(CheckDegreeLimit(message.degree(), limits, "degree"));
  absl::StatusOr<PointsView> points =
      LimitedPoints(message.control_points(), limits, "control_points", false);
  if (!points.ok()) return points.status();
  return BSplineCurve::Create({.degree = static_cast<int>(message.degree()),
                               .control_points = *points,
                               .knots = SpanOf(message.knots()),
                               .weights = SpanOf(message.weights())});
}

absl::StatusOr<Curve> LagrangeOf(const v1::LagrangeCurve& message,
                                 const ServiceLimits& limits) {
  absl::StatusOr<PointsView> points =
      LimitedPoints(message.points(), limits, "points", true);
  if (!points.ok()) return points.status();
  return LagrangeCurve::Create(
      {.points = *points, .nodes = SpanOf(message.nodes())});
}

absl::StatusOr<Curve> HermiteOf(const v1::HermiteCurve& message,
                                const ServiceLimits& limits) {
  absl::StatusOr<PointsView> points =
      LimitedPoints(message.points(), limits, "points", false);
  if (!points.ok()) return points.status();
  return HermiteCurve::Create({.points = *points,
                               .tangents = ViewOf(message.tangents()),
                               .nodes = SpanOf(message.nodes())});
}

absl::StatusOr<CurveBasis> BernsteinOf(const v1::BernsteinBasis& message,
                                       const ServiceLimits& limits) {
  RETURN_IF_ERROR(CheckDegreeLimit(message.degree(), limits, "degree"));
  return BernsteinFunctions::Create(static_cast<int>(message.degree()),
                                    SpanOf(message.weights()));
}

absl::StatusOr<CurveBasis> BSplineBasisOf(const v1::BSplineBasis& message,
                                          const ServiceLimits& limits) {
  RETURN_IF_ERROR(CheckDegreeLimit(message.degree(), limits, "degree"));
  const uint64_t knots = static_cast<uint64_t>(message.knots_size());
  RETURN_IF_ERROR(CheckPointLimit(
      knots > message.degree() ? knots - message.degree() - 1 : 0, limits,
      "knots"));
  return BSplineFunctions::Create(static_cast<int>(message.degree()),
                                  SpanOf(message.knots()),
                                  SpanOf(message.weights()));
}

absl::StatusOr<CurveBasis> LagrangeBasisOf(const v1::LagrangeBasis& message,
                                           const ServiceLimits& limits) {
  const uint64_t count = static_cast<uint64_t>(message.nodes_size());
  RETURN_IF_ERROR(CheckCountAndDegree(count, static_cast<int64_t>(count) - 1,
                                      limits, "nodes"));
  return LagrangeFunctions::Create(SpanOf(message.nodes()));
}

absl::StatusOr<Surface> BezierSurfaceOf(const v1::BezierSurface& message,
                                        const ServiceLimits& limits) {
  absl::StatusOr<ControlNetView> net =
      PrepareNet(message.control_net(), limits, "control_net", true);
  if (!net.ok()) return net.status();
  return BezierSurface::Create(
      {.control_net = *net, .weights = SpanOf(message.weights())});
}

absl::StatusOr<Surface> BSplineSurfaceOf(const v1::BSplineSurface& message,
                                         const ServiceLimits& limits) {
  for (const auto& [degree, name] :
       {std::pair{message.degree_u(), "degree_u"},
        std::pair{message.degree_v(), "degree_v"}}) {
    RETURN_IF_ERROR(CheckDegreeLimit(degree, limits, name));
  }
  absl::StatusOr<ControlNetView> net =
      PrepareNet(message.control_net(), limits, "control_net", false);
  if (!net.ok()) return net.status();
  return BSplineSurface::Create(
      {.degree_u = static_cast<int>(message.degree_u()),
       .degree_v = static_cast<int>(message.degree_v()),
       .control_net = *net,
       .knots_u = SpanOf(message.knots_u()),
       .knots_v = SpanOf(message.knots_v()),
       .weights = SpanOf(message.weights())});
}

absl::StatusOr<Surface> InterpolatingOf(
    const v1::BicubicInterpolatingPatch& message, const ServiceLimits& limits) {
  absl::StatusOr<ControlNetView> points =
      PrepareNet(message.points(), limits, "points", true);
  if (!points.ok()) return points.status();
  return BezierSurface::FromInterpolatingPatch(*points);
}

absl::StatusOr<Surface> HermitePatchOf(const v1::BicubicHermitePatch& message,
                                       const ServiceLimits& limits) {
  ControlNetView nets[4];
  int index = 0;
  for (const auto& [net, name] :
       {std::pair{&message.positions(), "positions"},
        std::pair{&message.derivatives_u(), "derivatives_u"},
        std::pair{&message.derivatives_v(), "derivatives_v"},
        std::pair{&message.twists(), "twists"}}) {
    const bool empty_twists = index == 3 && net->coordinates_size() == 0;
    if (empty_twists) {
      ++index;
      continue;
    }
    absl::StatusOr<ControlNetView> view = PrepareNet(*net, limits, name, false);
    if (!view.ok()) return view.status();
    nets[index++] = *view;
  }
  return BezierSurface::FromHermitePatch(nets[0], nets[1], nets[2], nets[3]);
}

absl::StatusOr<Surface> TriangularOf(const v1::TriangularBezierPatch& message,
                                     const ServiceLimits& limits) {
  RETURN_IF_ERROR(CheckDegreeLimit(message.degree(), limits, "degree"));
  absl::StatusOr<PointsView> points =
      LimitedPoints(message.control_points(), limits, "control_points", false);
  if (!points.ok()) return points.status();
  absl::StatusOr<TriangularPatch> patch = TriangularPatch::Create(
      {.degree = static_cast<int>(message.degree()),
       .control_points = *points,
       .weights = SpanOf(message.weights()),
       .domain_triangle = SpanOf(message.domain_triangle().coordinates())});
  if (patch.ok()) return *std::move(patch);
  // The core names the triangle's values "domain_triangle[i]"; in the
  // request they are a Points message.
  const std::string path = FieldPathOf(patch.status()).value_or("");
  if (absl::StartsWith(path, "domain_triangle[")) {
    return InvalidFieldError(
        absl::StrCat("domain_triangle.coordinates",
                     path.substr(std::string("domain_triangle").size())),
        FieldRuleOf(patch.status()));
  }
  return patch.status();
}

}  // namespace

absl::StatusOr<PointsView> PreparePoints(const v1::Points& message,
                                         const ServiceLimits& limits,
                                         absl::string_view field) {
  absl::StatusOr<PointsView> points =
      LimitedPoints(message, limits, field, false);
  if (!points.ok()) return points.status();
  RETURN_IF_ERROR(ValidatePoints(*points, field));
  return points;
}

absl::StatusOr<ControlNetView> PrepareNet(const v1::ControlNet& message,
                                          const ServiceLimits& limits,
                                          absl::string_view field,
                                          bool degrees_from_counts) {
  RETURN_IF_ERROR(CheckDimensionLimit(message.dimension(), limits, field));
  for (const auto& [count, name] : {std::pair{message.count_u(), "count_u"},
                                    std::pair{message.count_v(), "count_v"}}) {
    if (absl::Status status = CheckCountAndDegree(
            count, degrees_from_counts ? int64_t{count} - 1 : 0, limits,
            Join(field, name));
        !status.ok()) {
      return status;
    }
  }
  if (absl::Status status =
          CheckPointLimit(uint64_t{message.count_u()} * message.count_v(),
                          limits, Join(field, "coordinates"));
      !status.ok()) {
    return status;
  }
  return ControlNetView{.dimension = static_cast<int>(message.dimension()),
                        .count_u = static_cast<int>(message.count_u()),
                        .count_v = static_cast<int>(message.count_v()),
                        .coordinates = SpanOf(message.coordinates())};
}

absl::StatusOr<Curve> PrepareCurveToEvaluate(const v1::Curve& message,
                                             const ServiceLimits& limits,
                                             absl::string_view field,
                                             BezierAlgorithm algorithm) {
  switch (message.kind_case()) {
    case v1::Curve::kBezier:
      return Prefixed(BezierOf(message.bezier(), algorithm, limits),
                      Join(field, "bezier"));
    case v1::Curve::kBspline:
      return Prefixed(BSplineOf(message.bspline(), limits),
                      Join(field, "bspline"));
    case v1::Curve::kLagrange:
      return Prefixed(LagrangeOf(message.lagrange(), limits),
                      Join(field, "lagrange"));
    case v1::Curve::kHermite:
      return Prefixed(HermiteOf(message.hermite(), limits),
                      Join(field, "hermite"));
    case v1::Curve::kPower:
      return Prefixed(PowerOf(message.power(), algorithm, limits),
                      Join(field, "power"));
    case v1::Curve::KIND_NOT_SET:
      break;
  }
  return InvalidFieldError(
      field, "set one curve kind: bezier, bspline, lagrange, hermite, power");
}

absl::StatusOr<Curve> PrepareCurve(const v1::Curve& message,
                                   const ServiceLimits& limits,
                                   absl::string_view field) {
  absl::StatusOr<Curve> curve =
      PrepareCurveToEvaluate(message, limits, field, BezierAlgorithm::kAuto);
  if (!curve.ok()) return curve.status();
  // Only a Lagrange curve's Bezier form can fail to exist in double
  // precision; a new kind must say whether its own can.
  const absl::Status pieces = std::visit(
      Overloaded{[](const BezierCurve&) { return absl::OkStatus(); },
                 [](const BSplineCurve&) { return absl::OkStatus(); },
                 [&](const LagrangeCurve& lagrange) {
                   return PrefixFieldPath(
                       CheckLagrangeBezierForm(lagrange.view()),
                       Join(field, "lagrange"));
                 },
                 [](const HermiteCurve&) { return absl::OkStatus(); }},
      *curve);
  if (!pieces.ok()) return pieces;
  return curve;
}

absl::StatusOr<CurveBasis> PrepareBasis(const v1::Basis& message,
                                        const ServiceLimits& limits,
                                        absl::string_view field) {
  switch (message.kind_case()) {
    case v1::Basis::kBernstein:
      return Prefixed(BernsteinOf(message.bernstein(), limits),
                      Join(field, "bernstein"));
    case v1::Basis::kBspline:
      return Prefixed(BSplineBasisOf(message.bspline(), limits),
                      Join(field, "bspline"));
    case v1::Basis::kLagrange:
      return Prefixed(LagrangeBasisOf(message.lagrange(), limits),
                      Join(field, "lagrange"));
    case v1::Basis::kHermite:
      return CurveBasis(HermiteFunctions());
    case v1::Basis::KIND_NOT_SET:
      break;
  }
  return InvalidFieldError(
      field, "set one basis kind: bernstein, bspline, lagrange, hermite");
}

absl::StatusOr<Surface> PrepareSurface(const v1::Surface& message,
                                       const ServiceLimits& limits,
                                       absl::string_view field) {
  switch (message.kind_case()) {
    case v1::Surface::kBezier:
      return Prefixed(BezierSurfaceOf(message.bezier(), limits),
                      Join(field, "bezier"));
    case v1::Surface::kBspline:
      return Prefixed(BSplineSurfaceOf(message.bspline(), limits),
                      Join(field, "bspline"));
    case v1::Surface::kBicubicInterpolating:
      return Prefixed(InterpolatingOf(message.bicubic_interpolating(), limits),
                      Join(field, "bicubic_interpolating"));
    case v1::Surface::kBicubicHermite:
      return Prefixed(HermitePatchOf(message.bicubic_hermite(), limits),
                      Join(field, "bicubic_hermite"));
    case v1::Surface::kTriangularBezier:
      return Prefixed(TriangularOf(message.triangular_bezier(), limits),
                      Join(field, "triangular_bezier"));
    case v1::Surface::KIND_NOT_SET:
      break;
  }
  return InvalidFieldError(
      field,
      "set one surface kind: bezier, bspline, bicubic_interpolating, "
      "bicubic_hermite, triangular_bezier");
}

}  // namespace freeform::server
