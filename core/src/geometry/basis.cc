#include "freeform/core/basis.h"

#include <vector>

#include "absl/strings/str_cat.h"
#include "freeform/core/bezier.h"
#include "freeform/core/hermite.h"
#include "freeform/core/lagrange.h"
#include "freeform/core/points.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "geometry/variant_dispatch.h"
#include "kinds/validated_bspline.h"
#include "kinds/validated_lagrange.h"

namespace freeform {

absl::StatusOr<BernsteinFunctions> BernsteinFunctions::Create(
    int degree, absl::Span<const double> weights) {
  if (degree < 0) {
    return InvalidFieldError(
        "degree", absl::StrCat("must not be negative, got ", degree));
  }
  // The weights follow the rules of a rational Bezier curve's.
  const std::vector<double> points(static_cast<size_t>(degree) + 1, 0.0);
  if (absl::Status status = ValidateBezierCurve(
          {.control_points = {.dimension = 1, .coordinates = points},
           .weights = weights});
      !status.ok()) {
    return status;
  }
  return BernsteinFunctions(degree, weights);
}

absl::Status BernsteinFunctions::Evaluate(
    absl::Span<const double> parameters, CurveOutput output,
    const ExecutionContext& context) const {
  return EvaluateBernsteinBasis(degree_, weights_, parameters, output, context);
}

absl::StatusOr<BSplineFunctions> BSplineFunctions::Create(
    int degree, absl::Span<const double> knots,
    absl::Span<const double> weights) {
  if (degree >= 0 && knots.size() < static_cast<size_t>(degree) + 2) {
    return InvalidFieldError(
        "knots", absl::StrCat("a degree-", degree, " basis needs at least ",
                              static_cast<size_t>(degree) + 2, " knots, got ",
                              knots.size()));
  }
  RETURN_IF_ERROR(ValidateBSplineBasis(degree, knots, weights));
  return BSplineFunctions(degree, knots, weights);
}

ParameterDomain BSplineFunctions::domain() const {
  return {.start = knots_[static_cast<size_t>(degree_)],
          .end = knots_[static_cast<size_t>(function_count())]};
}

absl::Status BSplineFunctions::Evaluate(absl::Span<const double> parameters,
                                        CurveOutput output,
                                        const ExecutionContext& context) const {
  return internal::EvaluateValidBSplineBasis(degree_, knots_, weights_,
                                             parameters, output, context);
}

absl::StatusOr<LagrangeFunctions> LagrangeFunctions::Create(
    absl::Span<const double> nodes) {
  if (nodes.empty()) {
    return InvalidFieldError("nodes", "needs at least one node");
  }
  const std::vector<double> points(nodes.size(), 0.0);
  if (absl::Status status = ValidateLagrangeCurve(
          {.points = {.dimension = 1, .coordinates = points}, .nodes = nodes});
      !status.ok()) {
    return status;
  }
  return LagrangeFunctions(nodes);
}

absl::Status LagrangeFunctions::Evaluate(
    absl::Span<const double> parameters, CurveOutput output,
    const ExecutionContext& context) const {
  return internal::EvaluateValidLagrangeBasis(nodes_, parameters, output,
                                              context);
}

absl::Status HermiteFunctions::Evaluate(absl::Span<const double> parameters,
                                        CurveOutput output,
                                        const ExecutionContext& context) const {
  return EvaluateHermiteBasis(parameters, output, context);
}

int FunctionCountOf(const CurveBasis& basis) {
  return std::visit([](const auto& kind) { return kind.function_count(); },
                    basis);
}

ParameterDomain DomainOf(const CurveBasis& basis) {
  return internal::DomainOfKind(basis);
}

absl::Status EvaluateBasis(const CurveBasis& basis,
                           absl::Span<const double> parameters,
                           CurveOutput output,
                           const ExecutionContext& context) {
  return internal::EvaluateKind(basis, parameters, output, context);
}

namespace {

// The values of one basis at `parameters`: [r * functions + i].
absl::StatusOr<std::vector<double>> BasisValues(
    const CurveBasis& basis, absl::Span<const double> parameters,
    const ExecutionContext& context) {
  std::vector<double> values(parameters.size() *
                             static_cast<size_t>(FunctionCountOf(basis)));
  const absl::Span<double> output[] = {absl::MakeSpan(values)};
  RETURN_IF_ERROR(EvaluateBasis(basis, parameters, output, context));
  return values;
}

// The u (which = 0) or v (which = 1) coordinate of every (u, v) pair.
std::vector<double> PairCoordinate(absl::Span<const double> uv, size_t which) {
  std::vector<double> values(uv.size() / 2);
  for (size_t r = 0; r < values.size(); ++r) values[r] = uv[2 * r + which];
  return values;
}

}  // namespace

absl::Status EvaluateTensorBasis(const CurveBasis& u, const CurveBasis& v,
                                 const SurfaceSamples& samples,
                                 absl::Span<double> values,
                                 const ExecutionContext& context) {
  const ParameterDomain du = DomainOf(u);
  const ParameterDomain dv = DomainOf(v);
  RETURN_IF_ERROR(
      ValidateSurfaceSamples(samples, du.start, du.end, dv.start, dv.end));
  const size_t fu = static_cast<size_t>(FunctionCountOf(u));
  const size_t fv = static_cast<size_t>(FunctionCountOf(v));
  const size_t count = samples.size();
  if (values.size() != count * fu * fv) {
    return InvalidFieldError("values", "wrong size for the tensor basis");
  }
  const std::vector<double> u_parameters =
      samples.grid ? std::vector<double>(samples.u.begin(), samples.u.end())
                   : PairCoordinate(samples.uv, 0);
  const std::vector<double> v_parameters =
      samples.grid ? std::vector<double>(samples.v.begin(), samples.v.end())
                   : PairCoordinate(samples.uv, 1);
  absl::StatusOr<std::vector<double>> u_values =
      BasisValues(u, u_parameters, context);
  if (!u_values.ok()) return u_values.status();
  absl::StatusOr<std::vector<double>> v_values =
      BasisValues(v, v_parameters, context);
  if (!v_values.ok()) return v_values.status();
  const size_t columns = samples.grid ? samples.v.size() : 1;
  return ParallelFor(count, context, [&](size_t begin, size_t end) {
    for (size_t r = begin; r < end; ++r) {
      const double* row_u =
          u_values->data() + (samples.grid ? r / columns : r) * fu;
      const double* row_v =
          v_values->data() + (samples.grid ? r % columns : r) * fv;
      double* out = values.data() + r * fu * fv;
      for (size_t i = 0; i < fu; ++i) {
        for (size_t j = 0; j < fv; ++j) out[i * fv + j] = row_u[i] * row_v[j];
      }
    }
  });
}

}  // namespace freeform
