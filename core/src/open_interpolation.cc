#include "open_interpolation.h"

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "freeform/core/bspline.h"
#include "freeform/core/status.h"

namespace freeform::internal {
namespace {

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

absl::StatusOr<Matrix> SolveOpen(const PointsView& points, int p,
                                 absl::Span<const double> knots,
                                 absl::Span<const double> t, EndCondition start,
                                 EndCondition end,
                                 const CancellationToken* cancel) {
  absl::StatusOr<BandedLu> matrix = FactorOpenSystem(
      p, BuildOpenRows(p, knots, t, start, end, cancel), cancel);
  if (!matrix.ok()) return matrix.status();
  Matrix rhs = OpenRightHandSide(points, start, end);
  if (absl::Status status = matrix->Solve(rhs.data(), points.dimension);
      !status.ok()) {
    return status;
  }
  return rhs;
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

}  // namespace freeform::internal
