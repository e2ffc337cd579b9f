#include "construct/fixed_end_least_squares.h"

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "freeform/core/bspline.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"

namespace freeform::internal {

FixedEndLeastSquares::FixedEndLeastSquares(int p, size_t control_count,
                                           size_t data_count)
    : p_(p),
      control_count_(control_count),
      first_(data_count),
      basis_(data_count * (static_cast<size_t>(p) + 1)),
      normal_(control_count - 2, static_cast<size_t>(p)) {}

absl::StatusOr<FixedEndLeastSquares> FixedEndLeastSquares::Create(
    int p, absl::Span<const double> knots, absl::Span<const double> t,
    absl::string_view field, const CancellationToken* cancel) {
  const size_t w = static_cast<size_t>(p) + 1;
  const size_t count = knots.size() - w;
  FixedEndLeastSquares fit(p, count, t.size());
  const int n = static_cast<int>(count) - 1;
  std::vector<double> scratch(BasisScratchSize(p));
  CancellationPoll poll(cancel);
  int span = p;
  for (size_t k = 0; k < t.size(); ++k) {
    RETURN_IF_ERROR(poll.Done(w * w));
    span = FindSpanFrom(span, n, p, t[k], knots);
    const size_t first = static_cast<size_t>(span - p);
    double* basis = fit.basis_.data() + k * w;
    BasisFunctions(span, t[k], p, knots, absl::MakeSpan(basis, w),
                   absl::MakeSpan(scratch));
    fit.first_[k] = first;
    if (k == 0 || k + 1 == t.size()) continue;  // the interpolated ends
    // Unknown P_i is row i - 1; P_0 and P_n are not unknowns.
    for (size_t a = 0; a < w; ++a) {
      const size_t i = first + a;
      if (i == 0 || i >= count - 1) continue;
      for (size_t b = 0; b <= a; ++b) {
        const size_t j = first + b;
        if (j == 0) continue;
        fit.normal_.lower(i - 1, j - 1) += basis[a] * basis[b];
      }
    }
  }
  if (absl::Status status = fit.normal_.Factor(cancel); !status.ok()) {
    if (!absl::IsFailedPrecondition(status)) return status;
    return InvalidFieldError(
        field, absl::StrCat(
                   "the least-squares system is singular (detected at control "
                   "point ",
                   fit.normal_.failed_row() + 1,
                   "): the parameters and knots break the "
                   "Schoenberg-Whitney condition"));
  }
  return fit;
}

absl::StatusOr<std::vector<double>> FixedEndLeastSquares::Solve(
    const double* data, size_t columns, const CancellationToken* cancel) const {
  const size_t w = static_cast<size_t>(p_) + 1;
  const size_t m = first_.size() - 1;
  const size_t n = control_count_ - 1;
  std::vector<double> control(control_count_ * columns, 0.0);
  const double* start = data;
  const double* end = data + m * columns;
  std::copy_n(start, columns, control.begin());
  std::copy_n(end, columns, control.begin() + n * columns);
  // Right-hand side N^T R with R_k = Q_k - N_0(t_k) Q_0 - N_n(t_k) Q_m
  // (eq. 9.63), accumulated straight into the rows of P_1..P_{n-1}.
  double* rhs = control.data() + columns;
  std::vector<double> residual(columns);
  CancellationPoll poll(cancel);
  for (size_t k = 1; k < m; ++k) {
    RETURN_IF_ERROR(poll.Done(2 * w * columns));
    const double* basis = basis_.data() + k * w;
    const size_t first = first_[k];
    std::copy_n(data + k * columns, columns, residual.begin());
    if (first == 0) {
      for (size_t c = 0; c < columns; ++c) residual[c] -= basis[0] * start[c];
    }
    if (first + w - 1 == n) {
      for (size_t c = 0; c < columns; ++c) {
        residual[c] -= basis[w - 1] * end[c];
      }
    }
    for (size_t a = 0; a < w; ++a) {
      const size_t i = first + a;
      if (i == 0 || i == n) continue;
      double* row = rhs + (i - 1) * columns;
      for (size_t c = 0; c < columns; ++c) row[c] += basis[a] * residual[c];
    }
  }
  RETURN_IF_ERROR(normal_.Solve(rhs, columns, cancel));
  return control;
}

absl::Status FixedEndLeastSquares::Evaluate(
    const double* control, size_t columns, double* values,
    const CancellationToken* cancel) const {
  const size_t w = static_cast<size_t>(p_) + 1;
  CancellationPoll poll(cancel);
  for (size_t k = 0; k < first_.size(); ++k) {
    RETURN_IF_ERROR(poll.Done(w * columns));
    double* value = values + k * columns;
    std::fill_n(value, columns, 0.0);
    const double* basis = basis_.data() + k * w;
    for (size_t a = 0; a < w; ++a) {
      const double* point = control + (first_[k] + a) * columns;
      for (size_t c = 0; c < columns; ++c) value[c] += basis[a] * point[c];
    }
  }
  return absl::OkStatus();
}

}  // namespace freeform::internal
