#include "construct/tolerance_refinement.h"

#include <algorithm>
#include <cstddef>
#include <functional>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "freeform/core/bspline.h"
#include "freeform/core/status.h"

namespace freeform::internal {

std::vector<double> SingleSpanKnots(int p, double start, double end) {
  std::vector<double> knots(static_cast<size_t>(p) + 1, start);
  knots.insert(knots.end(), static_cast<size_t>(p) + 1, end);
  return knots;
}

std::vector<double> SplitFailingSpans(int p, absl::Span<const double> knots,
                                      absl::Span<const double> t,
                                      absl::Span<const double> errors,
                                      double tolerance, size_t capacity) {
  const int n = static_cast<int>(knots.size()) - p - 2;
  std::vector<std::pair<double, double>> splits;  // (error, knot)
  int span = p;
  for (size_t a = 0; a < t.size();) {
    span = FindSpanFrom(span, n, p, t[a], knots);
    size_t b = a + 1;
    double worst = errors[a];
    while (b < t.size() && FindSpanFrom(span, n, p, t[b], knots) == span) {
      worst = std::max(worst, errors[b]);
      ++b;
    }
    const size_t count = b - a;
    if (worst > tolerance && count >= 2 * kMinSpanParameters) {
      const double lo = t[a + count / 2 - 1], hi = t[a + count / 2];
      const double knot = lo + 0.5 * (hi - lo);
      if (lo < knot && knot < hi) splits.emplace_back(worst, knot);
    }
    a = b;
  }
  if (splits.size() > capacity) {
    std::nth_element(splits.begin(),
                     splits.begin() + static_cast<ptrdiff_t>(capacity),
                     splits.end(), std::greater<>());
    splits.resize(capacity);
  }
  std::vector<double> inserted;
  inserted.reserve(splits.size());
  for (const auto& [error, knot] : splits) inserted.push_back(knot);
  std::sort(inserted.begin(), inserted.end());
  return inserted;
}

bool SpansHoldData(int p, absl::Span<const double> knots,
                   absl::Span<const double> t) {
  const int n = static_cast<int>(knots.size()) - p - 2;
  std::vector<size_t> held(static_cast<size_t>(n - p) + 1, 0);
  int span = p;
  for (size_t k = 0; k < t.size(); ++k) {
    span = FindSpanFrom(span, n, p, t[k], knots);
    const bool interior = k > 0 && k + 1 < t.size();
    if (interior && knots[static_cast<size_t>(span)] == t[k]) return false;
    ++held[static_cast<size_t>(span - p)];
  }
  for (int s = p; s <= n; ++s) {
    const size_t i = static_cast<size_t>(s);
    if (knots[i] < knots[i + 1] &&
        held[static_cast<size_t>(s - p)] < kMinSpanParameters) {
      return false;
    }
  }
  return true;
}

std::vector<double> WithKnots(absl::Span<const double> knots,
                              absl::Span<const double> inserted) {
  std::vector<double> merged;
  merged.reserve(knots.size() + inserted.size());
  std::merge(knots.begin(), knots.end(), inserted.begin(), inserted.end(),
             std::back_inserter(merged));
  return merged;
}

absl::Status ToleranceNotMet(double achieved, double tolerance,
                             bool cap_reached, absl::string_view cap_field,
                             int cap) {
  const std::string reached =
      absl::StrCat("the fit reached a max residual of ", achieved,
                   " > tolerance ", tolerance);
  if (cap_reached) {
    return ExhaustedFieldError(
        "tolerance", absl::StrCat(reached, " at the cap ", cap_field, " = ",
                                  cap, " control points"));
  }
  return ExhaustedFieldError(
      "tolerance",
      absl::StrCat(reached,
                   ", and every knot span above the tolerance holds fewer "
                   "than ",
                   2 * kMinSpanParameters,
                   " data points (too few data to refine further; interpolate "
                   "them instead)"));
}

}  // namespace freeform::internal
