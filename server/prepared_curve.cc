#include "prepared_curve.h"

#include <memory>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "convert.h"
#include "freeform/core/bezier.h"
#include "freeform/core/bspline.h"
#include "freeform/core/hermite.h"
#include "freeform/core/lagrange.h"
#include "freeform/core/status.h"

namespace freeform::server {
namespace {

absl::Status CheckDimension(const v1::Points& points,
                            const ServiceLimits& limits,
                            absl::string_view field) {
  return CheckDimensionLimit(points.dimension(), limits, field);
}

// The degree limit (INVALID_ARGUMENT on `field`) and the size limit
// (RESOURCE_EXHAUSTED) on `count` points.
absl::Status CheckSize(size_t count, int64_t degree,
                       const ServiceLimits& limits, absl::string_view field) {
  if (absl::Status status = CheckPointLimit(count, limits, field);
      !status.ok()) {
    return status;
  }
  return CheckDegreeLimit(degree, limits, field);
}

BezierAlgorithm ToCore(v1::BezierAlgorithm algorithm) {
  switch (algorithm) {
    case v1::BEZIER_ALGORITHM_DE_CASTELJAU:
      return BezierAlgorithm::kDeCasteljau;
    case v1::BEZIER_ALGORITHM_HORNER:
      return BezierAlgorithm::kHorner;
    case v1::BEZIER_ALGORITHM_LADDER:
      return BezierAlgorithm::kLadder;
    default:
      return BezierAlgorithm::kAuto;
  }
}

PreparedCurve MakePrepared(int dimension, BatchEvaluator evaluate,
                           double domain_start = 0.0, double domain_end = 1.0) {
  return PreparedCurve{.dimension = dimension,
                       .domain_start = domain_start,
                       .domain_end = domain_end,
                       .evaluate = std::move(evaluate)};
}

// A Bezier curve over points that the prepared curve owns (converted forms).
PreparedCurve OwnedBezier(std::vector<double> control, int dimension,
                          BezierAlgorithm algorithm) {
  auto owned = std::make_shared<const std::vector<double>>(std::move(control));
  return MakePrepared(dimension, [owned, dimension, algorithm](
                                     absl::Span<const double> parameters,
                                     CurveOutput output,
                                     const ExecutionContext& context) {
    const BezierCurveView curve{.control_points = {dimension, *owned},
                                .weights = {}};
    return EvaluateBezierCurve(curve, parameters, output, context, algorithm);
  });
}

absl::StatusOr<PreparedCurve> PrepareBezier(const v1::BezierCurve& message,
                                            BezierAlgorithm algorithm,
                                            const ServiceLimits& limits) {
  absl::StatusOr<BezierCurveView> curve = ValidatedBezier(message, limits);
  if (!curve.ok()) return curve.status();
  return MakePrepared(curve->control_points.dimension,
                      [curve = *curve, algorithm](
                          absl::Span<const double> parameters,
                          CurveOutput output, const ExecutionContext& context) {
                        return EvaluateBezierCurve(curve, parameters, output,
                                                   context, algorithm);
                      });
}

absl::StatusOr<PreparedCurve> PreparePower(const v1::PowerCurve& message,
                                           BezierAlgorithm algorithm,
                                           const ServiceLimits& limits) {
  if (absl::Status status =
          CheckDimension(message.coefficients(), limits, "coefficients");
      !status.ok()) {
    return status;
  }
  const PointsView coefficients = ViewOf(message.coefficients());
  if (absl::Status status = ValidatePoints(coefficients, "coefficients");
      !status.ok()) {
    return status;
  }
  const size_t count = coefficients.size();
  if (absl::Status status = CheckSize(count, static_cast<int64_t>(count) - 1,
                                      limits, "coefficients");
      !status.ok()) {
    return status;
  }
  return OwnedBezier(PowerToBezier(coefficients), coefficients.dimension,
                     algorithm);
}

absl::StatusOr<PreparedCurve> PrepareBSpline(const v1::BSplineCurve& message,
                                             const ServiceLimits& limits) {
  absl::StatusOr<BSplineCurveView> curve = ValidatedBSpline(message, limits);
  if (!curve.ok()) return curve.status();
  const ParameterDomain domain = BSplineDomain(*curve);
  return MakePrepared(
      curve->control_points.dimension,
      [curve = *curve](absl::Span<const double> parameters, CurveOutput output,
                       const ExecutionContext& context) {
        return EvaluateBSplineCurve(curve, parameters, output, context);
      },
      domain.start, domain.end);
}

absl::StatusOr<PreparedCurve> PrepareLagrange(const v1::LagrangeCurve& message,
                                              const ServiceLimits& limits) {
  if (absl::Status status = CheckDimension(message.points(), limits, "points");
      !status.ok()) {
    return status;
  }
  const LagrangeCurveView curve{.points = ViewOf(message.points()),
                                .nodes = SpanOf(message.nodes())};
  if (absl::Status status = ValidateLagrangeCurve(curve); !status.ok()) {
    return status;
  }
  const size_t count = curve.points.size();
  if (absl::Status status =
          CheckSize(count, static_cast<int64_t>(count) - 1, limits, "points");
      !status.ok()) {
    return status;
  }
  const auto [start, end] = LagrangeDomain(curve);
  return MakePrepared(
      curve.points.dimension,
      [curve](absl::Span<const double> parameters, CurveOutput output,
              const ExecutionContext& context) {
        return EvaluateLagrangeCurve(curve, parameters, output, context);
      },
      start, end);
}

absl::StatusOr<PreparedCurve> PrepareHermite(const v1::HermiteCurve& message,
                                             const ServiceLimits& limits) {
  if (absl::Status status = CheckDimension(message.points(), limits, "points");
      !status.ok()) {
    return status;
  }
  const HermiteCurveView curve{.points = ViewOf(message.points()),
                               .tangents = ViewOf(message.tangents()),
                               .nodes = SpanOf(message.nodes())};
  if (absl::Status status = ValidateHermiteCurve(curve); !status.ok()) {
    return status;
  }
  if (absl::Status status = CheckSize(curve.points.size(), 3, limits, "points");
      !status.ok()) {
    return status;
  }
  const auto [start, end] = HermiteDomain(curve);
  return MakePrepared(
      curve.points.dimension,
      [curve](absl::Span<const double> parameters, CurveOutput output,
              const ExecutionContext& context) {
        return EvaluateHermiteCurve(curve, parameters, output, context);
      },
      start, end);
}

// Runs `prepare` and puts `prefix` in front of the field path of its error.
absl::StatusOr<PreparedCurve> WithPrefix(absl::StatusOr<PreparedCurve> prepared,
                                         absl::string_view prefix) {
  if (!prepared.ok()) return PrefixFieldPath(prepared.status(), prefix);
  return prepared;
}

absl::StatusOr<PreparedCurve> PrepareBernsteinBasis(
    const v1::BernsteinBasis& message, const ServiceLimits& limits) {
  if (absl::Status status = CheckSize(0, message.degree(), limits, "degree");
      !status.ok()) {
    return status;
  }
  const int degree = static_cast<int>(message.degree());
  const absl::Span<const double> weights = SpanOf(message.weights());
  // Validate the weights like a Bezier curve's, on dummy 1D points.
  const std::vector<double> dummy(static_cast<size_t>(degree + 1), 0.0);
  if (absl::Status status = ValidateBezierCurve(
          {.control_points = {1, dummy}, .weights = weights});
      !status.ok()) {
    return status;
  }
  return MakePrepared(degree + 1, [degree, weights](
                                      absl::Span<const double> parameters,
                                      CurveOutput output,
                                      const ExecutionContext& context) {
    return EvaluateBernsteinBasis(degree, weights, parameters, output, context);
  });
}

absl::StatusOr<PreparedCurve> PrepareBSplineBasis(
    const v1::BSplineBasis& message, const ServiceLimits& limits) {
  if (absl::Status status = CheckSize(0, message.degree(), limits, "degree");
      !status.ok()) {
    return status;
  }
  const int degree = static_cast<int>(message.degree());
  const absl::Span<const double> knots = SpanOf(message.knots());
  const absl::Span<const double> weights = SpanOf(message.weights());
  const int64_t count = static_cast<int64_t>(knots.size()) - degree - 1;
  if (count < 1) {
    return InvalidFieldError(
        "knots", absl::StrCat("a degree-", degree, " basis needs at least ",
                              degree + 2, " knots, got ", knots.size()));
  }
  if (absl::Status status =
          CheckSize(static_cast<size_t>(count), 0, limits, "knots");
      !status.ok()) {
    return status;
  }
  if (absl::Status status = ValidateBSplineBasis(degree, knots, weights);
      !status.ok()) {
    return status;
  }
  const std::vector<double> dummy(static_cast<size_t>(count), 0.0);
  const BSplineCurveView curve{.degree = degree,
                               .control_points = {1, dummy},
                               .knots = knots,
                               .weights = weights};
  const ParameterDomain domain = BSplineDomain(curve);
  return MakePrepared(
      static_cast<int>(count),
      [degree, knots, weights](absl::Span<const double> parameters,
                               CurveOutput output,
                               const ExecutionContext& context) {
        return EvaluateBSplineBasis(degree, knots, weights, parameters, output,
                                    context);
      },
      domain.start, domain.end);
}

absl::StatusOr<PreparedCurve> PrepareLagrangeBasis(
    const v1::LagrangeBasis& message, const ServiceLimits& limits) {
  const absl::Span<const double> nodes = SpanOf(message.nodes());
  if (nodes.empty()) {
    return InvalidFieldError("nodes", "needs at least one node");
  }
  if (absl::Status status =
          CheckSize(nodes.size(), static_cast<int64_t>(nodes.size()) - 1,
                    limits, "nodes");
      !status.ok()) {
    return status;
  }
  const std::vector<double> dummy(nodes.size(), 0.0);
  const LagrangeCurveView curve{.points = {1, dummy}, .nodes = nodes};
  if (absl::Status status = ValidateLagrangeCurve(curve); !status.ok()) {
    return status;
  }
  const auto [start, end] = LagrangeDomain(curve);
  return MakePrepared(
      static_cast<int>(nodes.size()),
      [nodes](absl::Span<const double> parameters, CurveOutput output,
              const ExecutionContext& context) {
        return EvaluateLagrangeBasis(nodes, parameters, output, context);
      },
      start, end);
}

}  // namespace

absl::StatusOr<BezierCurveView> ValidatedBezier(const v1::BezierCurve& message,
                                                const ServiceLimits& limits) {
  if (absl::Status status =
          CheckDimension(message.control_points(), limits, "control_points");
      !status.ok()) {
    return status;
  }
  const BezierCurveView curve = ViewOf(message);
  if (absl::Status status = ValidateBezierCurve(curve); !status.ok()) {
    return status;
  }
  if (absl::Status status = CheckSize(curve.control_points.size(),
                                      curve.degree(), limits, "control_points");
      !status.ok()) {
    return status;
  }
  return curve;
}

absl::StatusOr<BSplineCurveView> ValidatedBSpline(
    const v1::BSplineCurve& message, const ServiceLimits& limits) {
  if (absl::Status status = CheckSize(0, message.degree(), limits, "degree");
      !status.ok()) {
    return status;
  }
  if (absl::Status status =
          CheckDimension(message.control_points(), limits, "control_points");
      !status.ok()) {
    return status;
  }
  const BSplineCurveView curve{
      .degree = static_cast<int>(message.degree()),
      .control_points = ViewOf(message.control_points()),
      .knots = SpanOf(message.knots()),
      .weights = SpanOf(message.weights())};
  if (absl::Status status =
          CheckSize(curve.control_points.size(), 0, limits, "control_points");
      !status.ok()) {
    return status;
  }
  if (absl::Status status = ValidateBSplineCurve(curve); !status.ok()) {
    return status;
  }
  return curve;
}

absl::StatusOr<PreparedCurve> PrepareCurve(const v1::Curve& curve,
                                           v1::BezierAlgorithm algorithm,
                                           const ServiceLimits& limits) {
  switch (curve.kind_case()) {
    case v1::Curve::kBezier:
      return WithPrefix(
          PrepareBezier(curve.bezier(), ToCore(algorithm), limits),
          "curve.bezier");
    case v1::Curve::kBspline:
      return WithPrefix(PrepareBSpline(curve.bspline(), limits),
                        "curve.bspline");
    case v1::Curve::kLagrange:
      return WithPrefix(PrepareLagrange(curve.lagrange(), limits),
                        "curve.lagrange");
    case v1::Curve::kHermite:
      return WithPrefix(PrepareHermite(curve.hermite(), limits),
                        "curve.hermite");
    case v1::Curve::kPower:
      return WithPrefix(PreparePower(curve.power(), ToCore(algorithm), limits),
                        "curve.power");
    case v1::Curve::KIND_NOT_SET:
      break;
  }
  return InvalidFieldError(
      "curve", "set one curve kind: bezier, bspline, lagrange, hermite, power");
}

absl::StatusOr<PreparedCurve> PrepareBasis(const v1::Basis& basis,
                                           const ServiceLimits& limits,
                                           absl::string_view field) {
  switch (basis.kind_case()) {
    case v1::Basis::kBernstein:
      return WithPrefix(PrepareBernsteinBasis(basis.bernstein(), limits),
                        absl::StrCat(field, ".bernstein"));
    case v1::Basis::kBspline:
      return WithPrefix(PrepareBSplineBasis(basis.bspline(), limits),
                        absl::StrCat(field, ".bspline"));
    case v1::Basis::kLagrange:
      return WithPrefix(PrepareLagrangeBasis(basis.lagrange(), limits),
                        absl::StrCat(field, ".lagrange"));
    case v1::Basis::kHermite: {
      return MakePrepared(
          4, [](absl::Span<const double> parameters, CurveOutput output,
                const ExecutionContext& context) {
            return EvaluateHermiteBasis(parameters, output, context);
          });
    }
    case v1::Basis::KIND_NOT_SET:
      break;
  }
  return InvalidFieldError(
      field, "set one basis kind: bernstein, bspline, lagrange, hermite");
}

}  // namespace freeform::server
