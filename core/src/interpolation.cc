#include "freeform/core/interpolation.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "freeform/core/bspline.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/lagrange.h"
#include "freeform/core/points.h"
#include "freeform/core/status.h"
#include "freeform/core/surface_output.h"
#include "knot_insertion.h"
#include "point_array.h"

namespace freeform {
namespace {

using Matrix = std::vector<double>;  // Row-major, rows x columns.

absl::Status SingularError() {
  return InvalidFieldError(
      "parameters",
      "the interpolation system is singular: the parameters and knots break "
      "the Schoenberg-Whitney condition");
}

// A square band matrix with kl sub- and ku super-diagonals, factored in
// place as LU without pivoting (safe for the totally nonnegative collocation
// matrices of increasing parameters and for symmetric positive definite
// normal equations; docs/references.md, 'Global B-spline interpolation').
class BandedMatrix {
 public:
  // `cancel` (may be null) is polled while factoring and solving.
  BandedMatrix(int n, int kl, int ku, const CancellationToken* cancel)
      : n_(n),
        kl_(kl),
        ku_(ku),
        width_(kl + ku + 1),
        band_(static_cast<size_t>(n) * static_cast<size_t>(width_), 0.0),
        cancel_(cancel) {}

  int size() const { return n_; }
  bool InBand(int i, int j) const { return j - i >= -kl_ && j - i <= ku_; }
  double& at(int i, int j) {
    return band_[static_cast<size_t>(i) * static_cast<size_t>(width_) +
                 static_cast<size_t>(j - i + kl_)];
  }

  // Factor overwrites the matrix with L (unit diagonal) and U; fails with
  // SingularError() when a pivot vanishes relative to its row.
  absl::Status Factor() {
    CancellationPoll poll(cancel_);
    std::vector<double> row_scale(static_cast<size_t>(n_), 0.0);
    for (int i = 0; i < n_; ++i) {
      if (absl::Status status = poll.Done(static_cast<size_t>(width_));
          !status.ok()) {
        return status;
      }
      for (int w = 0; w < width_; ++w) {
        row_scale[static_cast<size_t>(i)] =
            std::max(row_scale[static_cast<size_t>(i)],
                     std::abs(band_[static_cast<size_t>(i) * width_ + w]));
      }
    }
    for (int k = 0; k < n_; ++k) {
      if (absl::Status status =
              poll.Done(static_cast<size_t>(kl_ + 1) * (ku_ + 1));
          !status.ok()) {
        return status;
      }
      const double pivot = at(k, k);
      if (!(std::abs(pivot) > 1e-14 * row_scale[static_cast<size_t>(k)])) {
        return SingularError();
      }
      const int last_row = std::min(n_ - 1, k + kl_);
      const int last_column = std::min(n_ - 1, k + ku_);
      for (int i = k + 1; i <= last_row; ++i) {
        const double factor = at(i, k) / pivot;
        at(i, k) = factor;
        if (factor == 0.0) continue;
        for (int j = k + 1; j <= last_column; ++j)
          at(i, j) -= factor * at(k, j);
      }
    }
    return absl::OkStatus();
  }

  // Solve replaces the n x columns row-major `rhs` by the solution of the
  // factored system.
  absl::Status Solve(double* rhs, int columns) {
    const size_t d = static_cast<size_t>(columns);
    CancellationPoll poll(cancel_);
    const size_t row_work = static_cast<size_t>(width_) * d;
    for (int i = 0; i < n_; ++i) {
      if (absl::Status status = poll.Done(row_work); !status.ok()) {
        return status;
      }
      double* row = rhs + static_cast<size_t>(i) * d;
      for (int j = std::max(0, i - kl_); j < i; ++j) {
        const double factor = at(i, j);
        const double* source = rhs + static_cast<size_t>(j) * d;
        for (size_t c = 0; c < d; ++c) row[c] -= factor * source[c];
      }
    }
    for (int i = n_ - 1; i >= 0; --i) {
      if (absl::Status status = poll.Done(row_work); !status.ok()) {
        return status;
      }
      double* row = rhs + static_cast<size_t>(i) * d;
      for (int j = i + 1; j <= std::min(n_ - 1, i + ku_); ++j) {
        const double factor = at(i, j);
        const double* source = rhs + static_cast<size_t>(j) * d;
        for (size_t c = 0; c < d; ++c) row[c] -= factor * source[c];
      }
      const double pivot = at(i, i);
      for (size_t c = 0; c < d; ++c) row[c] /= pivot;
    }
    return absl::OkStatus();
  }

 private:
  int n_, kl_, ku_, width_;
  std::vector<double> band_;
  const CancellationToken* cancel_;
};

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

// ---------------------------------------------------------- parameters --

// CumulativeParameters returns chord-length (exponent 1) or centripetal
// (exponent 1/2) parameters of the open sequence (NURBS Book eqs. 9.5-9.6),
// normalized to [0, 1]; with `closed`, one more value for the chord back to
// the first point (the period is then 1).
absl::StatusOr<std::vector<double>> CumulativeParameters(
    const PointsView& points, double exponent, bool closed) {
  const size_t count = points.size();
  const size_t intervals = closed ? count : count - 1;
  std::vector<double> t(intervals + 1, 0.0);
  for (size_t k = 1; k <= intervals; ++k) {
    const double chord = PointDistance(points.point(k % count),
                                       points.point(k - 1), points.dimension);
    if (!(chord > 0)) {
      const size_t repeated = k % count == 0 ? count - 1 : k;
      return InvalidFieldError(
          IndexedField("points.coordinates",
                       repeated * static_cast<size_t>(points.dimension)),
          k % count == 0
              ? "the last point repeats the first; a closed curve must not "
                "repeat it"
              : "a point equals its predecessor (chord length and centripetal "
                "parameters need distinct consecutive points)");
    }
    t[k] = t[k - 1] + (exponent == 1.0 ? chord : std::sqrt(chord));
  }
  const double total = t[intervals];
  for (double& value : t) value /= total;
  t[intervals] = 1.0;
  return t;
}

std::vector<double> UniformValues(size_t intervals) {
  std::vector<double> t(intervals + 1);
  for (size_t k = 0; k <= intervals; ++k) {
    t[k] = static_cast<double>(k) / static_cast<double>(intervals);
  }
  return t;
}

// ClampedUniformKnots returns p + 1 zeros, j / (count - p) for
// j = 1..count-p-1 and p + 1 ones.
std::vector<double> ClampedUniformKnots(int count, int p) {
  std::vector<double> knots(static_cast<size_t>(p) + 1, 0.0);
  for (int j = 1; j < count - p; ++j) {
    knots.push_back(static_cast<double>(j) / (count - p));
  }
  knots.insert(knots.end(), static_cast<size_t>(p) + 1, 1.0);
  return knots;
}

// BasisSlope returns N'_{i,p}(u) and N''_{i,p}(u) (right-hand limits).
std::pair<double, double> BasisSlope(int i, int p, double u,
                                     absl::Span<const double> knots) {
  const int n = static_cast<int>(knots.size()) - p - 2;
  const int span = FindSpan(n, p, u, knots);
  if (i < span - p || i > span) return {0.0, 0.0};
  std::vector<double> ders(3 * (static_cast<size_t>(p) + 1));
  std::vector<double> scratch(BasisDerivativesScratchSize(p));
  BasisFunctionDerivatives(span, u, p, 2, knots, absl::MakeSpan(ders),
                           absl::MakeSpan(scratch));
  const size_t j = static_cast<size_t>(i - span + p);
  return {ders[static_cast<size_t>(p) + 1 + j],
          ders[2 * (static_cast<size_t>(p) + 1) + j]};
}

// BasisArgmax returns the maximum of the unimodal N_{i,p} inside its support
// [lo, hi]: Newton on N' = 0 safeguarded by the bracket (N' > 0 left of the
// maximum, <= 0 right of it), which also converges to the kink of p = 1.
double BasisArgmax(int i, int p, double lo, double hi,
                   absl::Span<const double> knots) {
  double x = 0.5 * (lo + hi);
  for (int iteration = 0; iteration < 200 && hi - lo > 1e-16; ++iteration) {
    const auto [slope, curvature] = BasisSlope(i, p, x, knots);
    if (slope > 0) {
      lo = x;
    } else {
      hi = x;
    }
    if (slope == 0.0 && curvature < 0) break;
    double next = curvature < 0 ? x - slope / curvature : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - x) <= 1e-17) break;
    x = next;
  }
  return x;
}

