// The LU factorization without pivoting of a B-spline collocation matrix,
// done row by row while the rows are computed, fused with the forward
// substitution of all right-hand-side columns at once, then the back
// substitution: the solver of global interpolation's open systems
// (open_interpolation.h). Row r holds the p + 1 coefficients of the
// consecutive columns first_r..first_r + p, first_r <= r <= first_r + p (the
// basis functions nonzero at the row's parameter), so L has at most p
// sub-diagonals and U at most p super-diagonals; the factors live in a
// count x (p + 1) array of U's rows only, read once forward and once
// backward. The arithmetic is BandedLu's (banded_lu.h), operation for
// operation: the same pivots, multipliers and order of updates, so the
// solution is the same bit for bit (up to the sign of zero). Internal to the
// core; one object per system, not thread-safe.
#ifndef FREEFORM_CORE_SRC_CONSTRUCT_COLLOCATION_LU_H_
#define FREEFORM_CORE_SRC_CONSTRUCT_COLLOCATION_LU_H_

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>
#include <vector>

#include "base/zeroed_array.h"
#include "kinds/bspline_spans.h"

namespace freeform::internal {

// A count x count collocation system with kDimension (0: `dimension` at run
// time) right-hand-side columns, row-major in `rhs`, which the solver
// overwrites with the solution. kDegree is p, or kAnyDegree.
template <int kDegree, int kDimension>
class CollocationLu {
 public:
  CollocationLu(int count, int p, int dimension, double* rhs)
      : count_(count),
        p_(DegreeOf<kDegree>(p)),
        dimension_(kDimension > 0 ? kDimension : dimension),
        rhs_(rhs),
        upper_(static_cast<size_t>(count) * (static_cast<size_t>(p_) + 1)) {
    if constexpr (kDegree == kAnyDegree) {
      window_.resize(2 * static_cast<size_t>(p_) + 1);
    }
  }
  CollocationLu(const CollocationLu&) = delete;
  CollocationLu& operator=(const CollocationLu&) = delete;

  // AddRow eliminates the next row, r (rows come in order 0..count-1), whose
  // coefficients values[0..p] sit in columns first..first + p (those beyond
  // the last column are dropped), and applies its multipliers to row r of
  // the right-hand side. Returns false when the system is singular: r lies
  // outside [first, first + p], or the pivot vanishes relative to the row's
  // largest coefficient (BandedLu::Factor's test).
  bool AddRow(int first, const double* values) {
    const int r = row_++;
    const int p = DegreeOf<kDegree>(p_);
    if (r < first || r > first + p) return false;
    // window[c - (r - p)] is the entry in column c, c = r - p..r + p.
    double* window = window_.data();
    std::fill(window, window + 2 * p + 1, 0.0);
    double scale = 0.0;
    for (int j = 0; j <= p && first + j < count_; ++j) {
      window[first + j - r + p] = values[j];
      scale = std::max(scale, std::abs(values[j]));
    }
    double* b = Rhs(r);
    for (int k = std::max(first, 0); k < r; ++k) {
      const double* u = Upper(k);
      const double factor = window[k - r + p] * u[0];
      if (factor == 0.0) continue;
      Subtract(factor, Rhs(k), b);
      const int last = std::min(count_ - 1, k + p);
      for (int j = k + 1; j <= last; ++j) {
        window[j - r + p] -= factor * u[j - k];
      }
    }
    if (!(std::abs(window[p]) > 1e-14 * scale)) return false;
    double* u = Upper(r);
    std::copy(window + p, window + 2 * p + 1, u);
    u[0] = 1.0 / window[p];
    return true;
  }

  // BackSubstitute finishes the solution once every row was added.
  void BackSubstitute() { BackSubstituteRows(count_, 0); }

  // BackSubstituteRows solves rows [end, begin) from the last down (the
  // rows above `begin` already solved), so that callers can poll between
  // blocks.
  void BackSubstituteRows(int begin, int end) {
    const int p = DegreeOf<kDegree>(p_);
    for (int i = begin - 1; i >= end; --i) {
      const double* u = Upper(i);
      double* b = Rhs(i);
      const int last = std::min(count_ - 1, i + p);
      for (int j = i + 1; j <= last; ++j) Subtract(u[j - i], Rhs(j), b);
      Scale(u[0], b);
    }
  }

 private:
  double* Rhs(int row) const {
    return rhs_ + static_cast<size_t>(row) * static_cast<size_t>(Dimension());
  }
  double* Upper(int row) {
    return upper_.data() + static_cast<size_t>(row) *
                               (static_cast<size_t>(DegreeOf<kDegree>(p_)) + 1);
  }
  int Dimension() const {
    if constexpr (kDimension > 0) {
      return kDimension;
    } else {
      return dimension_;
    }
  }
  // b -= factor * x, column by column.
  void Subtract(double factor, const double* x, double* b) const {
    const int d = Dimension();
#pragma GCC unroll 4
    for (int c = 0; c < d; ++c) b[c] -= factor * x[c];
  }
  // b *= inverse_pivot.
  void Scale(double inverse_pivot, double* b) const {
    const int d = Dimension();
#pragma GCC unroll 4
    for (int c = 0; c < d; ++c) b[c] *= inverse_pivot;
  }

  const int count_;
  const int p_;
  const int dimension_;
  double* const rhs_;
  int row_ = 0;
  // U(r, r..r + p) at r * (p + 1), written by AddRow, with the reciprocal
  // of the pivot U(r, r) in place of the pivot (BandedLu divides once per
  // pivot too).
  ZeroedDoubles upper_;
  std::conditional_t<kDegree == kAnyDegree, std::vector<double>,
                     std::array<double, 2 * std::max(kDegree, 0) + 1>>
      window_{};
};

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_CONSTRUCT_COLLOCATION_LU_H_
