#include "construct/open_interpolation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "base/simd/range_simd.h"
#include "base/zeroed_array.h"
#include "construct/collocation_lu.h"
#include "freeform/core/bspline.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "kinds/bspline_spans.h"

namespace freeform::internal {
namespace {

// OpenRightHandSide stacks the points and end conditions in row order.
Matrix OpenRightHandSide(const PointsView& points, EndCondition start,
                         EndCondition end) {
  if (start.order == 0 && end.order == 0) {
    return Matrix(points.coordinates.begin(), points.coordinates.end());
  }
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

// What SolveOpenOf reads: the system of SolveOpen, with its right-hand side
// (OpenRightHandSide), which it overwrites with the control points.
struct OpenSystem {
  int p = 0;
  int dimension = 0;
  absl::Span<const double> knots;
  absl::Span<const double> t;
  EndCondition start;
  EndCondition end;
  double* rhs = nullptr;
};

// The rows of the collocation matrix in order (BuildOpenRows' rows, value
// for value): Next returns each row's first column and p + 1 coefficients.
// The basis functions of a span reuse its reciprocal knot differences.
template <int kDegree>
class OpenRowSource {
 public:
  OpenRowSource(const OpenSystem& system)
      : system_(system),
        p_(DegreeOf<kDegree>(system.p)),
        n_(static_cast<int>(system.knots.size()) - p_ - 2),
        w_(static_cast<size_t>(p_) + 1),
        scratch_(BasisDerivativesScratchSize(p_)),
        ders_(3 * w_) {
    if constexpr (kDegree == kAnyDegree) {
      inverse_.resize(static_cast<size_t>(p_) * w_ / 2);
      left_.resize(w_);
      right_.resize(w_);
    }
  }

  // ValueRow returns the first column of the row of N_{i,p}(u), whose
  // coefficients it writes to `values`; `hint` is the span of the previous
  // data row.
  int ValueRow(double u, int& hint, double* values) {
    const double* knots = system_.knots.data();
    const int span = FindSpanFrom(hint, n_, p_, u, system_.knots);
    if (span != inverse_span_) {
      InverseKnotDifferences<kDegree>(knots, span, p_, inverse_.data());
      inverse_span_ = span;
    }
    BasisFunctionsOn<kDegree, false>(knots, span, u, p_, inverse_.data(),
                                     left_.data(), right_.data(), values,
                                     nullptr);
    hint = span;
    return span - p_;
  }

  // DerivativeRow returns the first column of the row of N^(order)_{i,p}(u)
  // and points `values` at its coefficients.
  int DerivativeRow(double u, int order, const double*& values) {
    const int span = FindSpan(n_, p_, u, system_.knots);
    BasisFunctionDerivatives(span, u, p_, order, system_.knots,
                             absl::MakeSpan(ders_), absl::MakeSpan(scratch_));
    values = ders_.data() + static_cast<size_t>(order) * w_;
    return span - p_;
  }

 private:
  const OpenSystem& system_;
  const int p_;
  const int n_;
  const size_t w_;
  std::vector<double> scratch_;
  std::vector<double> ders_;
  // On the stack for a compiled-in degree.
  template <size_t kSize>
  using Storage = std::conditional_t<kDegree == kAnyDegree, std::vector<double>,
                                     std::array<double, kSize>>;
  static constexpr size_t kW = kDegree == kAnyDegree ? 1 : kDegree + 1;
  Storage<kW*(kW - 1) / 2 + 1> inverse_{};
  Storage<kW> left_{};
  Storage<kW> right_{};
  int inverse_span_ = -1;
};

// The solver of one open system: Eliminate computes the rows of A9.1 / A9.2
// in BuildOpenRows' order (the value at t_0, the start condition, values at
// t_1..t_{n-1}, the end condition, the value at t_n) and eliminates each as
// it comes; Finish back-substitutes, which gives the solution of
// FactorOpenSystem and BandedLu::Solve. When measuring it keeps the value
// rows and, block by block behind the back substitution, takes the largest
// residual |C(t_k) - Q_k|: C(t_k) summed as the scalar evaluator
// (bspline.cc, CombinePointsOf) and its Highway twin do, from the same basis
// values, so as EvaluateBSplineCurve; the largest squared distance, whose
// square root is the largest distance (sqrt is monotonic).
template <int kDegree, int kDimension>
class OpenSolver {
 public:
  OpenSolver(const OpenSystem& system, const PointsView& points, bool measure,
             const CancellationToken* cancel)
      : system_(system),
        points_(points),
        measure_(measure),
        p_(DegreeOf<kDegree>(system.p)),
        w_(static_cast<size_t>(p_) + 1),
        count_(static_cast<int>(system.t.size()) + (system.start.order > 0) +
               (system.end.order > 0)),
        work_(w_ * w_ * static_cast<size_t>(system.dimension)),
        lu_(count_, p_, system.dimension, system.rhs),
        rows_(system),
        poll_(cancel),
        first_(measure ? system.t.size() : 1),
        basis_((measure ? system.t.size() : 1) * w_) {}

  absl::Status Eliminate() {
    const absl::Span<const double> t = system_.t;
    int hint = p_;
    for (size_t k = 0; k < t.size(); ++k) {
      RETURN_IF_ERROR(poll_.Done(work_));
      if (k + 1 == t.size() && system_.end.order > 0 &&
          !DerivativeRow(t[k], system_.end.order)) {
        return SingularSystemError();
      }
      const size_t kept = measure_ ? k : 0;
      double* values = basis_.data() + kept * w_;
      first_[kept] = rows_.ValueRow(t[k], hint, values);
      if (!lu_.AddRow(first_[kept], values)) return SingularSystemError();
      if (k == 0 && system_.start.order > 0 &&
          !DerivativeRow(t[k], system_.start.order)) {
        return SingularSystemError();
      }
    }
    return absl::OkStatus();
  }

  // Finish returns the largest residual when measuring (NaN when a control
  // point is not finite), else 0.
  absl::StatusOr<double> Finish() {
    constexpr int kBlock = 1024;
    int pending = static_cast<int>(system_.t.size()) - 1;  // last unmeasured
    constexpr double kLargest = std::numeric_limits<double>::max();
    bool finite = true;  // every control point solved so far
    double largest = 0.0;
    const size_t d = static_cast<size_t>(system_.dimension);
    for (int begin = count_; begin > 0; begin -= kBlock) {
      RETURN_IF_ERROR(poll_.Done(work_ * kBlock));
      const int end = std::max(0, begin - kBlock);
      lu_.BackSubstituteRows(begin, end);
      if (!measure_) continue;
      finite =
          finite && simd::AllInRange(system_.rhs + static_cast<size_t>(end) * d,
                                     static_cast<size_t>(begin - end) * d,
                                     -kLargest, kLargest);
      for (; pending >= 0 && first_[static_cast<size_t>(pending)] >= end;
           --pending) {
        largest = std::max(largest, SquaredResidual(pending));
      }
    }
    if (!finite) return std::numeric_limits<double>::quiet_NaN();
    return std::sqrt(largest);
  }

 private:
  bool DerivativeRow(double u, int order) {
    const double* values = nullptr;
    const int first = rows_.DerivativeRow(u, order, values);
    return lu_.AddRow(first, values);
  }

  // SquaredResidual returns |C(t_k) - Q_k|^2 once the control points of
  // data row k are solved.
  double SquaredResidual(int k) const {
    const int p = DegreeOf<kDegree>(p_);
    const int d = kDimension > 0 ? kDimension : system_.dimension;
    const size_t row = static_cast<size_t>(k);
    const double* basis = basis_.data() + row * w_;
    const double* control =
        system_.rhs + static_cast<size_t>(first_[row]) * static_cast<size_t>(d);
    const double* point = points_.point(row);
    double squared = 0.0;
#pragma GCC unroll 4
    for (int c = 0; c < d; ++c) {
      double sum = 0.0;
#pragma GCC unroll 8
      for (int j = 0; j <= p; ++j) sum += basis[j] * control[j * d + c];
      squared += (sum - point[c]) * (sum - point[c]);
    }
    return squared;
  }

  const OpenSystem& system_;
  const PointsView& points_;
  const bool measure_;
  const int p_;
  const size_t w_;
  const int count_;
  const size_t work_;  // per row, for the cancellation poll
  CollocationLu<kDegree, kDimension> lu_;
  OpenRowSource<kDegree> rows_;
  CancellationPoll poll_;
  // The value rows' first columns and coefficients: all of them when
  // measuring, else only the current one.
  ZeroedArray<int> first_;
  ZeroedDoubles basis_;
};

// SolveOpenOf solves the system in place (system.rhs) and, with `measured`
// (may be null), writes the largest residual there.
template <int kDegree, int kDimension>
absl::Status SolveOpenOf(const OpenSystem& system, const PointsView& points,
                         double* measured, const CancellationToken* cancel) {
  OpenSolver<kDegree, kDimension> solver(system, points, measured != nullptr,
                                         cancel);
  RETURN_IF_ERROR(solver.Eliminate());
  absl::StatusOr<double> largest = solver.Finish();
  if (!largest.ok()) return largest.status();
  if (measured != nullptr) *measured = *largest;
  return absl::OkStatus();
}

// SolveOpenSystem dispatches SolveOpenOf on the degree and the dimension.
absl::Status SolveOpenSystem(const OpenSystem& system, const PointsView& points,
                             double* measured,
                             const CancellationToken* cancel) {
  absl::Status status;
  WithDegree(system.p, [&]<int kDegree>() {
    switch (system.dimension) {
      case 2:
        status = SolveOpenOf<kDegree, 2>(system, points, measured, cancel);
        break;
      case 3:
        status = SolveOpenOf<kDegree, 3>(system, points, measured, cancel);
        break;
      default:
        status = SolveOpenOf<kDegree, 0>(system, points, measured, cancel);
    }
  });
  return status;
}
}  // namespace

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
    RETURN_IF_ERROR(poll.Done(w * w));
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

absl::StatusOr<BandedLu> FactorOpenSystem(int p,
                                          const absl::StatusOr<OpenRows>& built,
                                          const CancellationToken* cancel) {
  if (!built.ok()) return built.status();
  const OpenRows& rows = *built;
  const int count = static_cast<int>(rows.first.size());
  int kl = 0, ku = 0;
  for (int r = 0; r < count; ++r) {
    const int first = rows.first[static_cast<size_t>(r)];
    if (r < first || r > first + p) return SingularSystemError();
    kl = std::max(kl, r - first);
    ku = std::max(ku, first + p - r);
  }
  BandedLu matrix(count, kl, ku, cancel);
  CancellationPoll poll(cancel);
  for (int r = 0; r < count; ++r) {
    RETURN_IF_ERROR(poll.Done(static_cast<size_t>(p) + 1));
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
  RETURN_IF_ERROR(matrix.Factor());
  return matrix;
}

absl::StatusOr<Matrix> SolveOpen(const PointsView& points, int p,
                                 absl::Span<const double> knots,
                                 absl::Span<const double> t, EndCondition start,
                                 EndCondition end,
                                 const CancellationToken* cancel) {
  absl::StatusOr<OpenSolution> solved =
      SolveOpenMeasured(points, p, knots, t, start, end, false, cancel);
  if (!solved.ok()) return solved.status();
  return std::move(solved->control);
}

absl::StatusOr<OpenSolution> SolveOpenMeasured(
    const PointsView& points, int p, absl::Span<const double> knots,
    absl::Span<const double> t, EndCondition start, EndCondition end,
    bool measure, const CancellationToken* cancel) {
  OpenSolution solution{.control = OpenRightHandSide(points, start, end)};
  const OpenSystem system{.p = p,
                          .dimension = points.dimension,
                          .knots = knots,
                          .t = t,
                          .start = start,
                          .end = end,
                          .rhs = solution.control.data()};
  RETURN_IF_ERROR(SolveOpenSystem(
      system, points, measure ? &solution.max_residual : nullptr, cancel));
  return solution;
}

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

absl::Status ValidateEndDerivatives(const CurveInterpolationOptions& options,
                                    int dimension) {
  for (const auto& [value, field] :
       {std::pair{options.start_derivative, "start_derivative"},
        std::pair{options.end_derivative, "end_derivative"}}) {
    if (value.empty()) continue;
    RETURN_IF_ERROR(ValidateDerivative(value, field, dimension, true));
    if (options.degree < 2) {
      return InvalidFieldError(field, "end derivatives need degree >= 2");
    }
  }
  return absl::OkStatus();
}

}  // namespace freeform::internal
