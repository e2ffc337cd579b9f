#include "freeform/core/curve.h"

#include <cstdint>
#include <utility>
#include <vector>

#include "freeform/core/status_macros.h"
#include "geometry/piece_values.h"
#include "geometry/scaled_evaluation.h"
#include "geometry/variant_dispatch.h"
#include "kinds/validated_bezier.h"
#include "kinds/validated_bspline.h"
#include "kinds/validated_hermite.h"
#include "kinds/validated_lagrange.h"

namespace freeform {

absl::StatusOr<BezierCurve> BezierCurve::Create(const BezierCurveView& view,
                                                BezierAlgorithm algorithm) {
  RETURN_IF_ERROR(ValidateBezierCurve(view));
  return BezierCurve(view, algorithm, nullptr);
}

absl::StatusOr<BezierCurve> BezierCurve::FromPowerForm(
    const PointsView& coefficients, BezierAlgorithm algorithm) {
  RETURN_IF_ERROR(ValidatePoints(coefficients, "coefficients"));
  auto owned =
      std::make_shared<const std::vector<double>>(PowerToBezier(coefficients));
  const BezierCurveView view{
      .control_points = {.dimension = coefficients.dimension,
                         .coordinates = *owned},
      .weights = {}};
  return BezierCurve(view, algorithm, std::move(owned));
}

absl::Status BezierCurve::Evaluate(absl::Span<const double> parameters,
                                   CurveOutput output,
                                   const ExecutionContext& context) const {
  return internal::EvaluateValidBezierCurve(view_, parameters, output, context,
                                            algorithm_);
}

absl::StatusOr<BSplineCurve> BSplineCurve::Create(
    const BSplineCurveView& view) {
  RETURN_IF_ERROR(ValidateBSplineCurve(view));
  return BSplineCurve(view);
}

absl::Status BSplineCurve::Evaluate(absl::Span<const double> parameters,
                                    CurveOutput output,
                                    const ExecutionContext& context) const {
  return internal::EvaluateValidBSplineCurve(view_, parameters, output,
                                             context);
}

LagrangeCurve::LagrangeCurve(const LagrangeCurveView& view) : view_(view) {
  const auto [start, end] = LagrangeDomain(view);
  domain_ = {.start = start, .end = end};
}

absl::StatusOr<LagrangeCurve> LagrangeCurve::Create(
    const LagrangeCurveView& view) {
  RETURN_IF_ERROR(ValidateLagrangeCurve(view));
  return LagrangeCurve(view);
}

absl::Status LagrangeCurve::Evaluate(absl::Span<const double> parameters,
                                     CurveOutput output,
                                     const ExecutionContext& context) const {
  return internal::EvaluateValidLagrangeCurve(view_, parameters, output,
                                              context);
}

HermiteCurve::HermiteCurve(const HermiteCurveView& view) : view_(view) {
  const auto [start, end] = HermiteDomain(view);
  domain_ = {.start = start, .end = end};
}

absl::StatusOr<HermiteCurve> HermiteCurve::Create(
    const HermiteCurveView& view) {
  RETURN_IF_ERROR(ValidateHermiteCurve(view));
  return HermiteCurve(view);
}

absl::Status HermiteCurve::Evaluate(absl::Span<const double> parameters,
                                    CurveOutput output,
                                    const ExecutionContext& context) const {
  return internal::EvaluateValidHermiteCurve(view_, parameters, output,
                                             context);
}

int DimensionOf(const Curve& curve) {
  return std::visit([](const auto& kind) { return kind.dimension(); }, curve);
}

ParameterDomain DomainOf(const Curve& curve) {
  return internal::DomainOfKind(curve);
}

absl::Status EvaluateCurve(const Curve& curve,
                           absl::Span<const double> parameters,
                           CurveOutput output,
                           const ExecutionContext& context) {
  if (internal::NeedsScaledEvaluation(curve)) {
    return internal::EvaluateScaledCurve(curve, parameters, output, context);
  }
  return internal::EvaluateKind(curve, parameters, output, context);
}

namespace {

// The distinct values of the sorted `values` that lie in [start, end].
std::vector<double> DistinctWithin(absl::Span<const double> values,
                                   double start, double end) {
  std::vector<double> distinct;
  for (const double value : values) {
    if (value < start || value > end) continue;
    if (distinct.empty() || distinct.back() != value) distinct.push_back(value);
  }
  return distinct;
}

// A single Bezier piece on [start, end].
BezierDecomposition SinglePiece(BezierCurveData piece, double start,
                                double end) {
  BezierDecomposition single;
  single.segments.push_back(std::move(piece));
  single.breakpoints = {start, end};
  return single;
}

}  // namespace

std::vector<double> CurveBreakpoints(const Curve& curve) {
  const ParameterDomain domain = DomainOf(curve);
  const auto ends = [&domain] {
    return std::vector<double>{domain.start, domain.end};
  };
  return std::visit(
      internal::Overloaded{[&](const BezierCurve&) { return ends(); },
                           [&](const BSplineCurve& bspline) {
                             return DistinctWithin(bspline.view().knots,
                                                   domain.start, domain.end);
                           },
                           [&](const LagrangeCurve&) { return ends(); },
                           [](const HermiteCurve& hermite) {
                             return HermiteNodes(hermite.view());
                           }},
      curve);
}

uint64_t DecomposedCurveValues(const Curve& curve) {
  return std::visit(
      internal::Overloaded{
          [](const BezierCurve& bezier) {
            const BezierCurveView& view = bezier.view();
            return internal::PieceValues(1, view.control_points.size(),
                                         view.control_points.dimension,
                                         view.rational(), 2);
          },
          [](const BSplineCurve& bspline) {
            // At most one piece per span of the domain, n - p + 1.
            const BSplineCurveView& view = bspline.view();
            const uint64_t spans =
                view.control_points.size() - static_cast<uint64_t>(view.degree);
            return internal::PieceValues(
                spans, static_cast<uint64_t>(view.degree) + 1,
                view.control_points.dimension, view.rational(), spans + 1);
          },
          [](const LagrangeCurve& lagrange) {
            return internal::PieceValues(1, lagrange.view().points.size(),
                                         lagrange.dimension(), false, 2);
          },
          [](const HermiteCurve& hermite) {
            const uint64_t pieces = hermite.view().points.size() - 1;
            return internal::PieceValues(pieces, 4, hermite.dimension(), false,
                                         pieces + 1);
          }},
      curve);
}

uint64_t DecomposedCurvePieces(const Curve& curve) {
  return std::visit(
      internal::Overloaded{[](const BezierCurve&) -> uint64_t { return 1; },
                           [](const BSplineCurve& bspline) -> uint64_t {
                             const BSplineCurveView& view = bspline.view();
                             return view.control_points.size() -
                                    static_cast<uint64_t>(view.degree);
                           },
                           [](const LagrangeCurve&) -> uint64_t { return 1; },
                           [](const HermiteCurve& hermite) -> uint64_t {
                             return hermite.view().points.size() - 1;
                           }},
      curve);
}

absl::StatusOr<BezierDecomposition> DecomposeCurve(
    const Curve& curve, const CancellationToken* cancel) {
  return std::visit(
      internal::Overloaded{
          [](const BezierCurve& bezier) -> absl::StatusOr<BezierDecomposition> {
            const BezierCurveView& view = bezier.view();
            return SinglePiece(
                {.dimension = view.control_points.dimension,
                 .coordinates = {view.control_points.coordinates.begin(),
                                 view.control_points.coordinates.end()},
                 .weights = {view.weights.begin(), view.weights.end()}},
                0.0, 1.0);
          },
          [cancel](const BSplineCurve& bspline) {
            return DecomposeBSplineCurve(bspline.view(), cancel);
          },
          [](const LagrangeCurve& lagrange)
              -> absl::StatusOr<BezierDecomposition> {
            const ParameterDomain domain = lagrange.domain();
            absl::StatusOr<std::vector<double>> coordinates =
                LagrangeToBezier(lagrange.view());
            if (!coordinates.ok()) return coordinates.status();
            return SinglePiece({.dimension = lagrange.dimension(),
                                .coordinates = *std::move(coordinates),
                                .weights = {}},
                               domain.start, domain.end);
          },
          [](const HermiteCurve& hermite)
              -> absl::StatusOr<BezierDecomposition> {
            return DecomposeHermiteCurve(hermite.view());
          }},
      curve);
}

}  // namespace freeform
