// Eigenvalues and eigenvectors of a small symmetric matrix by the cyclic
// Jacobi method (Golub and Van Loan, "Matrix Computations", 3rd ed.,
// section 8.4; docs/references.md, 'Scattered-data surface fitting'), for the
// best-fit plane of scattered points (PlaneParameters in fitting.h). Internal
// to the core.
#ifndef FREEFORM_CORE_SRC_LINALG_SYMMETRIC_EIGEN_H_
#define FREEFORM_CORE_SRC_LINALG_SYMMETRIC_EIGEN_H_

#include <cstddef>
#include <vector>

namespace freeform::internal {

struct SymmetricEigenSystem {
  // The eigenvalues, largest first.
  std::vector<double> values;
  // Orthonormal eigenvectors as rows, in the order of `values`: component
  // c of eigenvector k is vectors[k * n + c].
  std::vector<double> vectors;
};

// SymmetricEigen returns the eigen-decomposition of the symmetric n x n
// row-major matrix `a` (only its upper triangle is read). Cyclic sweeps of
// Jacobi rotations run until the off-diagonal part is below 1e-15 of the
// matrix's norm in the Frobenius sense (at most 64 sweeps; convergence is
// quadratic, a handful of sweeps for n <= 64). Costs O(n^3) per sweep.
SymmetricEigenSystem SymmetricEigen(size_t n, std::vector<double> a);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_LINALG_SYMMETRIC_EIGEN_H_
