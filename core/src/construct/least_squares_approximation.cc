// Least-squares approximation of points by a B-spline curve with a given
// number of control points (ApproximateCurve; The NURBS Book A9.7, knots by
// eq. 9.69), its normal equations solved by a banded LU.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/types/span.h"
#include "construct/interpolation_parameters.h"
#include "construct/interpolation_result.h"
#include "freeform/core/bspline.h"
#include "freeform/core/interpolation.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "linalg/banded_lu.h"

namespace freeform {
namespace {

using internal::BandedLu;
using internal::CurveResiduals;
using internal::ExplicitParameters;
using internal::MakeCurve;
using internal::Matrix;
using internal::ValidateCurveData;

}  // namespace

absl::StatusOr<CurveApproximation> ApproximateCurve(
    const PointsView& points, int degree, int control_point_count,
    Parameterization parameterization, absl::Span<const double> parameters,
    const CancellationToken* cancel) {
  const int p = degree;
  RETURN_IF_ERROR(ValidateCurveData(points, p));
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
    BandedLu normal(unknowns, p, p, cancel);
    CancellationPoll poll(cancel);
    Matrix rhs(static_cast<size_t>(unknowns) * d, 0.0);
    std::vector<double> basis(static_cast<size_t>(p) + 1);
    std::vector<double> scratch(BasisScratchSize(p));
    std::vector<double> residual(d);
    int span = p;
    for (int k = 1; k < m; ++k) {
      RETURN_IF_ERROR(poll.Done(static_cast<size_t>(p + 1) * (p + 1 + d)));
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
    RETURN_IF_ERROR(normal.Factor());
    RETURN_IF_ERROR(normal.Solve(rhs.data(), points.dimension));
    std::copy(rhs.begin(), rhs.end(),
              control.begin() + static_cast<ptrdiff_t>(d));
  }
  CurveApproximation result{
      .curve =
          MakeCurve(p, points.dimension, std::move(control), std::move(knots)),
      .parameters = std::move(t)};
  absl::StatusOr<std::pair<double, double>> residuals =
      CurveResiduals(result.curve, result.parameters, points, cancel);
  if (!residuals.ok()) return residuals.status();
  result.max_residual = residuals->first;
  result.rms_residual = std::sqrt(residuals->second / (m + 1));
  return result;
}

}  // namespace freeform