// UniversalParameters returns the maxima of the `count` basis functions of
// degree p on ClampedUniformKnots(count, p). Functions with an all-uniform
// support are symmetric, their maximum is the support's midpoint; the ends
// mirror each other.
std::vector<double> UniversalParameters(int count, int p) {
  const std::vector<double> knots = ClampedUniformKnots(count, p);
  std::vector<double> t(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) {
    const size_t k = static_cast<size_t>(i);
    const double lo = knots[k], hi = knots[k + static_cast<size_t>(p) + 1];
    if (i == 0) {
      t[k] = 0.0;
    } else if (i == count - 1) {
      t[k] = 1.0;
    } else if ((i >= p && i <= count - 1 - p) || 2 * i == count - 1) {
      t[k] = 0.5 * (lo + hi);
    } else if (2 * i > count - 1) {
      t[k] = 1.0 - t[static_cast<size_t>(count - 1 - i)];
    } else {
      t[k] = BasisArgmax(i, p, lo, hi, knots);
    }
  }
  return t;
}

absl::Status ValidateParameters(absl::Span<const double> parameters) {
  if (absl::Status status = ValidateFinite(parameters, "parameters");
      !status.ok()) {
    return status;
  }
  for (size_t i = 1; i < parameters.size(); ++i) {
    if (!(parameters[i] > parameters[i - 1])) {
      return InvalidFieldError(IndexedField("parameters", i),
                               "parameters must be strictly increasing");
    }
  }
  return absl::OkStatus();
}

// ExplicitParameters returns the caller's parameters: one per point, finite
// and strictly increasing.
absl::StatusOr<std::vector<double>> ExplicitParameters(
    absl::Span<const double> parameters, size_t count) {
  if (parameters.size() != count) {
    return InvalidFieldError(
        "parameters", absl::StrCat("needs one parameter per point (", count,
                                   "), got ", parameters.size()));
  }
  if (absl::Status status = ValidateParameters(parameters); !status.ok()) {
    return status;
  }
  return std::vector<double>(parameters.begin(), parameters.end());
}

absl::Status ValidateDegree(int degree, absl::string_view field) {
  if (degree < 1) {
    return InvalidFieldError(field, absl::StrCat("must be >= 1, got ", degree));
  }
  return absl::OkStatus();
}

// ValidateCurveData checks "degree" (>= 1) and "points" (at least
// degree + 1 of them).
absl::Status ValidateCurveData(const PointsView& points, int degree) {
  if (absl::Status status = ValidateDegree(degree, "degree"); !status.ok()) {
    return status;
  }
  return ValidatePoints(points, "points", static_cast<size_t>(degree) + 1);
}

// OpenParameters computes parameters of an open sequence (no universal).
absl::StatusOr<std::vector<double>> OpenParameters(
    const PointsView& points, Parameterization parameterization) {
  switch (parameterization) {
    case Parameterization::kChordLength:
      return CumulativeParameters(points, 1.0, false);
    case Parameterization::kCentripetal:
      return CumulativeParameters(points, 0.5, false);
    default:
      return UniformValues(points.size() - 1);
  }
}

// ----------------------------------------------------------- knots --

// AveragingKnots returns the clamped knots u_{j+p} = (s_j + ... +
// s_{j+p-1}) / p, j = 1..N-p-1, for N sites s (eq. 9.8).
std::vector<double> AveragingKnots(absl::Span<const double> s, int p) {
  const int count = static_cast<int>(s.size());
  std::vector<double> knots(static_cast<size_t>(p) + 1, s.front());
  for (int j = 1; j < count - p; ++j) {
    double sum = 0;
    for (int i = j; i < j + p; ++i) sum += s[static_cast<size_t>(i)];
    knots.push_back(sum / p);
  }
  knots.insert(knots.end(), static_cast<size_t>(p) + 1, s.back());
  return knots;
}

// UniformKnots returns clamped knots with equally spaced interior knots on
// [start, end] for `count` functions of degree p.
std::vector<double> UniformKnots(double start, double end, int count, int p) {
  std::vector<double> knots = ClampedUniformKnots(count, p);
  for (double& knot : knots) knot = start + knot * (end - start);
  knots.front() = start;
  knots.back() = end;
  return knots;
}

// ------------------------------------------------------ open systems --

// A derivative condition C^(order)(t) = value at one end (order 0: none;
// empty value: zero).
struct EndCondition {
  int order = 0;
  absl::Span<const double> value;
};

// A row of the collocation system: coefficients of p + 1 consecutive
// control points starting at `first`.
struct OpenRows {
  std::vector<int> first;
  std::vector<double> values;  // (p + 1) per row
};

