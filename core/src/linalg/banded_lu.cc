#include "linalg/banded_lu.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"

namespace freeform::internal {

absl::Status SingularSystemError() {
  return InvalidFieldError(
      "parameters",
      "the interpolation system is singular: the parameters and knots break "
      "the Schoenberg-Whitney condition");
}

absl::Status BandedLu::Factor() {
  CancellationPoll poll(cancel_);
  std::vector<double> row_scale(static_cast<size_t>(n_), 0.0);
  for (int i = 0; i < n_; ++i) {
    RETURN_IF_ERROR(poll.Done(static_cast<size_t>(width_)));
    for (int w = 0; w < width_; ++w) {
      row_scale[static_cast<size_t>(i)] =
          std::max(row_scale[static_cast<size_t>(i)],
                   std::abs(band_[static_cast<size_t>(i) * width_ + w]));
    }
  }
  for (int k = 0; k < n_; ++k) {
    RETURN_IF_ERROR(poll.Done(static_cast<size_t>(kl_ + 1) * (ku_ + 1)));
    const double pivot = at(k, k);
    if (!(std::abs(pivot) > 1e-14 * row_scale[static_cast<size_t>(k)])) {
      return SingularSystemError();
    }
    const int last_row = std::min(n_ - 1, k + kl_);
    const int last_column = std::min(n_ - 1, k + ku_);
    // One division per pivot; the multipliers are products with it.
    const double inverse = 1.0 / pivot;
    for (int i = k + 1; i <= last_row; ++i) {
      const double factor = at(i, k) * inverse;
      at(i, k) = factor;
      if (factor == 0.0) continue;
      for (int j = k + 1; j <= last_column; ++j) at(i, j) -= factor * at(k, j);
    }
  }
  return absl::OkStatus();
}

absl::Status BandedLu::Solve(double* rhs, int columns) {
  const size_t d = static_cast<size_t>(columns);
  CancellationPoll poll(cancel_);
  const size_t row_work = static_cast<size_t>(width_) * d;
  for (int i = 0; i < n_; ++i) {
    RETURN_IF_ERROR(poll.Done(row_work));
    double* row = rhs + static_cast<size_t>(i) * d;
    for (int j = std::max(0, i - kl_); j < i; ++j) {
      const double factor = at(i, j);
      const double* source = rhs + static_cast<size_t>(j) * d;
      for (size_t c = 0; c < d; ++c) row[c] -= factor * source[c];
    }
  }
  for (int i = n_ - 1; i >= 0; --i) {
    RETURN_IF_ERROR(poll.Done(row_work));
    double* row = rhs + static_cast<size_t>(i) * d;
    for (int j = i + 1; j <= std::min(n_ - 1, i + ku_); ++j) {
      const double factor = at(i, j);
      const double* source = rhs + static_cast<size_t>(j) * d;
      for (size_t c = 0; c < d; ++c) row[c] -= factor * source[c];
    }
    const double inverse = 1.0 / at(i, i);
    for (size_t c = 0; c < d; ++c) row[c] *= inverse;
  }
  return absl::OkStatus();
}

}  // namespace freeform::internal
