// The least-squares B-spline fit with fixed end points on a given knot
// vector (The NURBS Book A9.7 with any clamped knots; docs/references.md,
// 'Least-squares fitting to a tolerance'), shared by the curve fit and the
// gridded surface fit (fitting.h). Internal to the core.
//
// For data Q_0..Q_m at increasing parameters t_0..t_m and clamped knots on
// [t_0, t_m] with n + 1 functions of degree p, P_0 = Q_0 and P_n = Q_m and
// the interior points minimise sum_k |C(t_k) - Q_k|^2: the normal equations
// (N^T N) P = N^T R over P_1..P_{n-1} are banded (bandwidth p) and symmetric
// positive definite when the Schoenberg-Whitney condition holds. One object
// factors them once and solves for any number of right-hand sides (a curve's
// coordinates, or every column of a grid at once).
#ifndef FREEFORM_CORE_SRC_CONSTRUCT_FIXED_END_LEAST_SQUARES_H_
#define FREEFORM_CORE_SRC_CONSTRUCT_FIXED_END_LEAST_SQUARES_H_

#include <cstddef>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "freeform/core/cancellation.h"
#include "linalg/banded_cholesky.h"

namespace freeform::internal {

class FixedEndLeastSquares {
 public:
  // Create assembles and factors the normal equations of degree p >= 1 on
  // the clamped `knots` (first and last p + 1 knots equal to t.front() and
  // t.back()) for the strictly increasing parameters `t`, at least as many
  // as the control points. A singular system (the data break the
  // Schoenberg-Whitney condition) is INVALID_ARGUMENT on `field`; the token
  // stops it with its status.
  static absl::StatusOr<FixedEndLeastSquares> Create(
      int p, absl::Span<const double> knots, absl::Span<const double> t,
      absl::string_view field, const CancellationToken* cancel);

  size_t control_count() const { return control_count_; }
  size_t data_count() const { return first_.size(); }

  // Solve returns the control_count() x columns control values fitted to
  // the data_count() x columns row-major `data`.
  absl::StatusOr<std::vector<double>> Solve(
      const double* data, size_t columns,
      const CancellationToken* cancel) const;

  // Evaluate writes the fit sum_i N_i(t_k) P_i of the control_count() x
  // columns `control` at every parameter into `values` (data_count() x
  // columns).
  absl::Status Evaluate(const double* control, size_t columns, double* values,
                        const CancellationToken* cancel) const;

 private:
  FixedEndLeastSquares(int p, size_t control_count, size_t data_count);

  int p_;
  size_t control_count_;
  // Per parameter: the first of its p + 1 nonzero functions and their
  // values, kept for Solve and Evaluate.
  std::vector<size_t> first_;
  std::vector<double> basis_;
  // The normal equations of the interior points P_1..P_{n-1}, factored.
  BandedCholesky normal_;
};

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_CONSTRUCT_FIXED_END_LEAST_SQUARES_H_