// BuildOpenRows fills the rows of A9.1 / A9.2: the value at t_0, the start
// condition, values at t_1..t_{n-1}, the end condition, the value at t_n.
absl::StatusOr<OpenRows> BuildOpenRows(int p, absl::Span<const double> knots,
                                       absl::Span<const double> t,
                                       EndCondition start, EndCondition end,
                                       const CancellationToken* cancel) {
  CancellationPoll poll(cancel);
  const size_t w = static_cast<size_t>(p) + 1;
  const int n = static_cast<int>(knots.size()) - p - 2;
  OpenRows rows;
  const size_t count = t.size() + (start.order > 0) + (end.order > 0);
  rows.first.reserve(count);
  rows.values.reserve(count * w);
  std::vector<double> scratch(BasisDerivativesScratchSize(p));
  std::vector<double> ders(3 * w);
  auto derivative_row = [&](double u, int order) {
    const int span = FindSpan(n, p, u, knots);
    BasisFunctionDerivatives(span, u, p, order, knots, absl::MakeSpan(ders),
                             absl::MakeSpan(scratch));
    rows.first.push_back(span - p);
    rows.values.insert(rows.values.end(),
                       ders.begin() + static_cast<ptrdiff_t>(order * w),
                       ders.begin() + static_cast<ptrdiff_t>((order + 1) * w));
  };
  int span = p;
  for (size_t k = 0; k < t.size(); ++k) {
    if (absl::Status status = poll.Done(w * w); !status.ok()) return status;
    if (k + 1 == t.size() && end.order > 0) derivative_row(t[k], end.order);
    span = FindSpanFrom(span, n, p, t[k], knots);
    const size_t offset = rows.values.size();
    rows.values.resize(offset + w);
    BasisFunctions(span, t[k], p, knots,
                   absl::MakeSpan(rows.values).subspan(offset, w),
                   absl::MakeSpan(scratch));
    rows.first.push_back(span - p);
    if (k == 0 && start.order > 0) derivative_row(t[k], start.order);
  }
  return rows;
}

// FactorOpenSystem builds and factors the banded system of the rows; fails
// when the Schoenberg-Whitney condition breaks (a zero diagonal value).
absl::StatusOr<BandedMatrix> FactorOpenSystem(
    int p, const absl::StatusOr<OpenRows>& built,
    const CancellationToken* cancel) {
  if (!built.ok()) return built.status();
  const OpenRows& rows = *built;
  const int count = static_cast<int>(rows.first.size());
  int kl = 0, ku = 0;
  for (int r = 0; r < count; ++r) {
    const int first = rows.first[static_cast<size_t>(r)];
    if (r < first || r > first + p) return SingularError();
    kl = std::max(kl, r - first);
    ku = std::max(ku, first + p - r);
  }
  BandedMatrix matrix(count, kl, ku, cancel);
  CancellationPoll poll(cancel);
  for (int r = 0; r < count; ++r) {
    if (absl::Status status = poll.Done(static_cast<size_t>(p) + 1);
        !status.ok()) {
      return status;
    }
    const int first = rows.first[static_cast<size_t>(r)];
    for (int j = 0; j <= p; ++j) {
      const int column = first + j;
      if (column < count) {
        matrix.at(r, column) =
            rows.values[static_cast<size_t>(r) * (static_cast<size_t>(p) + 1) +
                        static_cast<size_t>(j)];
      }
    }
  }
  if (absl::Status status = matrix.Factor(); !status.ok()) return status;
  return matrix;
}

// OpenRightHandSide stacks the points and end conditions in row order.
Matrix OpenRightHandSide(const PointsView& points, EndCondition start,
                         EndCondition end) {
  const size_t d = static_cast<size_t>(points.dimension);
  const size_t count = points.size();
  Matrix rhs;
  rhs.reserve((count + 2) * d);
  auto append_condition = [&](const EndCondition& condition) {
    if (condition.value.empty()) {
      rhs.insert(rhs.end(), d, 0.0);
    } else {
      rhs.insert(rhs.end(), condition.value.begin(), condition.value.end());
    }
  };
  for (size_t k = 0; k < count; ++k) {
    if (k + 1 == count && end.order > 0) append_condition(end);
    rhs.insert(rhs.end(), points.point(k), points.point(k) + d);
    if (k == 0 && start.order > 0) append_condition(start);
  }
  return rhs;
}

// SolveOpen returns the control points of the clamped curve of degree p on
// `knots` through the points at t with the end conditions.
absl::StatusOr<Matrix> SolveOpen(const PointsView& points, int p,
                                 absl::Span<const double> knots,
                                 absl::Span<const double> t, EndCondition start,
                                 EndCondition end,
                                 const CancellationToken* cancel) {
  absl::StatusOr<BandedMatrix> matrix = FactorOpenSystem(
      p, BuildOpenRows(p, knots, t, start, end, cancel), cancel);
  if (!matrix.ok()) return matrix.status();
  Matrix rhs = OpenRightHandSide(points, start, end);
  if (absl::Status status = matrix->Solve(rhs.data(), points.dimension);
      !status.ok()) {
    return status;
  }
  return rhs;
}

// MaxResidual returns max_k |C(t_k) - Q_k| (and the sum of squares).
absl::StatusOr<std::pair<double, double>> Residuals(
    const BSplineCurveData& curve, absl::Span<const double> t,
    const PointsView& points, const CancellationToken* cancel) {
  std::vector<double> values(points.coordinates.size());
  const std::vector<absl::Span<double>> output = {absl::MakeSpan(values)};
  if (absl::Status status = EvaluateBSplineCurve(
          curve.view(), t, output, ExecutionContext{.cancellation = cancel});
      !status.ok()) {
    return status;
  }
  double max = 0, sum = 0;
  for (size_t k = 0; k < points.size(); ++k) {
    const double distance =
        PointDistance(values.data() + k * static_cast<size_t>(points.dimension),
                      points.point(k), points.dimension);
    max = std::max(max, distance);
    sum += distance * distance;
  }
  return std::make_pair(max, sum);
}

absl::StatusOr<CurveInterpolation> Finish(BSplineCurveData curve,
                                          std::vector<double> t,
                                          const PointsView& points,
                                          const CancellationToken* cancel) {
  absl::StatusOr<std::pair<double, double>> residuals =
      Residuals(curve, t, points, cancel);
  if (!residuals.ok()) return residuals.status();
  return CurveInterpolation{.curve = std::move(curve),
                            .parameters = std::move(t),
                            .max_residual = residuals->first};
}

BSplineCurveData MakeCurve(int p, int dimension, Matrix coordinates,
                           std::vector<double> knots) {
  return BSplineCurveData{.degree = p,
                          .dimension = dimension,
                          .coordinates = std::move(coordinates),
                          .knots = std::move(knots),
                          .weights = {}};
}

// -------------------------------------------------- periodic systems --

// A periodic knot sequence kappa_j = base[j mod N] + floor(j / N) period.
struct PeriodicKnots {
  std::vector<double> base;
  double period = 1;

  double operator()(long j) const {
    const long n = static_cast<long>(base.size());
    const long q = j >= 0 ? j / n : -((-j + n - 1) / n);
    return base[static_cast<size_t>(j - q * n)] +
           static_cast<double>(q) * period;
  }
};

