#include "linalg/banded_cholesky.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "base/vectors.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/status_macros.h"

namespace freeform::internal {
namespace {

// The smallest pivot^2 / diagonal accepted by Factor.
constexpr double kPivotRatio = 1e-12;

using internal::Dot;

}  // namespace

BandedCholesky::BandedCholesky(size_t n, size_t bandwidth)
    : n_(n),
      bandwidth_(bandwidth),
      width_(bandwidth + 1),
      band_(n * (bandwidth + 1)) {}

absl::Status BandedCholesky::Factor(const CancellationToken* cancel) {
  CancellationPoll poll(cancel);
  for (size_t i = 0; i < n_; ++i) {
    const size_t first = i > bandwidth_ ? i - bandwidth_ : 0;
    RETURN_IF_ERROR(poll.Done((i - first + 1) * (i - first + 1)));
    double* row = band_.data() + i * width_ + (first + bandwidth_ - i);
    // row[j - first] is entry (i, j); L_ij = (A_ij - sum_{k<j} L_ik L_jk) /
    // L_jj over the columns k >= first that both rows hold.
    for (size_t j = first; j < i; ++j) {
      const double* other =
          band_.data() + j * width_ + (first + bandwidth_ - j);
      row[j - first] =
          (row[j - first] - Dot(row, other, j - first)) / other[j - first];
    }
    const double diagonal = row[i - first];
    const double pivot = diagonal - Dot(row, row, i - first);
    if (!(pivot > kPivotRatio * diagonal) || !(diagonal > 0)) {
      failed_row_ = i;
      return absl::FailedPreconditionError(
          absl::StrCat("the matrix is not positive definite at row ", i));
    }
    row[i - first] = std::sqrt(pivot);
  }
  return absl::OkStatus();
}

absl::Status BandedCholesky::Solve(double* rhs, size_t columns,
                                   const CancellationToken* cancel) const {
  CancellationPoll poll(cancel);
  const size_t row_work = width_ * columns;
  // L y = b, row by row.
  for (size_t i = 0; i < n_; ++i) {
    RETURN_IF_ERROR(poll.Done(row_work));
    const size_t first = i > bandwidth_ ? i - bandwidth_ : 0;
    const double* row = band_.data() + i * width_ + (first + bandwidth_ - i);
    double* target = rhs + i * columns;
    for (size_t j = first; j < i; ++j) {
      const double factor = row[j - first];
      const double* source = rhs + j * columns;
      for (size_t c = 0; c < columns; ++c) target[c] -= factor * source[c];
    }
    for (size_t c = 0; c < columns; ++c) target[c] /= row[i - first];
  }
  // L^T x = y from the last row up: once x_i is known, subtract its
  // multiples L_ij x_i from the rows j < i it couples to.
  for (size_t i = n_; i-- > 0;) {
    RETURN_IF_ERROR(poll.Done(row_work));
    const size_t first = i > bandwidth_ ? i - bandwidth_ : 0;
    const double* row = band_.data() + i * width_ + (first + bandwidth_ - i);
    double* source = rhs + i * columns;
    for (size_t c = 0; c < columns; ++c) source[c] /= row[i - first];
    for (size_t j = first; j < i; ++j) {
      const double factor = row[j - first];
      double* target = rhs + j * columns;
      for (size_t c = 0; c < columns; ++c) target[c] -= factor * source[c];
    }
  }
  return absl::OkStatus();
}

}  // namespace freeform::internal
