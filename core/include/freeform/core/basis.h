// CurveBasis: a validated set of blending functions (Bernstein, B-spline,
// Lagrange or cubic Hermite), evaluated like a curve whose coordinates are
// the function values; and the tensor product of two of them.
//
// Each kind is made by a Create function that validates it once, like the
// curve kinds of curve.h; `CurveBasis` is the std::variant over the kinds.
// Output layout (the EvaluateBasis RPC): output[k][r * function_count + i]
// is the k-th derivative of function i at parameter r.
//
// Thread-safe: evaluation is const.
#ifndef FREEFORM_CORE_BASIS_H_
#define FREEFORM_CORE_BASIS_H_

#include <variant>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/bspline.h"
#include "freeform/core/curve_output.h"
#include "freeform/core/surface_output.h"
#include "freeform/core/thread_pool.h"

namespace freeform {

// The n + 1 Bernstein polynomials of degree n on [0, 1], rational with
// weights (R_i = w_i B_i / sum_j w_j B_j).
class BernsteinFunctions {
 public:
  // Create checks 0 <= degree ("degree") and the weights as
  // ValidateBezierCurve does ("weights", "weights[i]").
  static absl::StatusOr<BernsteinFunctions> Create(
      int degree, absl::Span<const double> weights);

  int function_count() const { return degree_ + 1; }
  ParameterDomain domain() const { return {.start = 0.0, .end = 1.0}; }
  absl::Status Evaluate(absl::Span<const double> parameters, CurveOutput output,
                        const ExecutionContext& context = {}) const;

 private:
  BernsteinFunctions(int degree, absl::Span<const double> weights)
      : degree_(degree), weights_(weights) {}

  int degree_;
  absl::Span<const double> weights_;
};

// The B-splines N_{i,p} of a knot vector (NURBS basis with weights).
class BSplineFunctions {
 public:
  // Create checks at least degree + 2 knots ("knots"), then
  // ValidateBSplineBasis.
  static absl::StatusOr<BSplineFunctions> Create(
      int degree, absl::Span<const double> knots,
      absl::Span<const double> weights);

  int function_count() const {
    return static_cast<int>(knots_.size()) - degree_ - 1;
  }
  ParameterDomain domain() const;
  absl::Status Evaluate(absl::Span<const double> parameters, CurveOutput output,
                        const ExecutionContext& context = {}) const;

 private:
  BSplineFunctions(int degree, absl::Span<const double> knots,
                   absl::Span<const double> weights)
      : degree_(degree), knots_(knots), weights_(weights) {}

  int degree_;
  absl::Span<const double> knots_;
  absl::Span<const double> weights_;
};

// The Lagrange polynomials of strictly increasing nodes.
class LagrangeFunctions {
 public:
  // Create checks at least one node ("nodes"), finite and strictly
  // increasing ("nodes[i]").
  static absl::StatusOr<LagrangeFunctions> Create(
      absl::Span<const double> nodes);

  int function_count() const { return static_cast<int>(nodes_.size()); }
  ParameterDomain domain() const {
    return {.start = nodes_.front(), .end = nodes_.back()};
  }
  absl::Status Evaluate(absl::Span<const double> parameters, CurveOutput output,
                        const ExecutionContext& context = {}) const;

 private:
  explicit LagrangeFunctions(absl::Span<const double> nodes) : nodes_(nodes) {}

  absl::Span<const double> nodes_;
};

// The four cubic Hermite functions H0..H3 on [0, 1] (hermite.h).
class HermiteFunctions {
 public:
  int function_count() const { return 4; }
  ParameterDomain domain() const { return {.start = 0.0, .end = 1.0}; }
  absl::Status Evaluate(absl::Span<const double> parameters, CurveOutput output,
                        const ExecutionContext& context = {}) const;
};

// Every kind of blending functions.
using CurveBasis = std::variant<BernsteinFunctions, BSplineFunctions,
                                LagrangeFunctions, HermiteFunctions>;

// FunctionCountOf returns the number of functions of the basis.
int FunctionCountOf(const CurveBasis& basis);

// DomainOf returns the parameter domain of the basis.
ParameterDomain DomainOf(const CurveBasis& basis);

// EvaluateBasis writes derivatives 0..output.size()-1 of every function at
// every parameter. Fails like EvaluateCurve (curve.h).
absl::Status EvaluateBasis(const CurveBasis& basis,
                           absl::Span<const double> parameters,
                           CurveOutput output,
                           const ExecutionContext& context = {});

// EvaluateTensorBasis writes the tensor-product functions U_i(u) V_j(v) at
// every sample: function (i, j) at sample r goes to
// values[r * (fu * fv) + i * fv + j], fu and fv the function counts, the
// order of a control net. Samples must lie in DomainOf(u) x DomainOf(v)
// ("uv[i]", "u[i]", "v[i]"); `values` holds samples.size() * fu * fv
// doubles ("values").
absl::Status EvaluateTensorBasis(const CurveBasis& u, const CurveBasis& v,
                                 const SurfaceSamples& samples,
                                 absl::Span<double> values,
                                 const ExecutionContext& context = {});

}  // namespace freeform

#endif  // FREEFORM_CORE_BASIS_H_
