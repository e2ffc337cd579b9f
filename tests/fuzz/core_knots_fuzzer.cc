// libFuzzer target of the core's knot vectors: a B-spline or NURBS curve
// (BSplineCurve::Create) and the basis of the same knots and weights
// (BSplineFunctions::Create), from a fuzzed degree, knot vector, control
// points and weights. A refusal must name its field, and a curve the core
// accepts must give a basis it accepts too. Accepted geometry is evaluated
// with derivatives at a few parameters of its domain and at its knots; with
// moderate values (core_fuzz_input.h) the answers must be finite, the basis
// functions must sum to 1 (their derivatives to 0) and the curve must be
// the sum of its control points times the basis functions.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/types/span.h"
#include "core_fuzz_input.h"
#include "freeform/core/basis.h"
#include "freeform/core/curve.h"

namespace freeform::fuzz {
namespace {

// DerivativeScale bounds the size of the terms a k-th derivative of a
// degree-p basis is computed from: (p / h)^k for the shortest non-empty
// knot span h. Rounding errors are relative to it (knot spans of 1e-3
// next to spans of 1 make third derivatives of 1e10 cancel to 7).
double DerivativeScale(int degree, absl::Span<const double> knots, int k) {
  double shortest = 0;
  for (size_t i = 1; i < knots.size(); ++i) {
    const double span = knots[i] - knots[i - 1];
    if (span > 0 && (shortest == 0 || span < shortest)) shortest = span;
  }
  if (shortest == 0 || degree <= 0) return 0;
  return std::pow(degree / shortest, k);
}

// The parameters: a few of the domain and every knot inside it.
std::vector<double> Parameters(CoreFuzzInput& input, ParameterDomain domain,
                               absl::Span<const double> knots) {
  std::vector<double> parameters;
  for (int i = input.Int(1, 4); i > 0; --i) {
    parameters.push_back(input.Parameter(domain.start, domain.end));
  }
  for (const double knot : knots) {
    if (knot >= domain.start && knot <= domain.end) parameters.push_back(knot);
  }
  return parameters;
}

void Run(const uint8_t* data, size_t size) {
  CoreFuzzInput input(data, size);
  const int degree = input.Int(-1, 10);
  const int dimension = input.Int(0, 4);
  const int count = input.Int(0, 16);
  const std::vector<double> points =
      input.Values(input.Count(count * dimension, count * dimension + 3));
  const std::vector<double> knots =
      input.Knots(input.Count(count + degree + 1, 40));
  const std::vector<double> weights = input.Weights(count);
  const int orders = input.Int(1, 4);

  const absl::StatusOr<BSplineFunctions> basis =
      BSplineFunctions::Create(degree, knots, weights);
  const absl::StatusOr<BSplineCurve> curve = BSplineCurve::Create(
      {.degree = degree,
       .control_points = {.dimension = dimension, .coordinates = points},
       .knots = knots,
       .weights = weights});
  if (!curve.ok()) CheckRefusal(curve.status(), "a B-spline curve");
  if (!basis.ok()) {
    CheckRefusal(basis.status(), "a B-spline basis");
    Check(!curve.ok(), absl::StrCat("the curve is accepted, its basis is not: ",
                                    basis.status().ToString()));
    return;
  }

  const CurveBasis functions = *basis;
  const std::vector<double> parameters =
      Parameters(input, DomainOf(functions), knots);
  const size_t n = static_cast<size_t>(FunctionCountOf(functions));
  OutputBuffers basis_values(static_cast<size_t>(orders),
                             parameters.size() * n);
  const absl::Status basis_status =
      EvaluateBasis(functions, parameters, basis_values.spans);
  Check(basis_status.ok(), basis_status.ToString());
  if (!input.wild()) {
    for (int k = 0; k < orders; ++k) {
      CheckFinite(basis_values.storage[k], "basis values");
      CheckSumsTo(basis_values.storage[k], parameters.size(), n,
                  k == 0 ? 1.0 : 0.0,
                  absl::StrCat("the sum of the basis derivatives ", k),
                  DerivativeScale(degree, knots, k));
    }
  }
  if (!curve.ok()) return;

  OutputBuffers curve_values(
      static_cast<size_t>(orders),
      parameters.size() * static_cast<size_t>(dimension));
  const absl::Status curve_status =
      EvaluateCurve(Curve(*curve), parameters, curve_values.spans);
  Check(curve_status.ok(), curve_status.ToString());
  // A weight 0 makes its point a direction: the curve is then not the
  // rational basis times the points.
  const bool directions =
      std::find(weights.begin(), weights.end(), 0.0) != weights.end();
  if (input.wild() || directions) return;
  // The curve's derivatives are the basis derivatives times the points.
  for (int k = 0; k < orders; ++k) {
    CheckFinite(curve_values.storage[k], "curve values");
    CheckBasisTimesPoints(curve_values.storage[k], basis_values.storage[k],
                          points, dimension, parameters.size(), n,
                          absl::StrCat("the curve's derivative ", k),
                          DerivativeScale(degree, knots, k));
  }
}

}  // namespace
}  // namespace freeform::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  freeform::fuzz::Run(data, size);
  return 0;
}
