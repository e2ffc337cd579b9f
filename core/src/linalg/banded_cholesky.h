// A symmetric positive definite band matrix and its Cholesky factorization
// L L^T, for the normal equations of least-squares fitting (fitting.h).
// Internal to the core.
//
// Only the lower band is stored, row by row: row i keeps the columns
// max(0, i - bandwidth)..i, so n x n with bandwidth w costs n (w + 1)
// doubles, the factorization about n w^2 / 2 multiply-adds and a solve
// 2 n w per right-hand side (Golub and Van Loan, "Matrix Computations",
// 3rd ed., section 4.3; docs/references.md, 'Least-squares fitting to a
// tolerance'). The factor overwrites the matrix.
#ifndef FREEFORM_CORE_SRC_LINALG_BANDED_CHOLESKY_H_
#define FREEFORM_CORE_SRC_LINALG_BANDED_CHOLESKY_H_

#include <cstddef>

#include "absl/status/status.h"
#include "base/zeroed_array.h"
#include "freeform/core/cancellation.h"

namespace freeform::internal {

class BandedCholesky {
 public:
  // An n x n zero matrix with `bandwidth` sub-diagonals, its pages faulted
  // in as it is filled (zeroed_array.h). The caller checks that
  // n (bandwidth + 1) doubles fit in memory.
  BandedCholesky(size_t n, size_t bandwidth);

  size_t size() const { return n_; }
  size_t bandwidth() const { return bandwidth_; }

  // lower returns entry (i, j) of the lower triangle: j <= i < size() and
  // i - j <= bandwidth().
  double& lower(size_t i, size_t j) {
    return band_[i * width_ + (j + bandwidth_ - i)];
  }

  // Factor replaces the matrix by its Cholesky factor L. Returns OK; the
  // token's status when it stops (polled about every 2^16 multiply-adds);
  // or FAILED_PRECONDITION when a pivot is not above 1e-12 times its
  // diagonal entry (the matrix is singular or not positive definite to
  // working precision), with failed_row() naming the row.
  absl::Status Factor(const CancellationToken* cancel);

  // The row whose pivot failed in the last Factor.
  size_t failed_row() const { return failed_row_; }

  // Solve replaces the size() x columns row-major `rhs` by the solution of
  // L L^T x = rhs (after a successful Factor). Returns OK or the token's
  // status.
  absl::Status Solve(double* rhs, size_t columns,
                     const CancellationToken* cancel) const;

 private:
  size_t n_, bandwidth_, width_;
  ZeroedDoubles band_;
  size_t failed_row_ = 0;
};

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_LINALG_BANDED_CHOLESKY_H_