long Mod(long a, long n) { return ((a % n) + n) % n; }

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
                                                   : SingularError();
  }
  const int m = n - p;  // interior unknowns
  const size_t r = static_cast<size_t>(p), mm = static_cast<size_t>(m);
  BandedMatrix a11(m, p, p, cancel);
  Matrix a12(mm * r, 0.0), a21(r * mm, 0.0), a22(r * r, 0.0);
  for (size_t e = 0; e < columns.size(); ++e) {
    const int row = static_cast<int>(e / w), column = columns[e];
    long offset = Mod(column - row, n);
    if (offset > n / 2) offset -= n;
    if (std::abs(offset) > p) return SingularError();
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
  if (absl::Status status = a11.Factor(); !status.ok()) return status;
  // Y = A11^-1 A12, z = A11^-1 b1.
  if (absl::Status status = a11.Solve(a12.data(), p); !status.ok()) {
    return status;
  }
  if (absl::Status status = a11.Solve(rhs, d); !status.ok()) return status;
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
  if (!DenseSolve(p, std::move(a22), b2, d)) return SingularError();
  for (size_t k = 0; k < mm; ++k) {
    for (size_t j = 0; j < r; ++j) {
      const double y = a12[k * r + j];
      for (size_t c = 0; c < dd; ++c) rhs[k * dd + c] -= y * b2[j * dd + c];
    }
  }
  return absl::OkStatus();
}

// InterpolatePeriodic returns the periodic B-spline of degree p through the
// N points at the increasing sites t (t_{N-1} < t_0 + period) on the
// periodic knots. The basis function whose support starts at
// kappa_{m - shift} belongs to site m (it contains t_m inside its support),
// which makes the cyclic system banded around the diagonal. The curve's
// knots are u_i = kappa_{i + o} with u_p the last knot <= t_0, so its domain
// [u_p, u_p + period] holds every site (modulo the period).
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
  if (absl::Status status =
          SolveCyclic(static_cast<int>(n), p, columns, values, solution.data(),
                      points.dimension, cancel);
      !status.ok()) {
    return status;
  }
  const size_t d = static_cast<size_t>(points.dimension);
  Matrix control(static_cast<size_t>(n + p) * d);
  for (long i = 0; i < n + p; ++i) {
    const size_t source = static_cast<size_t>(Mod(i + c, n)) * d;
    std::copy_n(solution.begin() + static_cast<ptrdiff_t>(source), d,
                control.begin() +
                    static_cast<ptrdiff_t>(i) * static_cast<ptrdiff_t>(d));
  }
  return Finish(
      MakeCurve(p, points.dimension, std::move(control), std::move(knots)),
      std::move(sites), points, cancel);
}

