// Curve: a validated curve of any kind the core evaluates, ready to be
// evaluated again and again.
//
// Each kind is a small value class made by a Create function that checks
// every rule of the kind once (the Validate* functions of its header). Its
// Evaluate then checks only the batch (parameters inside the domain, output
// sizes), so a stream can evaluate chunk after chunk without validating the
// curve again. A class holds a view of caller memory (the request's arrays)
// or, for converted forms, memory of its own shared between copies; a view
// must not outlive what it points into.
//
// `Curve` is the std::variant over the kinds. Code that handles every kind
// uses std::visit, so adding a kind is a compile error wherever it is not
// handled yet.
//
// Example:
//   absl::StatusOr<Curve> curve = BSplineCurve::Create(view);
//   if (!curve.ok()) return curve.status();
//   absl::Status status = EvaluateCurve(*curve, parameters, output, context);
//
// Thread-safe: Evaluate is const and may run concurrently.
#ifndef FREEFORM_CORE_CURVE_H_
#define FREEFORM_CORE_CURVE_H_

#include <cstdint>
#include <memory>
#include <variant>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/bezier.h"
#include "freeform/core/bspline.h"
#include "freeform/core/curve_output.h"
#include "freeform/core/hermite.h"
#include "freeform/core/lagrange.h"
#include "freeform/core/points.h"
#include "freeform/core/subdivision.h"
#include "freeform/core/thread_pool.h"

namespace freeform {

// A polynomial or rational Bezier curve on [0, 1]. Power-form curves become
// Bezier curves of the same degree.
class BezierCurve {
 public:
  // Create validates `view` (ValidateBezierCurve).
  static absl::StatusOr<BezierCurve> Create(
      const BezierCurveView& view,
      BezierAlgorithm algorithm = BezierAlgorithm::kAuto);
  // FromPowerForm validates the coefficients a_0..a_n of
  // C(t) = sum_k a_k t^k (ValidatePoints, "coefficients...") and converts
  // them to Bezier form (PowerToBezier).
  static absl::StatusOr<BezierCurve> FromPowerForm(
      const PointsView& coefficients,
      BezierAlgorithm algorithm = BezierAlgorithm::kAuto);

  const BezierCurveView& view() const { return view_; }
  int dimension() const { return view_.control_points.dimension; }
  int degree() const { return view_.degree(); }
  ParameterDomain domain() const { return {.start = 0.0, .end = 1.0}; }
  absl::Status Evaluate(absl::Span<const double> parameters, CurveOutput output,
                        const ExecutionContext& context = {}) const;

 private:
  BezierCurve(const BezierCurveView& view, BezierAlgorithm algorithm,
              std::shared_ptr<const std::vector<double>> owned)
      : view_(view), algorithm_(algorithm), owned_(std::move(owned)) {}

  BezierCurveView view_;
  BezierAlgorithm algorithm_;
  std::shared_ptr<const std::vector<double>> owned_;
};

// A B-spline or NURBS curve on [u_p, u_{n+1}].
class BSplineCurve {
 public:
  // Create validates `view` (ValidateBSplineCurve).
  static absl::StatusOr<BSplineCurve> Create(const BSplineCurveView& view);

  const BSplineCurveView& view() const { return view_; }
  int dimension() const { return view_.control_points.dimension; }
  int degree() const { return view_.degree; }
  ParameterDomain domain() const { return domain_; }
  absl::Status Evaluate(absl::Span<const double> parameters, CurveOutput output,
                        const ExecutionContext& context = {}) const;

 private:
  explicit BSplineCurve(const BSplineCurveView& view)
      : view_(view), domain_(BSplineDomain(view)) {}

  BSplineCurveView view_;
  ParameterDomain domain_;
};

// The polynomial through points at nodes (lagrange.h).
class LagrangeCurve {
 public:
  // Create validates `view` (ValidateLagrangeCurve).
  static absl::StatusOr<LagrangeCurve> Create(const LagrangeCurveView& view);

