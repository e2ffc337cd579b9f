#include "refine/knot_insertion.h"

#include <algorithm>
#include <cstddef>
#include <vector>

#include "absl/status/status.h"
#include "freeform/core/status_macros.h"

namespace freeform::internal {
namespace {

// LastKnotAtOrBelow returns the largest index i in [p, n] with
// knots[i] <= u (p when there is none), the span A5.4 starts from.
int LastKnotAtOrBelow(const std::vector<double>& knots, int p, int n,
                      double u) {
  const int i =
      static_cast<int>(std::upper_bound(knots.begin(), knots.end(), u) -
                       knots.begin()) -
      1;
  return std::clamp(i, p, n);
}

}  // namespace

// The NURBS Book A5.4 (RefineKnotVectCurve), with the spans found by
// LastKnotAtOrBelow.
absl::StatusOr<Spline> RefineKnots(const Spline& spline,
                                   absl::Span<const double> x,
                                   const CancellationToken* cancel) {
  if (x.empty()) return spline;
  CancellationPoll poll(cancel);
  const int p = spline.degree;
  const std::vector<double>& u = spline.knots;
  const PointArray& pw = spline.points;
  const int dim = pw.dim;
  const int n = static_cast<int>(pw.count()) - 1;
  const int m = n + p + 1;
  const int r = static_cast<int>(x.size()) - 1;
  const int a = LastKnotAtOrBelow(u, p, n, x[0]);
  const int b = LastKnotAtOrBelow(u, p, n, x[r]) + 1;
  Spline out{p, std::vector<double>(static_cast<size_t>(m + r + 2)),
             PointArray{dim, std::vector<double>(
                                 static_cast<size_t>(n + r + 2) * dim)}};
  std::vector<double>& ubar = out.knots;
  PointArray& qw = out.points;
  for (int j = 0; j <= a - p; ++j) std::copy_n(pw.at(j), dim, qw.at(j));
  for (int j = b - 1; j <= n; ++j) std::copy_n(pw.at(j), dim, qw.at(j + r + 1));
  for (int j = 0; j <= a; ++j) ubar[j] = u[j];
  for (int j = b + p; j <= m; ++j) ubar[j + r + 1] = u[j];
  int i = b + p - 1;
  int k = b + p + r;
  for (int j = r; j >= 0; --j) {
    RETURN_IF_ERROR(poll.Done(static_cast<size_t>(p + 1) * dim));
    while (x[j] <= u[i] && i > a) {
      std::copy_n(pw.at(i - p - 1), dim, qw.at(k - p - 1));
      ubar[k] = u[i];
      --k;
      --i;
    }
    std::copy_n(qw.at(k - p), dim, qw.at(k - p - 1));
    for (int l = 1; l <= p; ++l) {
      const int ind = k - p + l;
      double alpha = ubar[k + l] - x[j];
      double* target = qw.at(ind - 1);
      const double* next = qw.at(ind);
      if (alpha == 0.0) {
        std::copy_n(next, dim, target);
        continue;
      }
      alpha /= ubar[k + l] - u[i - p + l];
      for (int c = 0; c < dim; ++c) {
        target[c] = alpha * target[c] + (1.0 - alpha) * next[c];
      }
    }
    ubar[k] = x[j];
    --k;
  }
  return out;
}

}  // namespace freeform::internal