// ClosedParameters returns N + 1 parameters: one per point and the one where
// the curve returns to the first point.
absl::StatusOr<std::vector<double>> ClosedParameters(
    const PointsView& points, const CurveInterpolationOptions& options) {
  const size_t count = points.size();
  if (!options.parameters.empty()) {
    if (options.parameters.size() != count &&
        options.parameters.size() != count + 1) {
      return InvalidFieldError(
          "parameters",
          absl::StrCat("a closed curve needs one parameter per point (", count,
                       ") or one more, got ", options.parameters.size()));
    }
    if (absl::Status status = ValidateParameters(options.parameters);
        !status.ok()) {
      return status;
    }
    std::vector<double> t(options.parameters.begin(), options.parameters.end());
    if (t.size() == count) {
      t.push_back(t.back() +
                  (t.back() - t.front()) / static_cast<double>(count - 1));
    }
    return t;
  }
  switch (options.parameterization) {
    case Parameterization::kChordLength:
      return CumulativeParameters(points, 1.0, true);
    case Parameterization::kCentripetal:
      return CumulativeParameters(points, 0.5, true);
    default:
      return UniformValues(count);
  }
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

// --------------------------------------------------------- cubic splines --

absl::Status ValidateDerivative(absl::Span<const double> value,
                                absl::string_view field, int dimension,
                                bool required) {
  if (value.empty() && !required) return absl::OkStatus();
  if (!required) {
    return InvalidFieldError(field, "only clamped ends take derivatives");
  }
  if (value.size() != static_cast<size_t>(dimension)) {
    return InvalidFieldError(
        field, absl::StrCat("needs ", dimension,
                            " values (the dimension), got ", value.size()));
  }
  return ValidateFinite(value, field);
}

// ValidateEndDerivatives checks the end derivatives given to InterpolateCurve:
// `dimension` finite values each, and degree >= 2.
absl::Status ValidateEndDerivatives(const CurveInterpolationOptions& options,
                                    int dimension) {
  for (const auto& [value, field] :
       {std::pair{options.start_derivative, "start_derivative"},
        std::pair{options.end_derivative, "end_derivative"}}) {
    if (value.empty()) continue;
    if (absl::Status status = ValidateDerivative(value, field, dimension, true);
        !status.ok()) {
      return status;
    }
    if (options.degree < 2) {
      return InvalidFieldError(field, "end derivatives need degree >= 2");
    }
  }
  return absl::OkStatus();
}

// CubicKnots returns x_0 (x4), x_1, ..., x_{n-1}, x_n (x4), without x_1
// and x_{n-1} when `not_a_knot`.
std::vector<double> CubicKnots(absl::Span<const double> x, bool not_a_knot) {
  std::vector<double> knots(4, x.front());
  for (size_t k = 1; k + 1 < x.size(); ++k) {
    if (not_a_knot && (k == 1 || k + 2 == x.size())) continue;
    knots.push_back(x[k]);
  }
  knots.insert(knots.end(), 4, x.back());
  return knots;
}

// WithKnots returns the non-rational `curve` with the non-decreasing knots
// `x` inserted (knot_insertion.h): the same curve on more knots.
absl::StatusOr<BSplineCurveData> WithKnots(BSplineCurveData curve,
                                           absl::Span<const double> x,
                                           const CancellationToken* cancel) {
  absl::StatusOr<internal::Spline> refined = internal::RefineKnots(
      internal::Spline{
          curve.degree, std::move(curve.knots),
          internal::PointArray{curve.dimension, std::move(curve.coordinates)}},
      x, cancel);
  if (!refined.ok()) return refined.status();
  curve.knots = std::move(refined->knots);
  curve.coordinates = std::move(refined->points.values);
  return curve;
}

// PolynomialEndSlopes returns the end derivatives of the line (2 points) or
// parabola (3 points) through the data, from divided differences.
std::pair<Matrix, Matrix> PolynomialEndSlopes(const PointsView& values,
                                              absl::Span<const double> x) {
  const size_t d = static_cast<size_t>(values.dimension);
  const size_t last = values.size() - 1;
  Matrix start(d), end(d);
  for (size_t c = 0; c < d; ++c) {
    const double f01 =
        (values.point(1)[c] - values.point(0)[c]) / (x[1] - x[0]);
    if (last == 1) {
      start[c] = end[c] = f01;
      continue;
    }
    const double f12 =
        (values.point(2)[c] - values.point(1)[c]) / (x[2] - x[1]);
    const double f012 = (f12 - f01) / (x[2] - x[0]);
    start[c] = f01 + f012 * (x[0] - x[1]);
    end[c] = f12 + f012 * (x[2] - x[1]);
  }
  return {std::move(start), std::move(end)};
}

absl::Status ValidatePeriodicEnds(const PointsView& values) {
  double scale = 1;
  for (double value : values.coordinates) {
    scale = std::max(scale, std::abs(value));
  }
  const double gap = PointDistance(
      values.point(0), values.point(values.size() - 1), values.dimension);
  if (gap > 1e-12 * scale) {
    return InvalidFieldError(
        "points", "a periodic spline needs the last value equal to the first");
  }
  return absl::OkStatus();
}

absl::StatusOr<CurveInterpolation> PeriodicCubicSpline(
    const PointsView& values, absl::Span<const double> x,
    const CancellationToken* cancel) {
  if (absl::Status status = ValidatePeriodicEnds(values); !status.ok()) {
    return status;
  }
  const size_t n = values.size() - 1;
  const PointsView distinct{.dimension = values.dimension,
                            .coordinates = values.coordinates.subspan(
                                0, n * static_cast<size_t>(values.dimension))};
  PeriodicKnots kappa{.base = std::vector<double>(x.begin(), x.end() - 1),
                      .period = x.back() - x.front()};
  absl::StatusOr<CurveInterpolation> result =
      InterpolatePeriodic(distinct, 3, x.subspan(0, n), kappa, 2, cancel);
  if (!result.ok()) return result;
  // The knots u_3..u_{n+3} are the abscissas themselves (x_0 + T may differ
  // from x_n in the last bit).
  std::copy(x.begin(), x.end(), result->curve.knots.begin() + 3);
  result->parameters.assign(x.begin(), x.end());
  return Finish(std::move(result->curve), std::move(result->parameters), values,
                cancel);
}

absl::Status ValidateSplineInput(const PointsView& values,
                                 absl::Span<const double> x, SplineEnd end,
                                 absl::Span<const double> start_derivative,
                                 absl::Span<const double> end_derivative) {
  if (absl::Status status =
          ValidatePoints(values, "points", end == SplineEnd::kPeriodic ? 3 : 2);
      !status.ok()) {
    return status;
  }
  if (x.size() != values.size()) {
    return InvalidFieldError("parameters",
                             absl::StrCat("needs one abscissa per point (",
                                          values.size(), "), got ", x.size()));
  }
  if (absl::Status status = ValidateParameters(x); !status.ok()) return status;
  const bool clamped = end == SplineEnd::kClamped;
  if (absl::Status status = ValidateDerivative(
          start_derivative, "start_derivative", values.dimension, clamped);
      !status.ok()) {
    return status;
  }
  return ValidateDerivative(end_derivative, "end_derivative", values.dimension,
                            clamped);
}

// ------------------------------------------------------------ surfaces --

// GridParameters averages the parameters of the count_u "columns"
// Q[.][l] (u direction) or of the rows (v direction, `along_u` false),
// skipping lines of zero length for chord length and centripetal (A9.3).
absl::StatusOr<std::vector<double>> GridParameters(
    const ControlNetView& net, bool along_u, int degree,
    Parameterization parameterization) {
  const int count = along_u ? net.count_u : net.count_v;
  const int lines = along_u ? net.count_v : net.count_u;
  if (parameterization == Parameterization::kUniversal) {
    return UniversalParameters(count, degree);
  }
  if (parameterization == Parameterization::kUniform) {
    return UniformValues(static_cast<size_t>(count) - 1);
  }
  const bool centripetal = parameterization == Parameterization::kCentripetal;
  std::vector<double> sum(static_cast<size_t>(count), 0.0), line(sum);
  int used = 0;
  for (int l = 0; l < lines; ++l) {
    for (int k = 1; k < count; ++k) {
      const double chord = PointDistance(
          along_u ? net.point(k, l) : net.point(l, k),
          along_u ? net.point(k - 1, l) : net.point(l, k - 1), net.dimension);
      line[static_cast<size_t>(k)] = line[static_cast<size_t>(k) - 1] +
                                     (centripetal ? std::sqrt(chord) : chord);
    }
    const double total = line.back();
    if (!(total > 0)) continue;
    ++used;
    for (int k = 1; k < count; ++k) {
      sum[static_cast<size_t>(k)] += line[static_cast<size_t>(k)] / total;
    }
  }
  if (used == 0) {
    return InvalidFieldError("points", "every grid line has zero length");
  }
  for (double& value : sum) value /= used;
  sum.back() = 1.0;
  for (size_t k = 1; k < sum.size(); ++k) {
    if (!(sum[k] > sum[k - 1])) {
      return InvalidFieldError(
          "points", absl::StrCat("the averaged ", along_u ? "u" : "v",
                                 " parameters repeat at index ", k,
                                 " (a whole grid line repeated)"));
    }
  }
  return sum;
}

std::vector<double> KnotsFor(absl::Span<const double> t, int p,
                             Parameterization parameterization,
                             KnotRule knot_rule) {
  const int count = static_cast<int>(t.size());
  if (parameterization == Parameterization::kUniversal) {
    return ClampedUniformKnots(count, p);
  }
  if (knot_rule == KnotRule::kUniform) {
    return UniformKnots(t.front(), t.back(), count, p);
  }
  return AveragingKnots(t, p);
}

absl::StatusOr<double> SurfaceResidual(const SurfaceInterpolation& result,
                                       const ControlNetView& points,
                                       const CancellationToken* cancel) {
  std::vector<double> values(points.coordinates.size());
  const std::vector<absl::Span<double>> output = {absl::MakeSpan(values)};
  if (absl::Status status = EvaluateBSplineSurface(
          result.surface.bspline_view(),
          SurfaceSamples::Grid(result.parameters_u, result.parameters_v),
          output, ExecutionContext{.cancellation = cancel});
      !status.ok()) {
    return status;
  }
  double max = 0;
  const size_t d = static_cast<size_t>(points.dimension);
  for (size_t k = 0; k * d < values.size(); ++k) {
    max = std::max(max, PointDistance(values.data() + k * d,
                                      points.coordinates.data() + k * d,
                                      points.dimension));
  }
  return max;
}

// ------------------------------ knots at the parameters (OpenCASCADE) --
// docs/references.md, 'Interpolation with knots at the parameters
// (OpenCASCADE rule)'.

// LagrangeSlope returns the derivative at `at` of the Lagrange polynomial
// through the `count` points from `first` at their parameters t.
Matrix LagrangeSlope(const PointsView& points, absl::Span<const double> t,
                     size_t first, size_t count, double at) {
  const absl::Span<const double> nodes = t.subspan(first, count);
  const std::vector<double> weights = BarycentricWeights(nodes);
  std::vector<double> basis(2 * count), scratch(2);
  LagrangeBasis(nodes, weights, at, 1, absl::MakeSpan(scratch),
                absl::MakeSpan(basis));
  const size_t d = static_cast<size_t>(points.dimension);
  Matrix slope(d, 0.0);
  for (size_t i = 0; i < count; ++i) {
    const double* point = points.point(first + i);
    for (size_t c = 0; c < d; ++c) slope[c] += basis[count + i] * point[c];
  }
  return slope;
}

double SumOfAbsolutes(absl::Span<const double> values) {
  double sum = 0;
  for (double value : values) sum += std::abs(value);
  return sum;
}

// EndSlope returns the derivative condition at the start (or end) of the
// open sequence at t: the given derivative; scaled by |L'|_1 / |given|_1
// with L the Lagrange polynomial through the first min(N, 3) points,
// evaluated at that end (GeomAPI_Interpolate's ScaleTangents, which takes
// the first points for every tangent); or, when not given, the derivative
// of the Lagrange polynomial through the min(N, 4) points at that end.
absl::StatusOr<Matrix> EndSlope(const PointsView& points,
                                absl::Span<const double> t,
                                absl::Span<const double> given, bool at_end,
                                bool scale, absl::string_view field) {
  const double at = at_end ? t.back() : t.front();
  if (given.empty()) {
    const size_t count = std::min<size_t>(t.size(), 4);
    return LagrangeSlope(points, t, at_end ? t.size() - count : 0, count, at);
  }
  Matrix slope(given.begin(), given.end());
  if (!scale) return slope;
  const double length = SumOfAbsolutes(given);
  if (!(length > 0)) {
    return InvalidFieldError(field,
                             "a zero vector has no direction to scale "
                             "(scale_end_derivatives)");
  }
  const double ratio = SumOfAbsolutes(LagrangeSlope(
                           points, t, 0, std::min<size_t>(t.size(), 3), at)) /
                       length;
  for (double& value : slope) value *= ratio;
  return slope;
}

// AtParametersDegree returns the degree of GeomAPI_Interpolate's curve: 1
// for two points and 2 for three open points without derivatives, else 3.
int AtParametersDegree(size_t count, const CurveInterpolationOptions& options) {
  if (!options.start_derivative.empty() || !options.end_derivative.empty() ||
      count > 3) {
    return 3;
  }
  if (count == 2) return 1;
  return options.closed ? 3 : 2;
}

absl::Status ValidateAtParameters(const PointsView& points,
                                  const CurveInterpolationOptions& options) {
  if (absl::Status status = ValidatePoints(points, "points", 2); !status.ok()) {
    return status;
  }
  if (options.closed && !options.end_derivative.empty()) {
    return InvalidFieldError(
        "end_derivative",
        "a closed curve takes its one derivative, where it closes, in "
        "start_derivative");
  }
  if (options.parameters.empty() &&
      options.parameterization == Parameterization::kUniversal) {
    return InvalidFieldError(
        "parameterization",
        "kUniversal fixes its own knots; the kAtParameters knot rule takes "
        "chord length, centripetal, uniform or explicit parameters");
  }
  const int degree = AtParametersDegree(points.size(), options);
  if (options.degree != degree) {
    return InvalidFieldError(
        "degree",
        absl::StrCat("the kAtParameters knot rule needs degree ", degree,
                     " for these ", points.size(),
                     " points and derivatives, got ", options.degree));
  }
  return ValidateEndDerivatives(options, points.dimension);
}

// InterpolateOpenAtParameters: the polygon (degree 1), the parabola
// (degree 2, knots t_0 (x3), t_2 (x3)) or the clamped cubic with a knot at
// every parameter and the two end derivatives.
absl::StatusOr<CurveInterpolation> InterpolateOpenAtParameters(
    const PointsView& points, const CurveInterpolationOptions& options) {
  absl::StatusOr<std::vector<double>> t =
      options.parameters.empty()
          ? OpenParameters(points, options.parameterization)
          : ExplicitParameters(options.parameters, points.size());
  if (!t.ok()) return t.status();
  const int p = options.degree;
  if (p < 3) {
    std::vector<double> knots(static_cast<size_t>(p) + 1, t->front());
    knots.insert(knots.end(), static_cast<size_t>(p) + 1, t->back());
    absl::StatusOr<Matrix> control =
        SolveOpen(points, p, knots, *t, {}, {}, options.cancel);
    if (!control.ok()) return control.status();
    return Finish(
        MakeCurve(p, points.dimension, *std::move(control), std::move(knots)),
        *std::move(t), points, options.cancel);
  }
  absl::StatusOr<Matrix> start =
      EndSlope(points, *t, options.start_derivative, false,
               options.scale_end_derivatives, "start_derivative");
  if (!start.ok()) return start.status();
  absl::StatusOr<Matrix> end =
      EndSlope(points, *t, options.end_derivative, true,
               options.scale_end_derivatives, "end_derivative");
  if (!end.ok()) return end.status();
  return InterpolateCubicSpline(points, *t, SplineEnd::kClamped, *start, *end,
                                options.cancel);
}

// InterpolateClosedAtParameters: GeomAPI_Interpolate's periodic curve, a
// cubic on the periodic knots t_0, t_0, t_1, ..., t_{N-1} (period T)
// solved as an open system with C(t_0) = C(t_N) = Q_0 and C'(t_0) =
// C'(t_N) = the start derivative, whose solution is the periodic one: its
// poles N+1, N+2 repeat 0, 1.
// Two points without a derivative give the closed polygon.
absl::StatusOr<CurveInterpolation> InterpolateClosedAtParameters(
    const PointsView& points, const CurveInterpolationOptions& options) {
  absl::StatusOr<std::vector<double>> t = ClosedParameters(points, options);
  if (!t.ok()) return t.status();
  const size_t n = points.size(), d = static_cast<size_t>(points.dimension);
  const int p = options.degree;
  const int before = p == 1 ? 1 : 2;  // knots before t_0
  PeriodicKnots kappa{.base = std::vector<double>(t->begin(), t->end() - 1),
                      .period = t->back() - t->front()};
  if (p == 3) kappa.base.insert(kappa.base.begin(), t->front());
  // N + 3 poles for the cubic (N + 1 knots a period, t_0 doubled), 3 for
  // the polygon.
  const size_t poles = kappa.base.size() + static_cast<size_t>(p + 1 - before);
  std::vector<double> knots(poles + static_cast<size_t>(p) + 1);
  for (size_t i = 0; i < knots.size(); ++i) {
    knots[i] = kappa(static_cast<long>(i) - before);
  }
  // The domain ends at t_N itself (t_0 + T may differ in the last bit).
  std::fill_n(
      knots.begin() + static_cast<ptrdiff_t>(kappa.base.size()) + before,
      before, t->back());
  Matrix closing(points.coordinates.begin(), points.coordinates.end());
  closing.insert(closing.end(), points.point(0), points.point(0) + d);
  Matrix control;
  if (p == 1) {
    control = std::move(closing);
  } else {
    const absl::Span<const double> open = absl::MakeConstSpan(*t).subspan(0, n);
    absl::StatusOr<Matrix> slope =
        EndSlope(points, open, options.start_derivative, false,
                 options.scale_end_derivatives, "start_derivative");
    if (!slope.ok()) return slope.status();
    const EndCondition seam{.order = 1, .value = *slope};
    absl::StatusOr<Matrix> solved =
        SolveOpen({.dimension = points.dimension, .coordinates = closing}, p,
                  knots, *t, seam, seam, options.cancel);
    if (!solved.ok()) return solved.status();
    control = *std::move(solved);
    // The last two poles equal the first two up to rounding; as
    // OpenCASCADE, keep the first ones, so the curve closes exactly.
    std::copy_n(control.begin(), 2 * d,
                control.end() - 2 * static_cast<ptrdiff_t>(d));
  }
  t->pop_back();
  return Finish(
      MakeCurve(p, points.dimension, std::move(control), std::move(knots)),
      *std::move(t), points, options.cancel);
}

absl::StatusOr<CurveInterpolation> InterpolateAtParameters(
    const PointsView& points, const CurveInterpolationOptions& options) {
  if (absl::Status status = ValidateAtParameters(points, options);
      !status.ok()) {
    return status;
  }
  return options.closed ? InterpolateClosedAtParameters(points, options)
                        : InterpolateOpenAtParameters(points, options);
}

}  // namespace

