#include "construct/interpolation_knots.h"

#include <algorithm>
#include <cstddef>
#include <vector>

#include "freeform/core/status_macros.h"

namespace freeform::internal {
namespace {

// AveragingKnots returns the clamped knots u_{j+p} = (s_j + ... +
// s_{j+p-1}) / p, j = 1..N-p-1, for N sites s (eq. 9.8).
absl::StatusOr<std::vector<double>> AveragingKnots(
    absl::Span<const double> s, int p, const CancellationToken* cancel) {
  const size_t count = s.size();
  const size_t degree = static_cast<size_t>(p);
  std::vector<double> knots(count + degree + 1, s.back());
  std::fill_n(knots.begin(), degree + 1, s.front());
  CancellationPoll poll(cancel);
  for (size_t j = 1; j + degree < count; ++j) {
    RETURN_IF_ERROR(poll.Done(degree));
    double sum = 0;
    for (size_t i = j; i < j + degree; ++i) sum += s[i];
    knots[j + degree] = sum / p;
  }
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

}  // namespace

std::vector<double> ClampedUniformKnots(int count, int p) {
  std::vector<double> knots(static_cast<size_t>(p) + 1, 0.0);
  for (int j = 1; j < count - p; ++j) {
    knots.push_back(static_cast<double>(j) / (count - p));
  }
  knots.insert(knots.end(), static_cast<size_t>(p) + 1, 1.0);
  return knots;
}

absl::StatusOr<std::vector<double>> KnotsFor(absl::Span<const double> t, int p,
                                             Parameterization parameterization,
                                             KnotRule knot_rule,
                                             const CancellationToken* cancel) {
  const int count = static_cast<int>(t.size());
  if (parameterization == Parameterization::kUniversal) {
    return ClampedUniformKnots(count, p);
  }
  if (knot_rule == KnotRule::kUniform) {
    return UniformKnots(t.front(), t.back(), count, p);
  }
  return AveragingKnots(t, p, cancel);
}

}  // namespace freeform::internal