  const LagrangeCurveView& view() const { return view_; }
  int dimension() const { return view_.points.dimension; }
  int degree() const { return view_.degree(); }
  ParameterDomain domain() const { return domain_; }
  absl::Status Evaluate(absl::Span<const double> parameters, CurveOutput output,
                        const ExecutionContext& context = {}) const;

 private:
  explicit LagrangeCurve(const LagrangeCurveView& view);

  LagrangeCurveView view_;
  ParameterDomain domain_;
};

// A piecewise cubic Hermite curve (hermite.h).
class HermiteCurve {
 public:
  // Create validates `view` (ValidateHermiteCurve).
  static absl::StatusOr<HermiteCurve> Create(const HermiteCurveView& view);

  const HermiteCurveView& view() const { return view_; }
  int dimension() const { return view_.points.dimension; }
  int degree() const { return 3; }
  ParameterDomain domain() const { return domain_; }
  absl::Status Evaluate(absl::Span<const double> parameters, CurveOutput output,
                        const ExecutionContext& context = {}) const;

 private:
  explicit HermiteCurve(const HermiteCurveView& view);

  HermiteCurveView view_;
  ParameterDomain domain_;
};

// Every curve kind the core evaluates.
using Curve =
    std::variant<BezierCurve, BSplineCurve, LagrangeCurve, HermiteCurve>;

// DimensionOf returns the curve's point dimension.
int DimensionOf(const Curve& curve);

// DomainOf returns the curve's parameter domain.
ParameterDomain DomainOf(const Curve& curve);

// EvaluateCurve writes derivatives 0..output.size()-1 at every parameter
// (see curve_output.h). Fails with INVALID_ARGUMENT for parameters outside
// the domain or not finite ("parameters[i]") or wrongly sized output, and
// with the token's CANCELLED / DEADLINE_EXCEEDED.
absl::Status EvaluateCurve(const Curve& curve,
                           absl::Span<const double> parameters,
                           CurveOutput output,
                           const ExecutionContext& context = {});

// CurveBreakpoints returns, in increasing order, the domain's ends and the
// parameters inside it where a derivative of the curve may jump: the
// distinct knot values of a B-spline curve and the nodes of a Hermite
// curve. Between two consecutive breakpoints the curve is one polynomial
// (rational) piece. A Lagrange curve with a single given node gives that
// node twice.
std::vector<double> CurveBreakpoints(const Curve& curve);

// DecomposeCurve returns the curve as (rational when it is) Bezier pieces,
// piece k being the curve on [breakpoints[k], breakpoints[k + 1]]
// reparameterized to [0, 1] (the breakpoints are CurveBreakpoints): a
// Bezier or power-form curve is its own piece, a B-spline curve is
// DecomposeBSplineCurve, a Hermite curve DecomposeHermiteCurve and a
// Lagrange curve LagrangeToBezier. Fails with the token's CANCELLED /
// DEADLINE_EXCEEDED, and with LagrangeToBezier's INVALID_ARGUMENT for a
// Lagrange curve whose Bezier form double precision cannot hold ("nodes",
// "points").
absl::StatusOr<BezierDecomposition> DecomposeCurve(
    const Curve& curve, const CancellationToken* cancel = nullptr);

// DecomposedCurveValues returns an upper bound, known before any work, of
// the doubles DecomposeCurve returns for `curve` (every piece's coordinates
// and weights, and the breakpoints): what a caller must plan for, in its
// answer or as working memory. Saturates at UINT64_MAX.
uint64_t DecomposedCurveValues(const Curve& curve);

// DecomposedCurvePieces returns an upper bound, known before any work, of
// the pieces DecomposeCurve returns: one per span of a B-spline, per node
// interval of a Hermite curve, one for a Bezier or Lagrange curve. Each
// piece costs its records besides its values.
uint64_t DecomposedCurvePieces(const Curve& curve);

}  // namespace freeform

#endif  // FREEFORM_CORE_CURVE_H_