absl::StatusOr<std::vector<double>> InterpolationParameters(
    const PointsView& points, int degree, Parameterization parameterization) {
  if (absl::Status status = ValidateCurveData(points, degree); !status.ok()) {
    return status;
  }
  if (parameterization == Parameterization::kUniversal) {
    return UniversalParameters(static_cast<int>(points.size()), degree);
  }
  return OpenParameters(points, parameterization);
}

absl::StatusOr<CurveInterpolation> InterpolateCurve(
    const PointsView& points, const CurveInterpolationOptions& options) {
  if (options.knot_rule == KnotRule::kAtParameters) {
    return InterpolateAtParameters(points, options);
  }
  if (options.scale_end_derivatives) {
    return InvalidFieldError(
        "scale_end_derivatives",
        "only the kAtParameters knot rule scales end derivatives");
  }
  const int p = options.degree;
  if (absl::Status status = ValidateCurveData(points, p); !status.ok()) {
    return status;
  }
  if (options.closed) return InterpolateClosed(points, options);
  const bool has_start = !options.start_derivative.empty();
  const bool has_end = !options.end_derivative.empty();
  if (absl::Status status = ValidateEndDerivatives(options, points.dimension);
      !status.ok()) {
    return status;
  }
  const int count = static_cast<int>(points.size()) + has_start + has_end;
  std::vector<double> t;
  const bool universal =
      options.parameters.empty() &&
      options.parameterization == Parameterization::kUniversal;
  if (!options.parameters.empty()) {
    absl::StatusOr<std::vector<double>> given =
        ExplicitParameters(options.parameters, points.size());
    if (!given.ok()) return given.status();
    t = *std::move(given);
  } else if (universal) {
    // The maxima of every basis function except the derivative rows'.
    const std::vector<double> maxima = UniversalParameters(count, p);
    for (int i = 0; i < count; ++i) {
      if ((has_start && i == 1) || (has_end && i == count - 2)) continue;
      t.push_back(maxima[static_cast<size_t>(i)]);
    }
  } else {
    absl::StatusOr<std::vector<double>> computed =
        OpenParameters(points, options.parameterization);
    if (!computed.ok()) return computed.status();
    t = *std::move(computed);
  }
  std::vector<double> sites;  // t with the derivative ends doubled
  if (has_start) sites.push_back(t.front());
  sites.insert(sites.end(), t.begin(), t.end());
  if (has_end) sites.push_back(t.back());
  std::vector<double> knots = KnotsFor(
      sites, p,
      universal ? Parameterization::kUniversal : Parameterization::kUniform,
      options.knot_rule);
  const EndCondition start{.order = has_start ? 1 : 0,
                           .value = options.start_derivative};
  const EndCondition end{.order = has_end ? 1 : 0,
                         .value = options.end_derivative};
  absl::StatusOr<Matrix> control =
      SolveOpen(points, p, knots, t, start, end, options.cancel);
  if (!control.ok()) return control.status();
  return Finish(
      MakeCurve(p, points.dimension, *std::move(control), std::move(knots)),
      std::move(t), points, options.cancel);
}

