#include "construct/periodic_interpolation.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "construct/interpolation_parameters.h"
#include "construct/interpolation_result.h"
#include "freeform/core/bspline.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "linalg/banded_lu.h"

namespace freeform::internal {
namespace {

long Mod(long a, long n) { return ((a % n) + n) % n; }

// DenseSolve solves the n x n system a x = b (b: n x columns, replaced by x)
// by Gaussian elimination with partial pivoting; false when singular.
bool DenseSolve(int n, Matrix a, double* b, int columns) {
  const size_t N = static_cast<size_t>(n), d = static_cast<size_t>(columns);
  double scale = 0;
  for (double value : a) scale = std::max(scale, std::abs(value));
  for (size_t k = 0; k < N; ++k) {
    size_t best = k;
    for (size_t i = k + 1; i < N; ++i) {
      if (std::abs(a[i * N + k]) > std::abs(a[best * N + k])) best = i;
    }
    if (!(std::abs(a[best * N + k]) > 1e-14 * scale)) return false;
    if (best != k) {
      for (size_t j = 0; j < N; ++j) std::swap(a[k * N + j], a[best * N + j]);
      for (size_t c = 0; c < d; ++c) std::swap(b[k * d + c], b[best * d + c]);
    }
    for (size_t i = k + 1; i < N; ++i) {
      const double factor = a[i * N + k] / a[k * N + k];
      if (factor == 0.0) continue;
      for (size_t j = k; j < N; ++j) a[i * N + j] -= factor * a[k * N + j];
      for (size_t c = 0; c < d; ++c) b[i * d + c] -= factor * b[k * d + c];
    }
  }
  for (size_t i = N; i-- > 0;) {
    for (size_t j = i + 1; j < N; ++j) {
      for (size_t c = 0; c < d; ++c)
        b[i * d + c] -= a[i * N + j] * b[j * d + c];
    }
    for (size_t c = 0; c < d; ++c) b[i * d + c] /= a[i * N + i];
  }
  return true;
}

// SolveCyclic solves the cyclic system whose row k holds (column, value)
// pairs with columns within p of k (cyclically): a banded LU on the first
// N - p unknowns bordered by a dense p x p Schur complement, or a dense
// solve for small N. `rhs` (N x d) is replaced by the solution.
absl::Status SolveCyclic(int n, int p, const std::vector<int>& columns,
                         const std::vector<double>& values, double* rhs, int d,
                         const CancellationToken* cancel) {
  const size_t w = static_cast<size_t>(p) + 1;
  if (n <= 3 * p + 2) {
    Matrix dense(static_cast<size_t>(n) * static_cast<size_t>(n), 0.0);
    for (size_t e = 0; e < columns.size(); ++e) {
      dense[(e / w) * static_cast<size_t>(n) +
            static_cast<size_t>(columns[e])] += values[e];
    }
    return DenseSolve(n, std::move(dense), rhs, d) ? absl::OkStatus()
                                                   : SingularSystemError();
  }
  const int m = n - p;  // interior unknowns
  const size_t r = static_cast<size_t>(p), mm = static_cast<size_t>(m);
  BandedLu a11(m, p, p, cancel);
  Matrix a12(mm * r, 0.0), a21(r * mm, 0.0), a22(r * r, 0.0);
  for (size_t e = 0; e < columns.size(); ++e) {
    const int row = static_cast<int>(e / w), column = columns[e];
    long offset = Mod(column - row, n);
    if (offset > n / 2) offset -= n;
    if (std::abs(offset) > p) return SingularSystemError();
    if (row < m && column < m) {
      a11.at(row, column) += values[e];
    } else if (row < m) {
      a12[static_cast<size_t>(row) * r + static_cast<size_t>(column - m)] +=
          values[e];
    } else if (column < m) {
      a21[static_cast<size_t>(row - m) * mm + static_cast<size_t>(column)] +=
          values[e];
    } else {
      a22[static_cast<size_t>(row - m) * r + static_cast<size_t>(column - m)] +=
          values[e];
    }
  }
  RETURN_IF_ERROR(a11.Factor());
  // Y = A11^-1 A12, z = A11^-1 b1.
  RETURN_IF_ERROR(a11.Solve(a12.data(), p));
  RETURN_IF_ERROR(a11.Solve(rhs, d));
  const size_t dd = static_cast<size_t>(d);
  double* b2 = rhs + mm * dd;
  for (size_t i = 0; i < r; ++i) {
    for (size_t k = 0; k < mm; ++k) {
      const double a = a21[i * mm + k];
      if (a == 0.0) continue;
      for (size_t j = 0; j < r; ++j) a22[i * r + j] -= a * a12[k * r + j];
      for (size_t c = 0; c < dd; ++c) b2[i * dd + c] -= a * rhs[k * dd + c];
    }
  }
  if (!DenseSolve(p, std::move(a22), b2, d)) return SingularSystemError();
  for (size_t k = 0; k < mm; ++k) {
    for (size_t j = 0; j < r; ++j) {
      const double y = a12[k * r + j];
      for (size_t c = 0; c < dd; ++c) rhs[k * dd + c] -= y * b2[j * dd + c];
    }
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<CurveInterpolation> InterpolatePeriodic(
    const PointsView& points, int p, absl::Span<const double> t,
    const PeriodicKnots& kappa, int shift, const CancellationToken* cancel) {
  const long n = static_cast<long>(points.size());
  long start = 0;
  while (kappa(start) > t[0]) --start;
  while (kappa(start + 1) <= t[0]) ++start;
  const long o = start - p;
  std::vector<double> knots(static_cast<size_t>(n + 2 * p + 1));
  for (size_t i = 0; i < knots.size(); ++i) {
    knots[i] = kappa(static_cast<long>(i) + o);
  }
  const double domain_end = knots[static_cast<size_t>(n + p)];
  std::vector<double> sites(t.begin(), t.end());
  for (double& site : sites) {
    if (site > domain_end) site -= kappa.period;
  }
  const size_t w = static_cast<size_t>(p) + 1;
  std::vector<int> columns(static_cast<size_t>(n) * w);
  std::vector<double> values(columns.size());
  std::vector<double> scratch(BasisScratchSize(p));
  const long c = o + shift;
  for (size_t k = 0; k < sites.size(); ++k) {
    const int span = FindSpan(static_cast<int>(n) + p - 1, p, sites[k], knots);
    BasisFunctions(span, sites[k], p, knots,
                   absl::MakeSpan(values).subspan(k * w, w),
                   absl::MakeSpan(scratch));
    for (size_t j = 0; j < w; ++j) {
      columns[k * w + j] =
          static_cast<int>(Mod(span - p + static_cast<long>(j) + c, n));
    }
  }
  Matrix solution(points.coordinates.begin(), points.coordinates.end());
  RETURN_IF_ERROR(SolveCyclic(static_cast<int>(n), p, columns, values,
                              solution.data(), points.dimension, cancel));
  const size_t d = static_cast<size_t>(points.dimension);
  Matrix control(static_cast<size_t>(n + p) * d);
  for (long i = 0; i < n + p; ++i) {
    const size_t source = static_cast<size_t>(Mod(i + c, n)) * d;
    std::copy_n(solution.begin() + static_cast<ptrdiff_t>(source), d,
                control.begin() +
                    static_cast<ptrdiff_t>(i) * static_cast<ptrdiff_t>(d));
  }
  return FinishInterpolation(
      MakeCurve(p, points.dimension, std::move(control), std::move(knots)),
      std::move(sites), points, cancel);
}

absl::StatusOr<CurveInterpolation> InterpolateClosed(
    const PointsView& points, const CurveInterpolationOptions& options) {
  if (!options.start_derivative.empty() || !options.end_derivative.empty()) {
    return InvalidFieldError(options.start_derivative.empty()
                                 ? "end_derivative"
                                 : "start_derivative",
                             "end derivatives need an open curve");
  }
  absl::StatusOr<std::vector<double>> t = ClosedParameters(points, options);
  if (!t.ok()) return t.status();
  const int p = options.degree;
  const size_t n = points.size();
  PeriodicKnots kappa{.base = std::vector<double>(n),
                      .period = t->back() - t->front()};
  const bool uniform =
      options.knot_rule == KnotRule::kUniform ||
      (options.parameters.empty() &&
       options.parameterization == Parameterization::kUniversal);
  for (size_t j = 0; j < n; ++j) {
    if (uniform) {  // the averages of uniform parameters
      kappa.base[j] = t->front() + (static_cast<double>(j) + 0.5 * (p - 1)) *
                                       kappa.period / static_cast<double>(n);
    } else {  // eq. 9.8 on the periodically extended parameters
      double sum = 0;
      for (size_t i = j; i < j + static_cast<size_t>(p); ++i) {
        sum += (*t)[i % n] + static_cast<double>(i / n) * kappa.period;
      }
      kappa.base[j] = sum / p;
    }
  }
  t->pop_back();
  return InterpolatePeriodic(points, p, *t, kappa, p, options.cancel);
}

}  // namespace freeform::internal
