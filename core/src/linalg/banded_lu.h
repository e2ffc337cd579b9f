// A square band matrix factored in place as LU without pivoting, the solver
// of global interpolation's collocation systems and of least-squares
// approximation's normal equations (interpolation.h), and the error those
// report when a system is singular. Internal to the core.
#ifndef FREEFORM_CORE_SRC_LINALG_BANDED_LU_H_
#define FREEFORM_CORE_SRC_LINALG_BANDED_LU_H_

#include <cstddef>
#include <vector>

#include "absl/status/status.h"
#include "base/zeroed_array.h"
#include "freeform/core/cancellation.h"

namespace freeform::internal {

using Matrix = std::vector<double>;  // Row-major, rows x columns.

// SingularSystemError is INVALID_ARGUMENT on "parameters": the interpolation
// system is singular, the parameters and knots break the Schoenberg-Whitney
// condition.
absl::Status SingularSystemError();

// A square band matrix with kl sub- and ku super-diagonals, factored in
// place as LU without pivoting (safe for the totally nonnegative collocation
// matrices of increasing parameters and for symmetric positive definite
// normal equations; docs/references.md, 'Global B-spline interpolation').
class BandedLu {
 public:
  // An n x n zero matrix, its pages faulted in as it is filled
  // (zeroed_array.h); `cancel` (may be null) is polled while factoring and
  // solving.
  BandedLu(int n, int kl, int ku, const CancellationToken* cancel)
      : n_(n),
        kl_(kl),
        ku_(ku),
        width_(kl + ku + 1),
        band_(static_cast<size_t>(n) * static_cast<size_t>(width_)),
        cancel_(cancel) {}

  int size() const { return n_; }
  // at returns entry (i, j), which lies in the band: -kl <= j - i <= ku.
  double& at(int i, int j) {
    return band_[static_cast<size_t>(i) * static_cast<size_t>(width_) +
                 static_cast<size_t>(j - i + kl_)];
  }

  // Factor overwrites the matrix with L (unit diagonal) and U; fails with
  // SingularSystemError() when a pivot vanishes relative to its row, or
  // with the token's status.
  absl::Status Factor();

  // Solve replaces the n x columns row-major `rhs` by the solution of the
  // factored system; fails only with the token's status.
  absl::Status Solve(double* rhs, int columns);

 private:
  int n_, kl_, ku_, width_;
  ZeroedDoubles band_;
  const CancellationToken* cancel_;
};

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_LINALG_BANDED_LU_H_