absl::StatusOr<CurveInterpolation> InterpolateCubicSpline(
    const PointsView& values, absl::Span<const double> x, SplineEnd end,
    absl::Span<const double> start_derivative,
    absl::Span<const double> end_derivative, const CancellationToken* cancel) {
  if (absl::Status status =
          ValidateSplineInput(values, x, end, start_derivative, end_derivative);
      !status.ok()) {
    return status;
  }
  if (end == SplineEnd::kPeriodic) {
    return PeriodicCubicSpline(values, x, cancel);
  }
  std::vector<double> t(x.begin(), x.end());
  if (end == SplineEnd::kNotAKnot && values.size() >= 4) {
    absl::StatusOr<Matrix> control =
        SolveOpen(values, 3, CubicKnots(x, true), x, {}, {}, cancel);
    if (!control.ok()) return control.status();
    const double removed[] = {x[1], x[x.size() - 2]};
    absl::StatusOr<BSplineCurveData> curve =
        WithKnots(MakeCurve(3, values.dimension, *std::move(control),
                            CubicKnots(x, true)),
                  removed, cancel);
    if (!curve.ok()) return curve.status();
    return Finish(*std::move(curve), std::move(t), values, cancel);
  }
  EndCondition start{.order = 2, .value = {}}, finish{.order = 2, .value = {}};
  std::pair<Matrix, Matrix> slopes;
  if (end == SplineEnd::kNotAKnot) {  // 2 or 3 points: line or parabola
    slopes = PolynomialEndSlopes(values, x);
    start = {.order = 1, .value = slopes.first};
    finish = {.order = 1, .value = slopes.second};
  } else if (end == SplineEnd::kClamped) {
    start = {.order = 1, .value = start_derivative};
    finish = {.order = 1, .value = end_derivative};
  }
  absl::StatusOr<Matrix> control =
      SolveOpen(values, 3, CubicKnots(x, false), x, start, finish, cancel);
  if (!control.ok()) return control.status();
  return Finish(
      MakeCurve(3, values.dimension, *std::move(control), CubicKnots(x, false)),
      std::move(t), values, cancel);
}

absl::StatusOr<CurveApproximation> ApproximateCurve(
    const PointsView& points, int degree, int control_point_count,
    Parameterization parameterization, absl::Span<const double> parameters,
    const CancellationToken* cancel) {
  const int p = degree;
  if (absl::Status status = ValidateCurveData(points, p); !status.ok()) {
    return status;
  }
  const int m = static_cast<int>(points.size()) - 1;
  const int n = control_point_count - 1;
  if (n < p || n > m) {
    return InvalidFieldError(
        "control_point_count",
        absl::StrCat("must lie in [degree + 1, point count] = [", p + 1, ", ",
                     m + 1, "], got ", control_point_count));
  }
  absl::StatusOr<std::vector<double>> computed =
      parameters.empty() ? InterpolationParameters(points, p, parameterization)
                         : ExplicitParameters(parameters, points.size());
  if (!computed.ok()) return computed.status();
  std::vector<double> t = *std::move(computed);
  // Knots by eq. 9.69: every knot span holds at least one parameter.
  std::vector<double> knots(static_cast<size_t>(p) + 1, t.front());
  const double spacing = static_cast<double>(m + 1) / (n - p + 1);
  for (int j = 1; j <= n - p; ++j) {
    const int i = static_cast<int>(j * spacing);
    const double alpha = j * spacing - i;
    knots.push_back((1 - alpha) * t[static_cast<size_t>(i) - 1] +
                    alpha * t[static_cast<size_t>(i)]);
  }
  knots.insert(knots.end(), static_cast<size_t>(p) + 1, t.back());

  const size_t d = static_cast<size_t>(points.dimension);
  Matrix control(static_cast<size_t>(n + 1) * d, 0.0);
  std::copy_n(points.point(0), d, control.begin());
  std::copy_n(points.point(static_cast<size_t>(m)), d,
              control.end() - static_cast<ptrdiff_t>(d));
  const int unknowns = n - 1;  // P_1..P_{n-1}
  if (unknowns > 0) {
    BandedMatrix normal(unknowns, p, p, cancel);
    CancellationPoll poll(cancel);
    Matrix rhs(static_cast<size_t>(unknowns) * d, 0.0);
    std::vector<double> basis(static_cast<size_t>(p) + 1);
    std::vector<double> scratch(BasisScratchSize(p));
    std::vector<double> residual(d);
    int span = p;
    for (int k = 1; k < m; ++k) {
      if (absl::Status status =
              poll.Done(static_cast<size_t>(p + 1) * (p + 1 + d));
          !status.ok()) {
        return status;
      }
      const double u = t[static_cast<size_t>(k)];
      span = FindSpanFrom(span, n, p, u, knots);
      BasisFunctions(span, u, p, knots, absl::MakeSpan(basis),
                     absl::MakeSpan(scratch));
      // R_k = Q_k - N_0(t_k) Q_0 - N_n(t_k) Q_m (eq. 9.63).
      std::copy_n(points.point(static_cast<size_t>(k)), d, residual.begin());
      for (int j = 0; j <= p; ++j) {
        const int i = span - p + j;
        if (i != 0 && i != n) continue;
        const double* end_point =
            points.point(i == 0 ? 0 : static_cast<size_t>(m));
        for (size_t c = 0; c < d; ++c) {
          residual[c] -= basis[static_cast<size_t>(j)] * end_point[c];
        }
      }
      for (int a = 0; a <= p; ++a) {
        const int row = span - p + a - 1;
        if (row < 0 || row >= unknowns) continue;
        const double na = basis[static_cast<size_t>(a)];
        for (size_t c = 0; c < d; ++c) {
          rhs[static_cast<size_t>(row) * d + c] += na * residual[c];
        }
        for (int b = 0; b <= p; ++b) {
          const int column = span - p + b - 1;
          if (column < 0 || column >= unknowns) continue;
          normal.at(row, column) += na * basis[static_cast<size_t>(b)];
        }
      }
    }
    if (absl::Status status = normal.Factor(); !status.ok()) return status;
    if (absl::Status status = normal.Solve(rhs.data(), points.dimension);
        !status.ok()) {
      return status;
    }
    std::copy(rhs.begin(), rhs.end(),
              control.begin() + static_cast<ptrdiff_t>(d));
  }
  CurveApproximation result{
      .curve =
          MakeCurve(p, points.dimension, std::move(control), std::move(knots)),
      .parameters = std::move(t)};
  absl::StatusOr<std::pair<double, double>> residuals =
      Residuals(result.curve, result.parameters, points, cancel);
  if (!residuals.ok()) return residuals.status();
  result.max_residual = residuals->first;
  result.rms_residual = std::sqrt(residuals->second / (m + 1));
  return result;
}

absl::StatusOr<SurfaceInterpolation> InterpolateSurface(
    const ControlNetView& points, int degree_u, int degree_v,
    Parameterization parameterization, KnotRule knot_rule,
    const CancellationToken* cancel) {
  if (knot_rule == KnotRule::kAtParameters) {
    return InvalidFieldError(
        "knot_rule",
        "kAtParameters needs end derivatives, which surfaces do not take");
  }
  if (absl::Status status = ValidateDegree(degree_u, "degree_u");
      !status.ok()) {
    return status;
  }
  if (absl::Status status = ValidateDegree(degree_v, "degree_v");
      !status.ok()) {
    return status;
  }
  if (absl::Status status =
          ValidateControlNet(points, "points", degree_u + 1, degree_v + 1);
      !status.ok()) {
    return status;
  }
  SurfaceInterpolation result;
  absl::StatusOr<std::vector<double>> tu =
      GridParameters(points, true, degree_u, parameterization);
  if (!tu.ok()) return tu.status();
  absl::StatusOr<std::vector<double>> tv =
      GridParameters(points, false, degree_v, parameterization);
  if (!tv.ok()) return tv.status();
  result.parameters_u = *std::move(tu);
  result.parameters_v = *std::move(tv);
  SurfaceData& surface = result.surface;
  surface.degree_u = degree_u;
  surface.degree_v = degree_v;
  surface.dimension = points.dimension;
  surface.count_u = points.count_u;
  surface.count_v = points.count_v;
  surface.knots_u =
      KnotsFor(result.parameters_u, degree_u, parameterization, knot_rule);
  surface.knots_v =
      KnotsFor(result.parameters_v, degree_v, parameterization, knot_rule);
  // Two factorizations (docs/references.md, 'Global B-spline
  // interpolation'): u once for all columns, v once for all rows of the
  // intermediate net.
  absl::StatusOr<BandedMatrix> along_u =
      FactorOpenSystem(degree_u,
                       BuildOpenRows(degree_u, surface.knots_u,
                                     result.parameters_u, {}, {}, cancel),
                       cancel);
  if (!along_u.ok()) return along_u.status();
  absl::StatusOr<BandedMatrix> along_v =
      FactorOpenSystem(degree_v,
                       BuildOpenRows(degree_v, surface.knots_v,
                                     result.parameters_v, {}, {}, cancel),
                       cancel);
  if (!along_v.ok()) return along_v.status();
  surface.coordinates.assign(points.coordinates.begin(),
                             points.coordinates.end());
  const size_t row = static_cast<size_t>(points.count_v) *
                     static_cast<size_t>(points.dimension);
  if (absl::Status status =
          along_u->Solve(surface.coordinates.data(), static_cast<int>(row));
      !status.ok()) {
    return status;
  }
  for (size_t k = 0; k < static_cast<size_t>(points.count_u); ++k) {
    if (absl::Status status = along_v->Solve(
            surface.coordinates.data() + k * row, points.dimension);
        !status.ok()) {
      return status;
    }
  }
  absl::StatusOr<double> residual = SurfaceResidual(result, points, cancel);
  if (!residual.ok()) return residual.status();
  result.max_residual = *residual;
  return result;
}

}  // namespace freeform
